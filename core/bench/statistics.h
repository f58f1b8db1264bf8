// Robust summaries of repeated timings: the bench reports the median of K frames, which one
// slow frame (a page fault, another process on the shared machine) cannot move.
#pragma once

#include <vector>

namespace kdswap {

//! Median of `values` (mean of the two middle values for an even count); 0 for none.
double median(std::vector<double> values);

}  // namespace kdswap
