// Void-and-cluster ordering (Ulichney 1993) of a toroidal 64 x 64 tile. A cell's energy is the sum,
// over the cells chosen so far, of a Gaussian of their wrapped distance: "tightest cluster" is the
// chosen cell of highest energy, "largest void" the free cell of lowest.
#include "core/camera/blue_noise.h"

#include <algorithm>
#include <cstdint>
#include <vector>

namespace kdswap {
namespace {

constexpr int kSide = BlueNoiseTile::kSide;
constexpr int kCells = BlueNoiseTile::kCells;
constexpr double kSigma = 1.5;             //!< Ulichney's choice: wide enough to see voids, narrow enough to be local
constexpr int kReach = 8;                  //!< the kernel's support, cells each way (see Energy::set)
constexpr int kInitialOnes = kCells / 10;  //!< the random start pattern, before it is relaxed

//! exp(x) for x <= 0 as (1 + x / 2^16)^(2^16): additions, multiplications and a division only,
//! which IEEE arithmetic rounds the same everywhere. std::exp may differ in the last bit between
//! libm versions and CPU variants (glibc picks an FMA build where the CPU has it), and a last-bit
//! difference can reorder two cells of nearly equal energy: ranks on different MPI hosts would
//! then use different tiles, and their rays different lattices. (Within 0.02% of exp here.)
double portableExp(double x) {
  double y = 1.0 + x / 65536.0;
  for (int i = 0; i < 16; ++i) y *= y;
  return y;
}

//! The energy field of a set of chosen cells, updated as cells are added and removed.
class Energy {
 public:
  Energy() : kernel_(kCells), energy_(kCells, 0.0), chosen_(kCells, 0) {
    for (int dy = 0; dy < kSide; ++dy)
      for (int dx = 0; dx < kSide; ++dx) {
        const int wx = std::min(dx, kSide - dx), wy = std::min(dy, kSide - dy);  // wrapped distance
        kernel_[std::size_t(dy * kSide + dx)] = portableExp(-double(wx * wx + wy * wy) / (2.0 * kSigma * kSigma));
      }
  }

  void set(int cell, bool chosen) {
    if (bool(chosen_[std::size_t(cell)]) == chosen) return;
    chosen_[std::size_t(cell)] = char(chosen);
    const double sign = chosen ? 1.0 : -1.0;
    const int cx = cell % kSide, cy = cell / kSide;
    // Only cells within kReach (wrapped) change by more than exp(-kReach^2 / 2 sigma^2) = 7e-7.
    for (int dy = -kReach; dy <= kReach; ++dy)
      for (int dx = -kReach; dx <= kReach; ++dx) {
        const int x = (cx + dx) & (kSide - 1), y = (cy + dy) & (kSide - 1);
        energy_[std::size_t(y * kSide + x)] += sign * kernel_[std::size_t((dy & (kSide - 1)) * kSide + (dx & (kSide - 1)))];
      }
  }
  bool chosen(int cell) const { return chosen_[std::size_t(cell)]; }

  //! The chosen cell of highest energy (first on ties).
  int tightestCluster() const {
    int best = -1;
    for (int c = 0; c < kCells; ++c)
      if (chosen_[std::size_t(c)] && (best < 0 || energy_[std::size_t(c)] > energy_[std::size_t(best)])) best = c;
    return best;
  }
  //! The free cell of lowest energy (first on ties).
  int largestVoid() const {
    int best = -1;
    for (int c = 0; c < kCells; ++c)
      if (!chosen_[std::size_t(c)] && (best < 0 || energy_[std::size_t(c)] < energy_[std::size_t(best)])) best = c;
    return best;
  }

 private:
  std::vector<double> kernel_, energy_;
  std::vector<char> chosen_;
};

//! Ranks 0..kCells-1 over the tile's cells.
std::vector<int> voidAndClusterRanks() {
  // A random start (a fixed linear congruential sequence), relaxed by moving the tightest
  // cluster's cell to the largest void until the cell moved would go straight back.
  Energy start;
  std::uint32_t state = 12345u;
  for (int placed = 0; placed < kInitialOnes;) {
    state = state * 1664525u + 1013904223u;
    const int cell = int((state >> 8) % std::uint32_t(kCells));
    if (!start.chosen(cell)) start.set(cell, true), ++placed;
  }
  for (int moves = 0; moves < 4 * kCells; ++moves) {
    const int cluster = start.tightestCluster();
    start.set(cluster, false);
    const int hole = start.largestVoid();
    start.set(hole, true);
    if (hole == cluster) break;
  }

  std::vector<int> rank(kCells, -1);
  // The start pattern's cells take ranks kInitialOnes-1 down to 0, tightest cluster first ...
  Energy shrinking = start;
  for (int r = kInitialOnes - 1; r >= 0; --r) {
    const int cell = shrinking.tightestCluster();
    rank[std::size_t(cell)] = r;
    shrinking.set(cell, false);
  }
  // ... and the other cells the ranks above, each filling the largest void left. (Past half full,
  // Ulichney ranks the free cells' tightest cluster instead; with these energies, which sum to a
  // constant over chosen and free cells, that is the same cell.)
  Energy growing = start;
  for (int r = kInitialOnes; r < kCells; ++r) {
    const int cell = growing.largestVoid();
    rank[std::size_t(cell)] = r;
    growing.set(cell, true);
  }
  return rank;
}

}  // namespace

const BlueNoiseTile& BlueNoiseTile::instance() {
  static const BlueNoiseTile tile;
  return tile;
}

BlueNoiseTile::BlueNoiseTile() {
  const std::vector<int> rank = voidAndClusterRanks();
  for (int c = 0; c < kCells; ++c) values_[std::size_t(c)] = (float(rank[std::size_t(c)]) + 0.5f) / float(kCells);
}

}  // namespace kdswap
