// Blue-noise ray phases: a 64 x 64 tile, repeated over the image, whose cells hold the values
// (rank + 1/2) / 4096 for ranks 0..4095 in the order of Ulichney's void-and-cluster method (1993).
// Each new rank goes to the emptiest spot of those placed so far, so neighbouring pixels take
// far-apart values and the tile has almost no low-frequency energy. Used as each ray's sampling
// phase, it turns the rings of a fixed lattice into grain that is finer than white noise's
// (white noise clumps, leaving blotches a few pixels wide) and has no regular pattern (a
// low-discrepancy sequence such as R2 left hatching and moire on the default scene).
#pragma once

#include <array>

namespace kdswap {

class BlueNoiseTile {
 public:
  static constexpr int kSide = 64;  //!< a power of two: pixels wrap with a mask
  static constexpr int kCells = kSide * kSide;

  //! The tile, built on first use (deterministic: the same on every node, run and machine, as it
  //! uses IEEE basic operations only).
  static const BlueNoiseTile& instance();

  //! The value of pixel (px, py) of an image tiled with this tile, in (0, 1).
  float at(int px, int py) const { return values_[std::size_t((py & (kSide - 1)) * kSide + (px & (kSide - 1)))]; }
  //! The values, row by row (x fastest), for vector loads.
  const float* data() const { return values_.data(); }

 private:
  BlueNoiseTile();
  std::array<float, kCells> values_{};
};

}  // namespace kdswap
