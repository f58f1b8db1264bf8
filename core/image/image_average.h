// ImageAverage: the mean of several frames of one view, pixel by pixel. Pixels are premultiplied,
// so the mean is what the eye sees of the frames shown in quick turn; `kdswap render --passes`
// and the desktop app's refinement average frames whose sampling lattices differ
// (RenderSettings::phaseShift), which integrates the lattice's rings and grain away.
#pragma once

#include "core/image/image.h"
#include "core/image/rect.h"

namespace kdswap {

class ImageAverage {
 public:
  //! An empty average over the frame `frame` (every image added is read within it).
  explicit ImageAverage(const Rect& frame);

  //! Adds one frame; its pixels outside its rect() count as transparent.
  void add(const Image& image);
  int count() const { return count_; }
  const Rect& frame() const { return sum_.rect(); }
  //! The mean of the frames added so far (transparent before the first).
  Image mean() const;

 private:
  Image sum_;
  int count_ = 0;
};

}  // namespace kdswap
