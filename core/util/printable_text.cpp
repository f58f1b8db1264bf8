// \xNN escapes for what a terminal or ImGui cannot show.
#include "core/util/printable_text.h"

#include <cstdint>
#include <cstdio>

namespace kdswap {
namespace {

// Length of the well-formed UTF-8 sequence starting at text[i] (2..4), or 0.
std::size_t utf8Length(std::string_view text, std::size_t i) {
  const auto byte = [&](std::size_t k) { return static_cast<unsigned char>(text[k]); };
  const unsigned char b = byte(i);
  std::size_t n;
  std::uint32_t cp;
  if (b >= 0xC2 && b <= 0xDF) n = 2, cp = b & 0x1Fu;
  else if (b >= 0xE0 && b <= 0xEF) n = 3, cp = b & 0x0Fu;
  else if (b >= 0xF0 && b <= 0xF4) n = 4, cp = b & 0x07u;
  else return 0;
  if (i + n > text.size()) return 0;
  for (std::size_t k = 1; k < n; ++k) {
    if ((byte(i + k) & 0xC0) != 0x80) return 0;
    cp = (cp << 6) | (byte(i + k) & 0x3Fu);
  }
  const bool overlong = (n == 3 && cp < 0x800) || (n == 4 && cp < 0x10000);
  // Also refused: C1 controls, and the invisible format characters that reorder or hide text
  // (zero-width and direction marks, bidi embeddings and isolates, line separators, BOM).
  const bool format = (cp >= 0x200B && cp <= 0x200F) || (cp >= 0x2028 && cp <= 0x202E) ||
                      (cp >= 0x2060 && cp <= 0x2069) || cp == 0xFEFF;
  const bool invalid = cp > 0x10FFFF || (cp >= 0xD800 && cp <= 0xDFFF) || (cp >= 0x80 && cp <= 0x9F) || format;
  return overlong || invalid ? 0 : n;
}

}  // namespace

std::string printableText(std::string_view text, LineBreaks breaks) {
  const bool keepBreaks = breaks == LineBreaks::Keep;
  std::string out;
  out.reserve(text.size());
  for (std::size_t i = 0; i < text.size();) {
    const unsigned char b = static_cast<unsigned char>(text[i]);
    if ((b >= 0x20 && b < 0x7F) || (keepBreaks && (b == '\n' || b == '\t'))) {
      out += char(b);
      ++i;
      continue;
    }
    if (const std::size_t n = b >= 0x80 ? utf8Length(text, i) : 0) {
      out.append(text.substr(i, n));
      i += n;
      continue;
    }
    char escape[5];
    std::snprintf(escape, sizeof escape, "\\x%02X", unsigned(b));
    out += escape;
    ++i;
  }
  return out;
}

}  // namespace kdswap
