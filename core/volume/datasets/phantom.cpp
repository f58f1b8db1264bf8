// 3D Shepp-Logan phantom: ten ellipsoids, intensities added where they overlap. Each edge is a
// smooth step three voxels wide, measured as a distance from the surface, so that trilinear
// sampling shows neither a staircase nor contour rings: the skull is a shell only two or three
// voxels thick, and with a linear ramp 1.5 voxels wide its sampled peak (hence its opacity and
// shading) depended on where the voxel grid cut it, which drew rings around the poles of the head.
// Ellipsoid table: Kak & Slaney, "Principles of Computerized Tomographic Imaging", 3D extension,
// with the higher-contrast "modified" intensities (Toft) commonly used for visualisation.
#include "core/volume/datasets/phantom.h"

#include <algorithm>
#include <cmath>

#include <glm/geometric.hpp>

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

//! Width of an edge in voxels (of each axis's own voxels).
constexpr float kEdgeVoxels = 3.0f;

//! Value at p in unit coordinates ([-1, 1] per axis); `voxel` is one voxel's size there per axis.
float phantomValue(const glm::vec3& p, const glm::vec3& voxel) {
  const float halfEdge = 0.5f * kEdgeVoxels;
  const float largestVoxel = std::max({voxel.x, voxel.y, voxel.z});
  float value = 0.0f;
  for (const Ellipsoid& e : kEllipsoids) {
    const glm::vec3 d = p - e.centre;
    const float longest = std::max({e.semiAxes.x, e.semiAxes.y, e.semiAxes.z});
    const float shortest = std::min({e.semiAxes.x, e.semiAxes.y, e.semiAxes.z});
    // Beyond this the distance estimate below is at least halfEdge voxels: the step is 0 there.
    // (r >= |d| / longest and r / |grad r| >= shortest give estimate >= (|d| - longest) * shortest / longest.)
    const float reach = longest + halfEdge * largestVoxel * longest / shortest;
    if (glm::dot(d, d) >= reach * reach) continue;
    const float c = std::cos(e.rotationDeg * 3.14159265f / 180.0f), s = std::sin(e.rotationDeg * 3.14159265f / 180.0f);
    const glm::vec3 q(c * d.x + s * d.y, -s * d.x + c * d.y, d.z);  // in the ellipsoid's axes
    const glm::vec3 n = q / (e.semiAxes * e.semiAxes);
    const float r = std::sqrt(glm::dot(q, n));  // 1 on the surface
    // Signed distance from the surface in voxels, to first order: (r - 1) / |grad r|, the gradient
    // (n / r, turned back to the volume's axes) measured per voxel of each axis.
    const glm::vec3 gradient = glm::vec3(c * n.x - s * n.y, s * n.x + c * n.y, n.z) * voxel;
    const float length = glm::length(gradient);
    const float distance = length > 0.0f ? (r - 1.0f) * r / length : -halfEdge;  // the centre is inside
    // 1 inside, 0 outside, a smoothstep (continuous slope) across the edge.
    const float t = std::clamp(0.5f - 0.5f * distance / halfEdge, 0.0f, 1.0f);
    value += e.intensity * t * t * (3.0f - 2.0f * t);
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
  // unitCoordinate's step per axis (a one-voxel axis has none: any width will do there).
  const glm::vec3 voxel(dims.x > 1 ? 2.0f / float(dims.x - 1) : 2.0f, dims.y > 1 ? 2.0f / float(dims.y - 1) : 2.0f,
                        dims.z > 1 ? 2.0f / float(dims.z - 1) : 2.0f);
  return std::make_unique<ProceduralSource>(info, [dims, voxel](const VoxelBox& box, float* out) {
    const glm::ivec3 s = box.size();
    for (int z = 0; z < s.z; ++z)
      for (int y = 0; y < s.y; ++y)
        for (int x = 0; x < s.x; ++x) {
          const glm::vec3 p(unitCoordinate(box.lo.x + x, dims.x), unitCoordinate(box.lo.y + y, dims.y),
                            unitCoordinate(box.lo.z + z, dims.z));
          out[(std::size_t(z) * s.y + y) * s.x + x] = phantomValue(p, voxel);
        }
  });
}

}  // namespace kdswap
