// TransferFunction: piecewise-linear colour and opacity maps over the normalised scalar [0, 1]
// (Levoy 1988). Opacity is defined for a reference step of one voxel; TransferTable corrects it
// for the actual step: alpha = 1 - (1 - alpha_tf)^(step / 1 voxel).
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>
#include <glm/vec4.hpp>
#include <nlohmann/json_fwd.hpp>

namespace kdswap {

struct ColorStop {
  float x = 0;           //!< normalised scalar in [0, 1]
  glm::vec3 rgb{0.0f};   //!< linear colour in [0, 1]
};

struct OpacityPoint {
  float x = 0;      //!< normalised scalar in [0, 1]
  float alpha = 0;  //!< opacity per voxel of path length, in [0, 1]
};

class TransferFunction {
 public:
  TransferFunction() = default;
  TransferFunction(std::vector<ColorStop> colors, std::vector<OpacityPoint> opacity, std::string name = "");

  //! Colour (rgb) and per-voxel opacity (a) at normalised scalar s; clamped outside [0, 1].
  glm::vec4 evaluate(float s) const;

  const std::vector<ColorStop>& colors() const { return colors_; }
  const std::vector<OpacityPoint>& opacity() const { return opacity_; }
  const std::string& name() const { return name_; }
  void setColors(std::vector<ColorStop> colors);
  void setOpacity(std::vector<OpacityPoint> opacity);

  //! kdswap JSON: {"name": ..., "colors": [[x, r, g, b], ...], "opacity": [[x, a], ...]}.
  nlohmann::json toJson() const;
  //! Accepts kdswap JSON, or a ParaView colour-map export ("RGBPoints", optional "Points");
  //! `where` names the source in errors. Throws kdswap::Error.
  static TransferFunction fromJson(const nlohmann::json& j, const std::string& where);
  //! Grey ramp: opacity 0 up to `start`, rising linearly to `peak` at 1 (issue 6's VTK comparison).
  static TransferFunction ramp(float start, float peak);

 private:
  void validate(const std::string& where) const;
  std::vector<ColorStop> colors_;
  std::vector<OpacityPoint> opacity_;
  std::string name_;
};

//! (scale, bias) mapping scalars of `valueRange` to [0, 1]: normalised = value * scale + bias
//! (0 and 0 for an empty range). Everything that looks values up in a TransferTable uses this one.
inline glm::vec2 normalisingScaleBias(glm::vec2 valueRange) {
  const float span = valueRange.y - valueRange.x;
  return span > 0.0f ? glm::vec2(1.0f / span, -valueRange.x / span) : glm::vec2(0.0f);
}

//! A TransferFunction baked for one sampling step: a lookup table of colour and step-corrected
//! opacity, interpolated linearly. The ray caster reads only this.
class TransferTable {
 public:
  static constexpr int kSize = 1024;
  TransferTable() = default;
  TransferTable(const TransferFunction& tf, float stepVoxels);

  glm::vec4 lookup(float s) const {
    float f = s * float(kSize - 1);
    f = !(f >= 0.0f) ? 0.0f : (f > float(kSize - 1) ? float(kSize - 1) : f);  // NaN maps to entry 0
    const int i = int(f);
    const float t = f - float(i);  // 0 at the last entry, whose copy follows it
    return entries_[i] + t * (entries_[i + 1] - entries_[i]);
  }
  //! The entries lookup() interpolates (for the SIMD shader, which must match lookup exactly):
  //! kSize + 1 of them, the last a copy of entry kSize - 1, so entry i + 1 always exists and
  //! entries i and i + 1 are one contiguous 32-byte run.
  const glm::vec4* entries() const { return entries_.data(); }
  //! Largest corrected opacity over normalised scalars in [s0, s1].
  float maxAlpha(float s0, float s1) const;
  //! Smallest corrected opacity lookup(s) can give for s in [s0, s1] (conservative by one entry on
  //! each side; 0 for NaN). Constant time: occlusion culling asks it for every macro cell.
  float minAlpha(float s0, float s1) const;
  //! True when some lookup(s) with s in [s0, s1] can have opacity > 0 (conservative by one entry
  //! on each side). Constant time: empty-space skipping asks it for every macro cell.
  bool anyVisible(float s0, float s1) const;
  //! Bit i: entry i has opacity > 0. Tables with equal masks give equal anyVisible answers (what
  //! empty-space maps are built from); at 128 bytes, the 64 bricks' caches compare it each frame
  //! in a few cache lines (the 4 KiB counts they compared before, cold after a frame's rendering,
  //! took ~3 us per brick, on one thread before the waves start).
  using VisibleMask = std::array<std::uint64_t, kSize / 64>;
  const VisibleMask& visibleMask() const { return visibleMask_; }

 private:
  std::vector<glm::vec4> entries_;
  VisibleMask visibleMask_{};
  std::vector<int> visibleBefore_;  //!< visibleBefore_[i]: entries before i with opacity > 0
  //! minAlphaRuns_[l][i]: smallest opacity of entries [i, i + 2^l) (a sparse table for range minima)
  std::vector<std::vector<float>> minAlphaRuns_;
};

}  // namespace kdswap
