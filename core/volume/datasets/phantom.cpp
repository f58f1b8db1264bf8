// 3D Shepp-Logan phantom: ten ellipsoids, intensities added where they overlap. Edges are
// smoothed over about one voxel so that trilinear sampling shows no staircase.
// Ellipsoid table: Kak & Slaney, "Principles of Computerized Tomographic Imaging", 3D extension,
// with the higher-contrast "modified" intensities (Toft) commonly used for visualisation.
#include "core/volume/datasets/phantom.h"

#include <algorithm>
#include <cmath>

#include "core/volume/datasets/procedural_source.h"

namespace kdswap {
namespace {

struct Ellipsoid {
  float intensity;
  glm::vec3 semiAxes;
  glm::vec3 centre;
  float rotationDeg;  // about the z (head) axis
};

// x: left-right, y: front-back (face toward -y), z: foot-head.
constexpr Ellipsoid kEllipsoids[] = {
    {1.0f, {0.6900f, 0.920f, 0.810f}, {0.0f, 0.0f, 0.0f}, 0.0f},          // skull
    {-0.8f, {0.6624f, 0.874f, 0.780f}, {0.0f, -0.0184f, 0.0f}, 0.0f},     // brain
    {-0.2f, {0.1100f, 0.310f, 0.220f}, {0.22f, 0.0f, 0.0f}, -18.0f},      // right ventricle
    {-0.2f, {0.1600f, 0.410f, 0.280f}, {-0.22f, 0.0f, 0.0f}, 18.0f},      // left ventricle
    {0.1f, {0.2100f, 0.250f, 0.410f}, {0.0f, 0.35f, -0.15f}, 0.0f},
    {0.1f, {0.0460f, 0.046f, 0.050f}, {0.0f, 0.1f, 0.25f}, 0.0f},
    {0.1f, {0.0460f, 0.046f, 0.050f}, {0.0f, -0.1f, 0.25f}, 0.0f},
    {0.1f, {0.0460f, 0.023f, 0.050f}, {-0.08f, -0.605f, 0.0f}, 0.0f},
    {0.1f, {0.0230f, 0.023f, 0.020f}, {0.0f, -0.606f, 0.0f}, 0.0f},
    {0.1f, {0.0230f, 0.046f, 0.020f}, {0.06f, -0.605f, 0.0f}, 0.0f},
};

float phantomValue(const glm::vec3& p, float edge) {
  float value = 0.0f;
  for (const Ellipsoid& e : kEllipsoids) {
    const glm::vec3 d = p - e.centre;
    // The soft indicator below is 0 for r >= 1 + width / 2, and r >= |d| / (largest semi-axis).
    const float width = edge / std::min({e.semiAxes.x, e.semiAxes.y, e.semiAxes.z});
    const float reach = std::max({e.semiAxes.x, e.semiAxes.y, e.semiAxes.z}) * (1.0f + 0.5f * width) * 1.001f;
    if (d.x * d.x + d.y * d.y + d.z * d.z > reach * reach) continue;  // outside its reach: contributes 0
    const float c = std::cos(e.rotationDeg * 3.14159265f / 180.0f), s = std::sin(e.rotationDeg * 3.14159265f / 180.0f);
    const glm::vec3 q(c * d.x + s * d.y, -s * d.x + c * d.y, d.z);
    const float r = std::sqrt((q.x * q.x) / (e.semiAxes.x * e.semiAxes.x) + (q.y * q.y) / (e.semiAxes.y * e.semiAxes.y) +
                              (q.z * q.z) / (e.semiAxes.z * e.semiAxes.z));
    // Soft indicator: 1 inside, 0 outside, linear across about one voxel at the surface.
    const float inside = std::clamp((1.0f - r) / width + 0.5f, 0.0f, 1.0f);
    value += e.intensity * inside;
  }
  return std::clamp(value, 0.0f, 1.0f);
}

}  // namespace

std::unique_ptr<VolumeSource> makePhantom(const glm::ivec3& dims) {
  VolumeInfo info;
  info.dims = dims;
  info.type = "float32";
  info.minValue = 0.0f;
  info.maxValue = 1.0f;
  info.name = "phantom";
  info.preset = "phantom";
  const float edge = 3.0f / float(std::max({dims.x, dims.y, dims.z}) - 1);  // 1.5 voxels: no moire on the thin skull
  return std::make_unique<ProceduralSource>(info, [dims, edge](const VoxelBox& box, float* out) {
    const glm::ivec3 s = box.size();
    for (int z = 0; z < s.z; ++z)
      for (int y = 0; y < s.y; ++y)
        for (int x = 0; x < s.x; ++x) {
          const glm::vec3 p(unitCoordinate(box.lo.x + x, dims.x), unitCoordinate(box.lo.y + y, dims.y),
                            unitCoordinate(box.lo.z + z, dims.z));
          out[(std::size_t(z) * s.y + y) * s.x + x] = phantomValue(p, edge);
        }
  });
}

}  // namespace kdswap
