// The data's value histogram, drawn under the transfer-function editor.
#pragma once

#include <vector>

#include "core/volume/volume_source.h"

namespace kdswap {

//! Counts of the normalised scalar over [minValue, maxValue] in `bins` bins, read through
//! VolumeSource::read a few slices at a time (so a file source never loads the whole volume).
//! Returned as log(1 + count) scaled so the largest bin is 1: CT data is mostly air.
std::vector<float> computeHistogram(const VolumeSource& source, int bins = 256);

}  // namespace kdswap
