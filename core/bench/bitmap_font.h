// A tiny built-in 5x7 bitmap font (digits, upper-case letters, a few signs) for chart labels:
// no text-rendering library is available, and charts need only short labels.
#pragma once

#include <string>

#include "core/image/image.h"

namespace kdswap {

inline constexpr int kGlyphWidth = 5, kGlyphHeight = 7, kGlyphAdvance = 6;

//! Draws `text` with its top-left corner at (x, y), each font pixel `scale` image pixels wide.
//! Lower-case letters are drawn as upper case; characters without a glyph leave a blank cell.
//! Pixels outside the image are skipped.
void drawText(Image& image, int x, int y, const std::string& text, const Rgba& colour, int scale = 1);

//! Width in image pixels of `text` drawn at `scale`.
int textWidth(const std::string& text, int scale = 1);

}  // namespace kdswap
