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

//! Hashes one part of a message fed in pieces (the payload's rows, then the loan's): pieces are
//! joined into 8-byte words, so the hash depends only on the bytes, not on how they were cut.
class PartHasher {
 public:
  explicit PartHasher(std::uint64_t h) : h_(h) {}
  void add(const void* data, std::size_t bytes) {
    const auto* p = static_cast<const unsigned char*>(data);
    for (std::size_t i = 0; i < bytes; ++i) {  // finish a started word byte by byte
      if (filled_ == 0 && bytes - i >= 8) {
        for (; i + 8 <= bytes; i += 8) {
          std::uint64_t w;
          std::memcpy(&w, p + i, 8);
          h_ = mix(h_, w);
        }
        if (i == bytes) break;
      }
      word_ |= std::uint64_t(p[i]) << (8 * filled_);
      if (++filled_ == 8) h_ = mix(h_, word_), word_ = 0, filled_ = 0;
    }
    total_ += bytes;
  }
  std::uint64_t finish() const { return mix(h_, word_ ^ total_); }

 private:
  std::uint64_t h_, word_ = 0, total_ = 0;
  int filled_ = 0;
};

std::uint64_t hashBytes(std::uint64_t h, const void* data, std::size_t bytes) {
  PartHasher part(h);
  if (bytes > 0) part.add(data, bytes);  // an empty vector's data() may be null
  return part.finish();
}

}  // namespace

void Message::flatten() {
  if (loan.count() == 0) {
    loan = FloatLoan{};
    return;
  }
  payload.reserve(payload.size() + std::size_t(loan.count()));
  for (std::int64_t i = 0; i < loan.rows; ++i) payload.insert(payload.end(), loan.row(i), loan.row(i) + loan.rowFloats);
  loan = FloatLoan{};
}

std::uint64_t messageChecksum(const Message& m) {
  std::uint64_t h = 0x243f6a8885a308d3ull ^ std::uint64_t(m.tag);
  h = hashBytes(h, m.header.data(), m.header.size() * sizeof(std::int64_t));
  PartHasher bulk(h);
  if (!m.payload.empty()) bulk.add(m.payload.data(), m.payload.size() * sizeof(float));
  for (std::int64_t i = 0; i < m.loan.rows && m.loan.rowFloats > 0; ++i)
    bulk.add(m.loan.row(i), std::size_t(m.loan.rowFloats) * sizeof(float));
  h = bulk.finish();
  h = hashBytes(h, m.text.data(), m.text.size());
  return h == 0 ? 1 : h;
}

}  // namespace kdswap
