// JSON library errors as one printable line.
#include "core/util/json_error.h"

#include <cstdio>

namespace kdswap {

std::string jsonErrorText(const nlohmann::json::exception& e) {
  std::string what = e.what();
  if (what.rfind("[json.exception.", 0) == 0) {
    const std::size_t end = what.find("] ");
    if (end != std::string::npos) what.erase(0, end + 2);
  }
  std::string text;
  for (const unsigned char c : what) {
    if (c >= 0x20 && c < 0x7f) {
      text += char(c);
    } else {
      char escaped[8];
      std::snprintf(escaped, sizeof escaped, "\\x%02X", c);
      text += escaped;
    }
  }
  return text;
}

}  // namespace kdswap
