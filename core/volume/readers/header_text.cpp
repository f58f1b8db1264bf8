// Text helpers for header readers.
#include "core/volume/readers/header_text.h"

#include <cctype>
#include <cerrno>
#include <charconv>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>

#include "core/util/error.h"
#include "core/util/text_items.h"

namespace kdswap {

std::string readFilePrefix(const std::string& path, std::size_t maxBytes) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw Error(path + ": cannot open: " + std::strerror(errno));
  std::string text(maxBytes, '\0');
  in.read(text.data(), std::streamsize(maxBytes));
  text.resize(std::size_t(in.gcount()));
  return text;
}

bool nextLine(std::string_view text, std::size_t& pos, std::string_view& line) {
  const std::size_t nl = text.find('\n', pos);
  if (nl == std::string_view::npos) return false;
  line = text.substr(pos, nl - pos);
  if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
  pos = nl + 1;
  return true;
}

std::string_view trim(std::string_view s) {
  while (!s.empty() && std::isspace(static_cast<unsigned char>(s.front()))) s.remove_prefix(1);
  while (!s.empty() && std::isspace(static_cast<unsigned char>(s.back()))) s.remove_suffix(1);
  return s;
}

std::string lowercase(std::string_view s) {
  std::string out(s);
  for (char& c : out) c = char(std::tolower(static_cast<unsigned char>(c)));
  return out;
}

std::vector<std::string_view> splitWords(std::string_view s) {
  std::vector<std::string_view> words;
  std::size_t i = 0;
  while (i < s.size()) {
    while (i < s.size() && std::isspace(static_cast<unsigned char>(s[i]))) ++i;
    const std::size_t start = i;
    while (i < s.size() && !std::isspace(static_cast<unsigned char>(s[i]))) ++i;
    if (i > start) words.push_back(s.substr(start, i - start));
  }
  return words;
}

std::optional<std::int64_t> parseInteger(std::string_view s) { return parseWholeNumber(trim(s)); }

std::optional<double> parseNumber(std::string_view s) {
  s = trim(s);
  if (!s.empty() && s.front() == '+') s.remove_prefix(1);
  double v = 0;
  const auto [end, ec] = std::from_chars(s.data(), s.data() + s.size(), v);
  if (s.empty() || ec != std::errc() || end != s.data() + s.size()) return std::nullopt;
  return v;
}

std::optional<std::vector<std::int64_t>> parseSizes(std::string_view s, std::size_t count) {
  const auto words = splitWords(s);
  if (words.size() != count) return std::nullopt;
  std::vector<std::int64_t> sizes;
  for (std::string_view w : words) {
    const auto v = parseInteger(w);
    if (!v) return std::nullopt;
    sizes.push_back(*v);
  }
  return sizes;
}

std::string printable(std::string_view s, std::size_t maxChars) {
  std::string out;
  for (char c : s.substr(0, maxChars)) {
    const auto byte = static_cast<unsigned char>(c);
    if (byte >= 32 && byte < 127) {
      out += c;
    } else {
      char hex[5];
      std::snprintf(hex, sizeof hex, "\\x%02X", byte);
      out += hex;
    }
  }
  return s.size() > maxChars ? out + "..." : out;
}

std::string quote(std::string_view s, std::size_t maxChars) {
  std::string out = "\"";  // appended, not "\"" + ...: GCC 12 warns of a false -Wrestrict there
  out += printable(s, maxChars);
  out += '"';
  return out;
}

std::string siblingPath(const std::string& headerPath, const std::string& name) {
  const std::filesystem::path p(name);
  if (p.is_absolute()) return name;
  return (std::filesystem::path(headerPath).parent_path() / p).string();
}

}  // namespace kdswap
