// Message checksums: a word-wise multiply-xorshift hash, fast enough to run on every message of a
// test or debug build.
#include "core/comm/message.h"

#include <cstring>

namespace kdswap {
namespace {

std::uint64_t mix(std::uint64_t h, std::uint64_t word) {
  h ^= word + 0x9e3779b97f4a7c15ull + (h << 6) + (h >> 2);
  h *= 0xbf58476d1ce4e5b9ull;
  return h ^ (h >> 31);
}

std::uint64_t hashBytes(std::uint64_t h, const void* data, std::size_t bytes) {
  const auto* p = static_cast<const unsigned char*>(data);
  std::size_t i = 0;
  for (; i + 8 <= bytes; i += 8) {
    std::uint64_t w;
    std::memcpy(&w, p + i, 8);
    h = mix(h, w);
  }
  std::uint64_t tail = 0;
  if (bytes > i) std::memcpy(&tail, p + i, bytes - i);  // an empty vector's data() may be null
  return mix(h, tail ^ bytes);
}

}  // namespace

std::uint64_t messageChecksum(const Message& m) {
  std::uint64_t h = 0x243f6a8885a308d3ull ^ std::uint64_t(m.tag);
  h = hashBytes(h, m.header.data(), m.header.size() * sizeof(std::int64_t));
  h = hashBytes(h, m.payload.data(), m.payload.size() * sizeof(float));
  h = hashBytes(h, m.text.data(), m.text.size());
  return h == 0 ? 1 : h;
}

}  // namespace kdswap
