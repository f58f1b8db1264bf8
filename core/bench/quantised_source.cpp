// Quantisation of a volume source to 8 or 16 bits.
#include "core/bench/quantised_source.h"

#include <cmath>

#include "core/util/error.h"

namespace kdswap {

QuantisedSource::QuantisedSource(std::unique_ptr<VolumeSource> inner, int bits)
    : inner_(std::move(inner)), info_(inner_->info()) {
  if (bits != 8 && bits != 16) throw Error("quantise " + std::to_string(bits) + ": expected 8 or 16 bits");
  levels_ = float((1 << bits) - 1);
  info_.type = bits == 8 ? "uint8" : "uint16";
  info_.name += bits == 8 ? " (quantised to uint8)" : " (quantised to uint16)";
}

void QuantisedSource::read(const VoxelBox& box, float* out) const {
  inner_->read(box, out);
  const float lo = info_.minValue, span = info_.maxValue - info_.minValue;
  if (!(span > 0.0f)) return;
  const std::int64_t n = box.count();
  for (std::int64_t i = 0; i < n; ++i) {
    const float k = std::round((out[i] - lo) / span * levels_);
    out[i] = lo + k * span / levels_;
  }
}

}  // namespace kdswap
