// Synthetic turbulence. Velocity u(x) = Re sum_m a_m exp(i k_m.x) over 96 modes with integer
// wave vectors, 1 <= |k| <= 12, and a_m perpendicular to k_m (so div u = 0), |a_m| ~ |k|^(-11/6)
// (a Kolmogorov k^(-5/3) energy spectrum with modes spread uniformly in the ball). Vorticity
// w = curl u = Re sum_m (i k_m x a_m) exp(i k_m.x); the voxel value is |w|.
// Cost: exp(i k.x) factors per axis, so a row costs one complex product per mode, then per voxel
// six multiplies per mode against a table of exp(i k_x x).
// The value is |w| mapped to [0, 1] by its minimum and maximum over a sub-lattice of the voxels
// (every s-th voxel per axis), clamped: the range is exactly [0, 1] and only the rarest extremes
// between lattice points saturate.
#include "core/volume/datasets/turbulence.h"

#include <algorithm>
#include <cmath>
#include <complex>
#include <cstdint>
#include <limits>
#include <vector>

#include <glm/geometric.hpp>
#include <oneapi/tbb/blocked_range.h>
#include <oneapi/tbb/parallel_for.h>

#include "core/volume/datasets/procedural_source.h"

namespace kdswap {
namespace {

constexpr std::uint64_t kSeed = 0x7ab1'e5ca'1e5e'ed01ull;
constexpr int kModes = 96;
constexpr int kMaxWave = 12;
constexpr int kLatticeSamples = 48;  // sub-lattice points per axis used for normalisation

using Complex = std::complex<float>;

struct Mode {
  glm::ivec3 k;
  glm::vec3 re, im;  // b = i k x a, the mode's complex vorticity amplitude
};

//! splitmix64: a fixed, portable random sequence.
class Random {
 public:
  explicit Random(std::uint64_t seed) : state_(seed) {}
  double uniform() {
    std::uint64_t z = (state_ += 0x9e3779b97f4a7c15ull);
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
    return double((z ^ (z >> 31)) >> 11) / double(1ull << 53);
  }
  glm::dvec3 gaussian3() {  // Box-Muller
    glm::dvec3 v;
    for (int i = 0; i < 3; ++i)
      v[i] = std::sqrt(-2.0 * std::log(1.0 - uniform())) * std::cos(6.283185307179586 * uniform());
    return v;
  }

 private:
  std::uint64_t state_;
};

class TurbulenceField {
 public:
  explicit TurbulenceField(const glm::ivec3& dims) : dims_(dims) {
    Random random(kSeed);
    while (int(modes_.size()) < kModes) {
      const glm::ivec3 k(int(random.uniform() * (2 * kMaxWave + 1)) - kMaxWave,
                         int(random.uniform() * (2 * kMaxWave + 1)) - kMaxWave,
                         int(random.uniform() * (2 * kMaxWave + 1)) - kMaxWave);
      const double len = glm::length(glm::dvec3(k));
      if (len < 1.0 || len > kMaxWave) continue;
      const glm::dvec3 khat = glm::dvec3(k) / len;
      glm::dvec3 ar = random.gaussian3(), ai = random.gaussian3();
      ar -= glm::dot(ar, khat) * khat;  // a perpendicular to k: divergence-free
      ai -= glm::dot(ai, khat) * khat;
      const double amplitude = std::pow(len, -11.0 / 6.0);
      // b = i k x (ar + i ai) = -(k x ai) + i (k x ar)
      modes_.push_back({k, glm::vec3(-glm::cross(glm::dvec3(k), ai) * amplitude),
                        glm::vec3(glm::cross(glm::dvec3(k), ar) * amplitude)});
    }
    normalise();
  }

  //! Fills `out` for `box` with the normalised value, rows in parallel.
  void generate(const VoxelBox& box, float* out) const {
    const glm::ivec3 s = box.size();
    const AxisTable ex = axisTable(0, box.lo.x, s.x), ey = axisTable(1, box.lo.y, s.y), ez = axisTable(2, box.lo.z, s.z);
    tbb::parallel_for(tbb::blocked_range<int>(0, s.y * s.z), [&](const tbb::blocked_range<int>& rows) {
      std::vector<float> w(3 * std::size_t(s.x));
      for (int r = rows.begin(); r != rows.end(); ++r) {
        float* row = out + std::size_t(r) * s.x;
        vorticityRow(ex, ey, r % s.y, ez, r / s.y, w.data(), row);
        for (int x = 0; x < s.x; ++x) row[x] = std::clamp((row[x] - lo_) / span_, 0.0f, 1.0f);
      }
    });
  }

 private:
  //! exp(i k_axis 2 pi v / N) for voxels v = first .. first+n-1, as [m][v] real and imaginary parts.
  struct AxisTable {
    int n;
    std::vector<float> re, im;
  };

  AxisTable axisTable(int axis, int first, int n) const {
    const int longest = std::max({dims_.x, dims_.y, dims_.z});
    AxisTable t{n, std::vector<float>(std::size_t(n) * kModes), std::vector<float>(std::size_t(n) * kModes)};
    for (int m = 0; m < kModes; ++m)
      for (int v = 0; v < n; ++v) {
        // The integer phase k v reduced mod N keeps the angle small and exact for any size.
        const long phase = (long(modes_[m].k[axis]) * (first + v)) % longest;
        const double angle = 6.283185307179586 * double(phase) / double(longest);
        t.re[std::size_t(m) * n + v] = float(std::cos(angle));
        t.im[std::size_t(m) * n + v] = float(std::sin(angle));
      }
    return t;
  }

  //! |w| along row (y, z) of the tables: per mode the row factor c = b ey ez, then
  //! w += Re(c ex) for every x (contiguous, so the compiler vectorises it).
  void vorticityRow(const AxisTable& ex, const AxisTable& ey, int y, const AxisTable& ez, int z, float* w,
                    float* out) const {
    const int n = ex.n;
    float* wx = w;
    float* wy = w + n;
    float* wz = w + 2 * n;
    std::fill(w, w + 3 * std::size_t(n), 0.0f);
    for (int m = 0; m < kModes; ++m) {
      const std::size_t iy = std::size_t(m) * ey.n + y, iz = std::size_t(m) * ez.n + z;
      const Complex c = Complex(ey.re[iy], ey.im[iy]) * Complex(ez.re[iz], ez.im[iz]);
      const glm::vec3 cre = modes_[m].re * c.real() - modes_[m].im * c.imag();
      const glm::vec3 cim = modes_[m].re * c.imag() + modes_[m].im * c.real();
      const float* er = ex.re.data() + std::size_t(m) * n;
      const float* ei = ex.im.data() + std::size_t(m) * n;
      for (int x = 0; x < n; ++x) {
        wx[x] += cre.x * er[x] - cim.x * ei[x];
        wy[x] += cre.y * er[x] - cim.y * ei[x];
        wz[x] += cre.z * er[x] - cim.z * ei[x];
      }
    }
    for (int x = 0; x < n; ++x) out[x] = std::sqrt(wx[x] * wx[x] + wy[x] * wy[x] + wz[x] * wz[x]);
  }

  //! lo_ and span_ from |w| on every s-th voxel per axis (voxels of this very volume, computed
  //! by the same code as generate(), so the extremes map to exactly 0 and 1).
  void normalise() {
    const int longest = std::max({dims_.x, dims_.y, dims_.z});
    const int stride = std::max(1, longest / kLatticeSamples);
    const AxisTable ex = axisTable(0, 0, dims_.x), ey = axisTable(1, 0, dims_.y), ez = axisTable(2, 0, dims_.z);
    float lo = std::numeric_limits<float>::max(), hi = 0.0f;
    std::vector<float> w(3 * std::size_t(dims_.x)), row(dims_.x);
    for (int z = 0; z < dims_.z; z += stride)
      for (int y = 0; y < dims_.y; y += stride) {
        vorticityRow(ex, ey, y, ez, z, w.data(), row.data());
        for (int x = 0; x < dims_.x; x += stride) {
          lo = std::min(lo, row[x]);
          hi = std::max(hi, row[x]);
        }
      }
    lo_ = lo;
    span_ = hi > lo ? hi - lo : 1.0f;
  }

  glm::ivec3 dims_;
  std::vector<Mode> modes_;
  float lo_ = 0.0f, span_ = 1.0f;  // |w| = lo_ maps to 0, lo_ + span_ to 1
};

}  // namespace

std::unique_ptr<VolumeSource> makeTurbulence(const glm::ivec3& dims) {
  VolumeInfo info;
  info.dims = dims;
  info.type = "float32";
  info.name = "turbulence";
  info.preset = "turbulence";
  info.minValue = 0.0f;
  info.maxValue = 1.0f;
  validateVolumeInfo(info, info.name);
  auto field = std::make_shared<const TurbulenceField>(dims);
  return std::make_unique<ProceduralSource>(info, [field](const VoxelBox& box, float* out) { field->generate(box, out); });
}

}  // namespace kdswap
