// Text from files and errors made safe to print or show: bytes that are not printable UTF-8 (a
// binary file's header quoted in a reader's message) become \xNN escapes.
#pragma once

#include <string>
#include <string_view>

namespace kdswap {

//! `text` with control characters (newline and tab kept), C1 controls, invisible format
//! characters (bidi overrides, zero-width marks) and bytes that are not part of well-formed UTF-8
//! replaced by \xNN per byte; other UTF-8 (accented file names) is kept.
std::string printableText(std::string_view text);

}  // namespace kdswap
