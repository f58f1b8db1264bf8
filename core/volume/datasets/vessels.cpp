// Synthetic angiogram. Three trunks enter from below and bifurcate seven times (child radii
// about 0.85 and 0.65 of the parent, near Murray's law r^3 = r1^3 + r2^3), each vessel a chain of
// slightly tortuous segments. A voxel takes the brightest vessel near it: full intensity within
// half the radius, then a Gaussian fall-off cut smoothly to exactly 0 at three widths.
// Coordinates are isotropic: the longest axis spans [-1, 1], shorter axes crop the tree.
#include "core/volume/datasets/vessels.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

#include <glm/geometric.hpp>
#include <oneapi/tbb/parallel_for.h>

#include "core/volume/datasets/procedural_source.h"

namespace kdswap {
namespace {

constexpr std::uint64_t kSeed = 0x5eed'a461'0c0d'e001ull;
constexpr int kMaxDepth = 7;
constexpr float kRootRadius = 0.055f;
constexpr int kTile = 16;  // voxels per side of the blocks segments are culled against

struct Segment {
  glm::vec3 a, b;
  float core, sigma, intensity;
  glm::vec3 lo, hi;  // bounding box of everything this segment touches
};

//! splitmix64: a fixed, portable random sequence (std distributions differ between libraries).
class Random {
 public:
  explicit Random(std::uint64_t seed) : state_(seed) {}
  float uniform() {  // [0, 1)
    std::uint64_t z = (state_ += 0x9e3779b97f4a7c15ull);
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
    return float((z ^ (z >> 31)) >> 40) / float(1 << 24);
  }
  float range(float lo, float hi) { return lo + (hi - lo) * uniform(); }
  glm::vec3 direction() {
    const float z = range(-1.0f, 1.0f), phi = range(0.0f, 6.2831853f), r = std::sqrt(1.0f - z * z);
    return {r * std::cos(phi), r * std::sin(phi), z};
  }

 private:
  std::uint64_t state_;
};

class VesselTree {
 public:
  VesselTree(const glm::ivec3& dims) : dims_(dims), step_(2.0f / float(std::max({dims.x, dims.y, dims.z}) - 1)) {
    Random random(kSeed);
    const glm::vec3 roots[] = {{-0.32f, 0.12f, -0.97f}, {0.32f, 0.12f, -0.97f}, {0.0f, 0.42f, -0.97f}};
    for (const glm::vec3& start : roots)
      grow(random, start, glm::normalize(glm::vec3(-0.3f * start.x, 0.0f, 1.0f)), kRootRadius, 0.55f, 0);
  }

  glm::vec3 position(int x, int y, int z) const {
    return (glm::vec3(x, y, z) - 0.5f * glm::vec3(dims_ - 1)) * step_;
  }

  //! Fills `out` for `box` (voxel indices), one tile of kTile^3 at a time in parallel.
  void generate(const VoxelBox& box, float* out) const {
    const glm::ivec3 s = box.size(), tiles = (s + kTile - 1) / kTile;
    tbb::parallel_for(0, tiles.x * tiles.y * tiles.z, [&](int t) {
      const glm::ivec3 tile(t % tiles.x, (t / tiles.x) % tiles.y, t / (tiles.x * tiles.y));
      const glm::ivec3 lo = box.lo + tile * kTile, hi = glm::min(lo + kTile, box.hi);
      const glm::vec3 plo = position(lo.x, lo.y, lo.z), phi = position(hi.x - 1, hi.y - 1, hi.z - 1);
      std::vector<const Segment*> near;
      for (const Segment& g : segments_)
        if (g.lo.x <= phi.x && g.hi.x >= plo.x && g.lo.y <= phi.y && g.hi.y >= plo.y && g.lo.z <= phi.z && g.hi.z >= plo.z)
          near.push_back(&g);
      for (int z = lo.z; z < hi.z; ++z)
        for (int y = lo.y; y < hi.y; ++y)
          for (int x = lo.x; x < hi.x; ++x)
            out[(std::size_t(z - box.lo.z) * s.y + (y - box.lo.y)) * s.x + (x - box.lo.x)] =
                near.empty() ? 0.0f : value(position(x, y, z), near);
    });
  }

  float valueAt(const glm::ivec3& v) const {
    std::vector<const Segment*> all;
    for (const Segment& g : segments_) all.push_back(&g);
    return value(position(v.x, v.y, v.z), all);
  }

  //! Points along the first trunk's centre line, where the value is the trunk's full intensity 1.
  std::vector<glm::vec3> trunkPoints() const {
    std::vector<glm::vec3> points;
    for (int i = 0; i < kSegmentsPerVessel; ++i)
      for (float t : {0.0f, 0.25f, 0.5f, 0.75f}) points.push_back(glm::mix(segments_[i].a, segments_[i].b, t));
    return points;
  }
  float step() const { return step_; }
  const glm::ivec3& dims() const { return dims_; }

 private:
  static constexpr int kSegmentsPerVessel = 4;

  static float value(const glm::vec3& p, const std::vector<const Segment*>& near) {
    static const float kTail = std::exp(-4.5f);
    float best = 0.0f;
    for (const Segment* g : near) {
      if (g->intensity <= best || p.x < g->lo.x || p.y < g->lo.y || p.z < g->lo.z || p.x > g->hi.x || p.y > g->hi.y ||
          p.z > g->hi.z)
        continue;
      const glm::vec3 ab = g->b - g->a;
      const float t = std::clamp(glm::dot(p - g->a, ab) / glm::dot(ab, ab), 0.0f, 1.0f);
      const float d = glm::length(p - (g->a + t * ab));
      if (d <= g->core) {
        best = g->intensity;
        continue;
      }
      const float u = (d - g->core) / g->sigma;
      if (u >= 3.0f) continue;
      best = std::max(best, g->intensity * (std::exp(-0.5f * u * u) - kTail) / (1.0f - kTail));
    }
    return best;
  }

  void grow(Random& random, glm::vec3 p, glm::vec3 dir, float radius, float length, int depth) {
    const float intensity = depth == 0 ? 1.0f : 0.55f + 0.45f * std::sqrt(radius / kRootRadius);
    const float core = 0.5f * radius, sigma = std::max(0.5f * radius, 0.6f * step_);
    for (int i = 0; i < kSegmentsPerVessel; ++i) {
      if (depth > 0 || i > 0) dir = glm::normalize(dir + 0.3f * random.direction());
      if (glm::length(p) > 0.8f) dir = glm::normalize(dir - 0.6f * glm::normalize(p));  // stay inside
      const glm::vec3 q = p + dir * (length / kSegmentsPerVessel);
      const float reach = core + 3.0f * sigma;
      segments_.push_back({p, q, core, sigma, intensity, glm::min(p, q) - reach, glm::max(p, q) + reach});
      p = q;
    }
    if (depth == kMaxDepth) return;
    glm::vec3 axis = glm::cross(dir, random.direction());
    axis = glm::length(axis) > 1e-3f ? glm::normalize(axis) : glm::normalize(glm::cross(dir, glm::vec3(1, 0, 0)));
    const float angles[2] = {random.range(0.30f, 0.60f), -random.range(0.45f, 0.95f)};
    const float radii[2] = {0.85f * radius, 0.65f * radius};
    for (int c = 0; c < 2; ++c) {
      const glm::vec3 child = std::cos(angles[c]) * dir + std::sin(angles[c]) * glm::cross(axis, dir);
      grow(random, p, glm::normalize(child), radii[c], length * random.range(0.7f, 0.85f), depth + 1);
    }
  }

  glm::ivec3 dims_;
  float step_;  // world size of one voxel in the isotropic [-1, 1] frame
  std::vector<Segment> segments_;
};

//! The value range: 0 and 1 when a corner voxel is background and a voxel near the first trunk's
//! centre line lies in its full-intensity core (then no voxel can be outside [0, 1]); otherwise
//! (very small volumes) one exact pass.
void computeRange(const VesselTree& tree, VolumeInfo& info) {
  const glm::ivec3 d = tree.dims();
  bool background = false, full = false;
  for (int c = 0; c < 8; ++c) {
    const glm::ivec3 corner((c & 1) ? d.x - 1 : 0, (c & 2) ? d.y - 1 : 0, (c & 4) ? d.z - 1 : 0);
    background = background || tree.valueAt(corner) == 0.0f;
  }
  const glm::vec3 half = 0.5f * glm::vec3(d - 1);
  for (const glm::vec3& p : tree.trunkPoints()) {
    const glm::ivec3 v = glm::ivec3(glm::round(p / tree.step() + half));
    if (glm::all(glm::greaterThanEqual(v, glm::ivec3(0))) && glm::all(glm::lessThan(v, d)))
      full = full || tree.valueAt(v) == 1.0f;
  }
  if (background && full) {
    info.minValue = 0.0f;
    info.maxValue = 1.0f;
    return;
  }
  std::vector<float> slice(std::size_t(d.x) * d.y);
  info.minValue = 1.0f;
  info.maxValue = 0.0f;
  for (int z = 0; z < d.z; ++z) {
    tree.generate(VoxelBox{{0, 0, z}, {d.x, d.y, z + 1}}, slice.data());
    const auto [lo, hi] = std::minmax_element(slice.begin(), slice.end());
    info.minValue = std::min(info.minValue, *lo);
    info.maxValue = std::max(info.maxValue, *hi);
  }
}

}  // namespace

std::unique_ptr<VolumeSource> makeVessels(const glm::ivec3& dims) {
  VolumeInfo info;
  info.dims = dims;
  info.type = "float32";
  info.name = "vessels";
  info.preset = "vessels";
  validateVolumeInfo(info, info.name);
  auto tree = std::make_shared<const VesselTree>(dims);
  computeRange(*tree, info);
  return std::make_unique<ProceduralSource>(info, [tree](const VoxelBox& box, float* out) { tree->generate(box, out); });
}

}  // namespace kdswap
