// The data's value histogram, drawn under the transfer-function editor.
#pragma once

#include <vector>

#include "core/volume/volume_source.h"

namespace kdswap {

struct Histogram {
  //! log(1 + count) per bin, scaled so the largest bin is 1 (CT data is mostly air).
  std::vector<float> bins;
  //! Where the bins lie on the transfer function's axis (the value normalised over
  //! [minValue, maxValue]): the first bin's left edge and the last bin's right edge. Integer data
  //! is binned between half-integers, so these may lie half a value outside [0, 1].
  float x0 = 0.0f, x1 = 1.0f;
  //! Whole values per bin for integer-valued data (every bin holds the same number of values, so
  //! none is empty by rounding); 0 when the data is not integer-valued.
  int valuesPerBin = 0;
};

//! Counts of the scalar over [minValue, maxValue] in at most `bins` bins, read through
//! VolumeSource::read a few slices at a time (so a file source never loads the whole volume).
//! Integer-valued data with R + 1 values (R = max - min) gets one value per bin when R + 1 <= bins,
//! else k = ceil((R + 1) / bins) values per bin; other data gets `bins` equal bins over the range.
Histogram computeHistogram(const VolumeSource& source, int bins = 256);

}  // namespace kdswap
