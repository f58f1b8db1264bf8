// Cell range codes: outward rounding in double precision, then one float step further out, so no
// rounding in the decode can pull a bound inside the true range.
#include "core/volume/cell_range_codes.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace kdswap {
namespace {

constexpr int kLevels = 255;  //!< levels 0 .. 255
constexpr std::uint8_t kEmptyLow = 1, kEmptyHigh = 0;  //!< low > high: no voxel in the cell

}  // namespace

CellRangeCodes::CellRangeCodes(const std::vector<glm::vec2>& ranges) {
  float lo = std::numeric_limits<float>::max(), hi = std::numeric_limits<float>::lowest();
  for (const glm::vec2& r : ranges)
    if (r.x <= r.y) lo = std::min(lo, r.x), hi = std::max(hi, r.y);
  lo_ = lo, hi_ = hi;
  codes_.resize(2 * ranges.size());
  const double span = double(hi) - double(lo);
  const bool graded = span > 0.0 && std::isfinite(span);  // else every cell takes the whole range
  for (std::size_t i = 0; i < ranges.size(); ++i) {
    const glm::vec2& r = ranges[i];
    if (!(r.x <= r.y)) {
      codes_[2 * i] = kEmptyLow, codes_[2 * i + 1] = kEmptyHigh;
      continue;
    }
    const double low = graded ? std::floor((double(r.x) - lo) / span * kLevels) : 0.0;
    const double high = graded ? std::ceil((double(r.y) - lo) / span * kLevels) : (span > 0.0 ? kLevels : 0.0);
    codes_[2 * i] = std::uint8_t(std::clamp(low, 0.0, double(kLevels)));
    codes_[2 * i + 1] = std::uint8_t(std::clamp(high, 0.0, double(kLevels)));
  }
}

glm::vec2 CellRangeCodes::range(std::size_t i) const {
  const int low = codes_[2 * i], high = codes_[2 * i + 1];
  if (low > high) return glm::vec2(std::numeric_limits<float>::max(), std::numeric_limits<float>::lowest());
  const double span = double(hi_) - double(lo_);
  const float a = float(double(lo_) + span * low / kLevels), b = float(double(lo_) + span * high / kLevels);
  // The brick's own bounds are exact; in between, step one float outwards past any rounding.
  const float min = low == 0 ? lo_ : std::max(lo_, std::nextafter(a, std::numeric_limits<float>::lowest()));
  const float max = high == kLevels ? hi_ : std::min(hi_, std::nextafter(b, std::numeric_limits<float>::max()));
  return glm::vec2(min, max);
}

}  // namespace kdswap
