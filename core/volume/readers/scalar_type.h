// ScalarType: the stored voxel types kdswap reads, their names and sizes, and the conversion of
// stored bytes (either byte order) to float, shared by every reader.
#pragma once

#include <cstddef>
#include <optional>
#include <string>
#include <string_view>

namespace kdswap {

enum class ScalarType { Int8, Uint8, Int16, Uint16, Int32, Uint32, Float32, Float64 };
//! ScalarType(0) .. ScalarType(kScalarTypeCount - 1) are every type, in scalarTypeList()'s order.
inline constexpr int kScalarTypeCount = 8;

//! "int8" ... "float64": the names VolumeInfo::type and RawLayout::type use.
std::optional<ScalarType> parseScalarType(std::string_view name);
std::string_view scalarTypeName(ScalarType type);
std::size_t scalarTypeSize(ScalarType type);
//! "int8 uint8 int16 uint16 int32 uint32 float32 float64", for error messages.
std::string scalarTypeList();

//! Converts `count` stored values at `bytes` (any alignment) to floats: byte-swapped when
//! `bigEndian` differs from the machine's order, then scaled as value * scale + offset.
void convertToFloat(const void* bytes, std::size_t count, ScalarType type, bool bigEndian, float* out,
                    float scale = 1.0f, float offset = 0.0f);

}  // namespace kdswap
