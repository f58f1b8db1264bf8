// JSON library errors as one printable line.
#include "core/util/json_error.h"

#include "core/util/printable_text.h"

namespace kdswap {

std::string jsonErrorText(const nlohmann::json::exception& e) {
  std::string what = e.what();
  if (what.rfind("[json.exception.", 0) == 0) {  // the library's tag means nothing to a user
    const std::size_t end = what.find("] ");
    if (end != std::string::npos) what.erase(0, end + 2);
  }
  return oneLine(what);  // a bad byte it quotes becomes \xNN
}

}  // namespace kdswap
