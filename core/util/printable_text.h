// Text from files and errors made safe to print or show: bytes that are not printable UTF-8 (a
// binary file's header quoted in a reader's message) become \xNN escapes.
#pragma once

#include <string>
#include <string_view>

namespace kdswap {

//! Whether newlines and tabs stay (text shown in a window) or are escaped too (a one-line error on
//! a terminal: a file name with a newline in it must not start a second line).
enum class LineBreaks { Keep, Escape };

//! `text` with control characters (newline and tab kept unless `breaks` is Escape), C1 controls,
//! invisible format characters (bidi overrides, zero-width marks) and bytes that are not part of
//! well-formed UTF-8 replaced by \xNN per byte; other UTF-8 (accented file names) is kept.
std::string printableText(std::string_view text, LineBreaks breaks = LineBreaks::Keep);

//! A message for a one-line error on a terminal.
inline std::string oneLine(std::string_view text) { return printableText(text, LineBreaks::Escape); }

}  // namespace kdswap
