// Scalar ray march (the reference) and the choice of march.
#include "core/render/ray_march.h"

#include "core/util/cpu_features.h"

namespace kdswap {

namespace {

template <bool compact>
Rgba marchOne(const MarchContext& m, const RaySegment& s, std::uint64_t& samples) {
  FrontToBack result;
  const float stop = s.stopFor(m);
  ShadedSample group[FrontToBack::kGroup];  // visible samples, composited eight at a time
  int waiting = 0, taken = 0;
  std::size_t lastJumpedCell = std::size_t(-1);
  for (long k = s.first; k <= s.last; ++k) {
    const glm::vec3 p = s.point(k);
    const glm::ivec3 floor(int(p.x), int(p.y), int(p.z));  // p >= 0: truncation is floor
    const glm::ivec3 c = (floor >> m.cellShift) - m.cellLo;
    const std::size_t cell = m.cellIndex(c);
    const int code = m.cellCodes[cell];
    if (const int reach = code & EmptySpaceMap::kReachMask) {
      if (cell == lastJumpedCell) continue;  // landed just short of the exit: step on
      lastJumpedCell = cell;
      k = std::max(k, s.resumeAfterEmpty(m, c, reach));
      continue;
    }
    if (code & EmptySpaceMap::kUniformBit)  // the cell's record: what interpolation gives, to rounding
      group[waiting++] = shadeInterpolated(m.shading, s.toLight, uniformRecord(m.voxels, floor));
    else
      group[waiting++] = compact ? shadeCompactSample(m.shading, s.toLight, m.voxels, p, floor)
                                 : shadeSample(m.shading, s.toLight, m.voxels, p, floor);
    if (waiting < FrontToBack::kGroup) continue;
    const bool done = result.addEight(group, waiting, stop, taken);
    samples += std::uint64_t(taken);
    waiting = 0;
    if (done) return result.rgba();
  }
  if (waiting > 0) {
    result.addEight(group, waiting, stop, taken);
    samples += std::uint64_t(taken);
  }
  return result.rgba();
}

}  // namespace

void marchScalar(const MarchContext& m, const RaySegment* segments, std::size_t count, Rgba* colours,
                 std::uint64_t& samples) {
  if (m.voxels.compact)
    for (std::size_t i = 0; i < count; ++i) colours[i] = marchOne<true>(m, segments[i], samples);
  else
    for (std::size_t i = 0; i < count; ++i) colours[i] = marchOne<false>(m, segments[i], samples);
}

MarchFunction chooseMarch(const MarchBuilds& builds, std::string_view request) {
  if (request == "scalar") return &marchScalar;
  // Widest first; a request for a narrower build rules out the wider ones.
  const bool narrower = request == "avx2" || request == "avx512vl";
  if (!narrower && builds.avx512 && (request == "avx512" || builds.wideAtFullSpeed)) return builds.avx512;
  if (request != "avx2" && builds.avx512vl) return builds.avx512vl;
  return builds.avx2 ? builds.avx2 : &marchScalar;
}

MarchFunction selectedMarchFunction() {
  static const MarchFunction chosen = chooseMarch(
      MarchBuilds{avx2MarchFunction(), avx512vlMarchFunction(), avx512MarchFunction(), cpuRunsWideVectorsAtFullSpeed()},
      simdRequest());
  return chosen;
}

const char* marchName(MarchFunction march) {
  if (march == &marchScalar) return "scalar";
  if (march != nullptr && march == avx512MarchFunction()) return "avx512";
  if (march != nullptr && march == avx512vlMarchFunction()) return "avx2+avx512vl";
  return "avx2";
}

}  // namespace kdswap
