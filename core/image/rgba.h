// Rgba: one premultiplied RGBA float pixel, the unit every image, view and message carries.
#pragma once

namespace kdswap {

struct Rgba {
  float r = 0, g = 0, b = 0, a = 0;
};

}  // namespace kdswap
