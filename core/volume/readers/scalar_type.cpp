// Stored scalar types and their conversion to float.
#include "core/volume/readers/scalar_type.h"

#include <bit>
#include <cstdint>
#include <cstring>

namespace kdswap {
namespace {

constexpr std::string_view kNames[] = {"int8", "uint8", "int16", "uint16", "int32", "uint32", "float32", "float64"};
constexpr std::size_t kSizes[] = {1, 1, 2, 2, 4, 4, 4, 8};
static_assert(std::size(kNames) == kScalarTypeCount && std::size(kSizes) == kScalarTypeCount);

template <typename T>
T loadSwapped(const unsigned char* p, bool swap) {
  unsigned char b[sizeof(T)];
  std::memcpy(b, p, sizeof(T));
  if (swap)
    for (std::size_t i = 0; i < sizeof(T) / 2; ++i) std::swap(b[i], b[sizeof(T) - 1 - i]);
  T v;
  std::memcpy(&v, b, sizeof(T));
  return v;
}

template <typename T>
void convert(const unsigned char* p, std::size_t count, bool swap, float* out, float scale, float offset) {
  const bool identity = scale == 1.0f && offset == 0.0f;
  for (std::size_t i = 0; i < count; ++i) {
    const float v = float(loadSwapped<T>(p + i * sizeof(T), swap));
    out[i] = identity ? v : v * scale + offset;
  }
}

}  // namespace

std::optional<ScalarType> parseScalarType(std::string_view name) {
  for (std::size_t i = 0; i < std::size(kNames); ++i)
    if (kNames[i] == name) return ScalarType(i);
  return std::nullopt;
}

std::string_view scalarTypeName(ScalarType type) { return kNames[std::size_t(type)]; }
std::size_t scalarTypeSize(ScalarType type) { return kSizes[std::size_t(type)]; }

std::string scalarTypeList() {
  std::string list;
  for (std::string_view n : kNames) {
    if (!list.empty()) list += ' ';
    list += n;
  }
  return list;
}

void convertToFloat(const void* bytes, std::size_t count, ScalarType type, bool bigEndian, float* out, float scale,
                    float offset) {
  const auto* p = static_cast<const unsigned char*>(bytes);
  const bool swap = bigEndian != (std::endian::native == std::endian::big);
  switch (type) {
    case ScalarType::Int8: convert<std::int8_t>(p, count, swap, out, scale, offset); break;
    case ScalarType::Uint8: convert<std::uint8_t>(p, count, swap, out, scale, offset); break;
    case ScalarType::Int16: convert<std::int16_t>(p, count, swap, out, scale, offset); break;
    case ScalarType::Uint16: convert<std::uint16_t>(p, count, swap, out, scale, offset); break;
    case ScalarType::Int32: convert<std::int32_t>(p, count, swap, out, scale, offset); break;
    case ScalarType::Uint32: convert<std::uint32_t>(p, count, swap, out, scale, offset); break;
    case ScalarType::Float32: convert<float>(p, count, swap, out, scale, offset); break;
    case ScalarType::Float64: convert<double>(p, count, swap, out, scale, offset); break;
  }
}

}  // namespace kdswap
