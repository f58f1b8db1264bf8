// Legacy VTK parsing ("VTK File Formats", VTK User's Guide): header lines, then keywords up to
// LOOKUP_TABLE, after which the data start. Keywords compare case-insensitively, as VTK does.
#include "core/volume/readers/vtk_reader.h"

#include <cctype>
#include <charconv>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>

#include <glm/common.hpp>

#include "core/util/error.h"
#include "core/volume/readers/header_text.h"
#include "core/volume/readers/stored_data.h"

namespace kdswap {
namespace {

constexpr std::size_t kMaxHeaderBytes = 1 << 16;

std::optional<ScalarType> vtkType(const std::string& t) {
  static const std::map<std::string, ScalarType> types = {
      {"char", ScalarType::Int8},           {"unsigned_char", ScalarType::Uint8},
      {"short", ScalarType::Int16},         {"unsigned_short", ScalarType::Uint16},
      {"int", ScalarType::Int32},           {"unsigned_int", ScalarType::Uint32},
      {"float", ScalarType::Float32},       {"double", ScalarType::Float64},
      {"vtktypeint8", ScalarType::Int8},    {"vtktypeuint8", ScalarType::Uint8},
      {"vtktypeint16", ScalarType::Int16},  {"vtktypeuint16", ScalarType::Uint16},
      {"vtktypeint32", ScalarType::Int32},  {"vtktypeuint32", ScalarType::Uint32},
      {"vtktypefloat32", ScalarType::Float32}, {"vtktypefloat64", ScalarType::Float64},
  };
  auto it = types.find(t);
  return it == types.end() ? std::nullopt : std::optional(it->second);
}

glm::dvec3 parseVec3(const std::vector<std::string_view>& words, const std::string& where) {
  glm::dvec3 v(0.0);
  for (int a = 0; a < 3; ++a) {
    const auto n = words.size() == 4 ? parseNumber(words[a + 1]) : std::nullopt;
    if (!n) throw Error(where + ": " + printable(words[0]) + ": expected 3 numbers");
    v[a] = *n;
  }
  return v;
}

//! Parses `count` whitespace-separated numbers starting at byte `offset`, a chunk at a time.
std::vector<float> parseAsciiValues(const std::string& path, std::uint64_t offset, std::uint64_t count) {
  std::ifstream in(path, std::ios::binary);
  in.seekg(std::streamoff(offset));
  std::vector<float> values;
  values.reserve(count);
  std::string carry, chunk(1 << 20, '\0');
  bool ended = false;
  while (values.size() < count && !ended) {
    in.read(chunk.data(), std::streamsize(chunk.size()));
    const std::size_t got = std::size_t(in.gcount());
    ended = got == 0;
    std::string text = carry + chunk.substr(0, got);
    carry.clear();
    std::size_t i = 0;
    while (values.size() < count) {
      while (i < text.size() && std::isspace(static_cast<unsigned char>(text[i]))) ++i;
      std::size_t j = i;
      while (j < text.size() && !std::isspace(static_cast<unsigned char>(text[j]))) ++j;
      if (i == j) break;
      if (j == text.size() && !ended) {  // the token may continue in the next chunk
        carry = text.substr(i);
        break;
      }
      const auto v = parseNumber(std::string_view(text).substr(i, j - i));
      if (!v)
        throw Error(path + ": ASCII value " + std::to_string(values.size() + 1) + " " +
                    quote(std::string_view(text).substr(i, j - i), 20) + ": expected a number");
      values.push_back(float(*v));
      i = j;
    }
  }
  if (values.size() < count)
    throw Error(path + ": truncated: ASCII data hold " + std::to_string(values.size()) + " values, expected " +
                std::to_string(count));
  return values;
}

}  // namespace

bool VtkReader::accepts(const std::string& path) const {
  return lowercase(std::filesystem::path(path).extension().string()) == ".vtk";
}

std::unique_ptr<VolumeSource> VtkReader::open(const std::string& path, const RawLayout&) const {
  const std::string text = readFilePrefix(path, kMaxHeaderBytes);
  std::size_t pos = 0;
  std::string_view line;
  if (!nextLine(text, pos, line) || lowercase(line).rfind("# vtk datafile version", 0) != 0)
    throw Error(path + ": not a legacy VTK file: expected \"# vtk DataFile Version x.x\" on the first line");
  std::string_view title, format;
  if (!nextLine(text, pos, title)) throw Error(path + ": truncated: the header ends after the first line");
  do {  // VTK itself skips blank lines here (ironProt.vtk has one)
    if (!nextLine(text, pos, format)) throw Error(path + ": truncated: the header ends before the ASCII/BINARY line");
  } while (trim(format).empty());
  const std::string mode = lowercase(trim(format));
  if (mode != "ascii" && mode != "binary")
    throw Error(path + ": line 3 " + quote(trim(format), 20) + ": expected ASCII or BINARY");

  VolumeInfo info;
  info.name = path;
  std::optional<glm::ivec3> dims;
  std::optional<std::int64_t> pointCount;
  std::optional<ScalarType> type;
  std::optional<glm::dvec3> spacing;
  std::string spacingField;  // as messages show it: the keyword and its numbers
  bool dataset = false;
  for (;;) {
    const std::size_t lineStart = pos;
    if (!nextLine(text, pos, line)) throw Error(path + ": truncated: the header ends before the scalar data");
    const auto words = splitWords(line);
    if (words.empty()) continue;
    const std::string key = lowercase(words[0]);
    if (type) {  // after SCALARS: LOOKUP_TABLE, or the data start on this very line
      if (key != "lookup_table") pos = lineStart;
      break;
    }
    if (key == "dataset") {
      if (words.size() != 2 || lowercase(words[1]) != "structured_points")
        throw Error(path + ": " + printable(line) + ": only DATASET STRUCTURED_POINTS is supported");
      dataset = true;
    } else if (key == "dimensions") {
      std::vector<std::int64_t> sizes;
      for (std::size_t i = 1; i < words.size(); ++i) {
        const auto v = parseInteger(words[i]);
        if (!v) throw Error(path + ": " + printable(line) + ": expected 3 whole numbers");
        sizes.push_back(*v);
      }
      dims = dimsFromSizes(sizes, path, "DIMENSIONS");
    } else if (key == "spacing" || key == "aspect_ratio") {
      // Checked once DIMENSIONS are known; a negative spacing (VTK's reversed axis) is read as its
      // size, as in every format (kdswap ignores orientation).
      spacing = glm::abs(parseVec3(words, path));
      spacingField = printable(line);
    } else if (key == "origin") {
      parseVec3(words, path);
    } else if (key == "point_data") {
      pointCount = words.size() == 2 ? parseInteger(words[1]) : std::nullopt;
      if (!pointCount) throw Error(path + ": " + printable(line) + ": expected POINT_DATA n");
    } else if (key == "scalars") {
      if (!dataset || !dims || !pointCount)
        throw Error(path + ": SCALARS before DATASET STRUCTURED_POINTS, DIMENSIONS and POINT_DATA");
      if (words.size() < 3 || words.size() > 4) throw Error(path + ": " + printable(line) + ": expected SCALARS name type [1]");
      type = vtkType(lowercase(words[2]));
      if (!type)
        throw Error(path + ": SCALARS type " + quote(words[2]) + ": unsupported (expected unsigned_char char "
                    "unsigned_short short unsigned_int int float double)");
      if (words.size() == 4 && words[3] != "1")
        throw Error(path + ": SCALARS with " + printable(words[3]) + " components: only 1 component is supported");
    } else {
      throw Error(path + ": keyword " + quote(words[0], 30) + ": unsupported (expected DATASET "
                  "STRUCTURED_POINTS, DIMENSIONS, SPACING, ORIGIN, POINT_DATA, SCALARS)");
    }
  }

  info.dims = *dims;
  if (spacing) {
    checkSpacing(info.dims, *spacing, path, spacingField);
    info.spacing = glm::vec3(*spacing);
  }
  validateVolumeInfo(info, path);
  if (*pointCount != info.voxelCount())
    throw Error(path + ": header and data size disagree: POINT_DATA " + std::to_string(*pointCount) + ", DIMENSIONS " +
                dimsText(info.dims) + " make " + std::to_string(info.voxelCount()) + " points");
  if (mode == "ascii") {
    info.type = std::string(scalarTypeName(*type));
    return openDecoded(info, parseAsciiValues(path, pos, std::uint64_t(info.voxelCount())));
  }
  StoredData data;
  data.path = path;
  data.offset = pos;
  data.type = *type;
  data.bigEndian = true;      // legacy VTK binary data are always big-endian
  data.allowTrailing = true;  // further attributes or a final newline may follow
  return openStoredData(std::move(info), data);
}

}  // namespace kdswap
