// 5x7 bitmap font: each glyph is 7 rows of 5 columns, '#' marks a lit pixel.
#include "core/bench/bitmap_font.h"

#include <cctype>
#include <map>

namespace kdswap {
namespace {

using Glyph = const char*[kGlyphHeight];

const std::map<char, const char* const*>& glyphs() {
  static Glyph g0 = {".###.", "#...#", "#..##", "#.#.#", "##..#", "#...#", ".###."};
  static Glyph g1 = {"..#..", ".##..", "..#..", "..#..", "..#..", "..#..", ".###."};
  static Glyph g2 = {".###.", "#...#", "....#", "...#.", "..#..", ".#...", "#####"};
  static Glyph g3 = {"#####", "...#.", "..#..", "...#.", "....#", "#...#", ".###."};
  static Glyph g4 = {"...#.", "..##.", ".#.#.", "#..#.", "#####", "...#.", "...#."};
  static Glyph g5 = {"#####", "#....", "####.", "....#", "....#", "#...#", ".###."};
  static Glyph g6 = {"..##.", ".#...", "#....", "####.", "#...#", "#...#", ".###."};
  static Glyph g7 = {"#####", "....#", "...#.", "..#..", ".#...", ".#...", ".#..."};
  static Glyph g8 = {".###.", "#...#", "#...#", ".###.", "#...#", "#...#", ".###."};
  static Glyph g9 = {".###.", "#...#", "#...#", ".####", "....#", "...#.", ".##.."};
  static Glyph A = {".###.", "#...#", "#...#", "#####", "#...#", "#...#", "#...#"};
  static Glyph B = {"####.", "#...#", "#...#", "####.", "#...#", "#...#", "####."};
  static Glyph C = {".###.", "#...#", "#....", "#....", "#....", "#...#", ".###."};
  static Glyph D = {"###..", "#..#.", "#...#", "#...#", "#...#", "#..#.", "###.."};
  static Glyph E = {"#####", "#....", "#....", "####.", "#....", "#....", "#####"};
  static Glyph F = {"#####", "#....", "#....", "####.", "#....", "#....", "#...."};
  static Glyph G = {".###.", "#...#", "#....", "#.###", "#...#", "#...#", ".####"};
  static Glyph H = {"#...#", "#...#", "#...#", "#####", "#...#", "#...#", "#...#"};
  static Glyph I = {".###.", "..#..", "..#..", "..#..", "..#..", "..#..", ".###."};
  static Glyph J = {"..###", "...#.", "...#.", "...#.", "...#.", "#..#.", ".##.."};
  static Glyph K = {"#...#", "#..#.", "#.#..", "##...", "#.#..", "#..#.", "#...#"};
  static Glyph L = {"#....", "#....", "#....", "#....", "#....", "#....", "#####"};
  static Glyph M = {"#...#", "##.##", "#.#.#", "#.#.#", "#...#", "#...#", "#...#"};
  static Glyph N = {"#...#", "#...#", "##..#", "#.#.#", "#..##", "#...#", "#...#"};
  static Glyph O = {".###.", "#...#", "#...#", "#...#", "#...#", "#...#", ".###."};
  static Glyph P = {"####.", "#...#", "#...#", "####.", "#....", "#....", "#...."};
  static Glyph Q = {".###.", "#...#", "#...#", "#...#", "#.#.#", "#..#.", ".##.#"};
  static Glyph R = {"####.", "#...#", "#...#", "####.", "#.#..", "#..#.", "#...#"};
  static Glyph S = {".####", "#....", "#....", ".###.", "....#", "....#", "####."};
  static Glyph T = {"#####", "..#..", "..#..", "..#..", "..#..", "..#..", "..#.."};
  static Glyph U = {"#...#", "#...#", "#...#", "#...#", "#...#", "#...#", ".###."};
  static Glyph V = {"#...#", "#...#", "#...#", "#...#", "#...#", ".#.#.", "..#.."};
  static Glyph W = {"#...#", "#...#", "#...#", "#.#.#", "#.#.#", "#.#.#", ".#.#."};
  static Glyph X = {"#...#", "#...#", ".#.#.", "..#..", ".#.#.", "#...#", "#...#"};
  static Glyph Y = {"#...#", "#...#", ".#.#.", "..#..", "..#..", "..#..", "..#.."};
  static Glyph Z = {"#####", "....#", "...#.", "..#..", ".#...", "#....", "#####"};
  static Glyph dot = {".....", ".....", ".....", ".....", ".....", ".##..", ".##.."};
  static Glyph minus = {".....", ".....", ".....", "#####", ".....", ".....", "....."};
  static Glyph equals = {".....", ".....", "#####", ".....", "#####", ".....", "....."};
  static Glyph slash = {".....", "....#", "...#.", "..#..", ".#...", "#....", "....."};
  static Glyph colon = {".....", ".##..", ".##..", ".....", ".##..", ".##..", "....."};
  static Glyph lparen = {"...#.", "..#..", ".#...", ".#...", ".#...", "..#..", "...#."};
  static Glyph rparen = {".#...", "..#..", "...#.", "...#.", "...#.", "..#..", ".#..."};
  static const std::map<char, const char* const*> table = {
      {'0', g0}, {'1', g1}, {'2', g2}, {'3', g3}, {'4', g4}, {'5', g5}, {'6', g6}, {'7', g7}, {'8', g8},
      {'9', g9}, {'A', A},  {'B', B},  {'C', C},  {'D', D},  {'E', E},  {'F', F},  {'G', G},  {'H', H},
      {'I', I},  {'J', J},  {'K', K},  {'L', L},  {'M', M},  {'N', N},  {'O', O},  {'P', P},  {'Q', Q},
      {'R', R},  {'S', S},  {'T', T},  {'U', U},  {'V', V},  {'W', W},  {'X', X},  {'Y', Y},  {'Z', Z},
      {'.', dot}, {'-', minus}, {'=', equals}, {'/', slash}, {':', colon}, {'(', lparen}, {')', rparen}};
  return table;
}

}  // namespace

int textWidth(const std::string& text, int scale) {
  return text.empty() ? 0 : (int(text.size()) * kGlyphAdvance - 1) * scale;
}

void drawText(Image& image, int x, int y, const std::string& text, const Rgba& colour, int scale) {
  const Rect& r = image.rect();
  for (std::size_t i = 0; i < text.size(); ++i) {
    auto it = glyphs().find(char(std::toupper((unsigned char)text[i])));
    if (it == glyphs().end()) continue;
    const int gx = x + int(i) * kGlyphAdvance * scale;
    for (int row = 0; row < kGlyphHeight; ++row)
      for (int col = 0; col < kGlyphWidth; ++col) {
        if (it->second[row][col] != '#') continue;
        for (int sy = 0; sy < scale; ++sy)
          for (int sx = 0; sx < scale; ++sx) {
            const int px = gx + col * scale + sx, py = y + row * scale + sy;
            if (r.contains(px, py)) image.at(px, py) = colour;
          }
      }
  }
}

}  // namespace kdswap
