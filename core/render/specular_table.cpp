// SpecularTable: made once per exponent, kept in a small most-recent-first list.
#include "core/render/specular_table.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <mutex>
#include <utility>

#include "core/render/sample_shader.h"

namespace kdswap {
namespace {

constexpr std::size_t kKept = 4;  //!< exponents kept (the GUI's slider may pass through many)
constexpr float kSmallestEntry = 0x1p-64f;  //!< smaller entries are stored as 0

struct Kept {
  std::uint32_t bits;  //!< the exponent's bit pattern: equal bits, equal table
  std::shared_ptr<const std::vector<float>> table;
};

}  // namespace

std::shared_ptr<const std::vector<float>> specularTableFor(float shininess) {
  static std::mutex mutex;
  static std::vector<Kept> kept;  // most recent first
  std::uint32_t bits;
  std::memcpy(&bits, &shininess, sizeof bits);
  const std::lock_guard<std::mutex> lock(mutex);
  const auto found = std::find_if(kept.begin(), kept.end(), [&](const Kept& k) { return k.bits == bits; });
  if (found != kept.end()) {
    std::rotate(kept.begin(), found, found + 1);
    return kept.front().table;
  }
  auto table = std::make_shared<std::vector<float>>(kSpecularEntries + 1);
  for (int i = 0; i <= kSpecularEntries; ++i) {
    // Entries below 2^-64 are 0: pow(4 / 256, 24) is subnormal, and on Intel cores every vector
    // operation with a subnormal operand takes a microcode assist of ~100 cycles (grazing light:
    // 7% of the paper cell's frame on an Intel Xeon). A highlight that small, times any weight,
    // never reaches an 8-bit step, and what is still added to it stays a normal float.
    const float v = std::pow(float(i) / kSpecularEntries, shininess);
    (*table)[std::size_t(i)] = v < kSmallestEntry ? 0.0f : v;
  }
  kept.insert(kept.begin(), Kept{bits, table});
  if (kept.size() > kKept) kept.pop_back();
  return table;
}

}  // namespace kdswap
