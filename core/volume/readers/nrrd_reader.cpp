// NRRD header parsing (format spec: teem.sourceforge.net/nrrd/format.html).
#include "core/volume/readers/nrrd_reader.h"

#include <cmath>
#include <filesystem>
#include <map>

#include <glm/geometric.hpp>

#include "core/util/error.h"
#include "core/volume/readers/header_text.h"
#include "core/volume/readers/stored_data.h"

namespace kdswap {
namespace {

constexpr std::size_t kMaxHeaderBytes = 1 << 20;

std::optional<ScalarType> nrrdType(const std::string& t) {
  static const std::map<std::string, ScalarType> types = {
      {"signed char", ScalarType::Int8},      {"int8", ScalarType::Int8},
      {"int8_t", ScalarType::Int8},           {"uchar", ScalarType::Uint8},
      {"unsigned char", ScalarType::Uint8},   {"uint8", ScalarType::Uint8},
      {"uint8_t", ScalarType::Uint8},         {"short", ScalarType::Int16},
      {"short int", ScalarType::Int16},       {"signed short", ScalarType::Int16},
      {"signed short int", ScalarType::Int16}, {"int16", ScalarType::Int16},
      {"int16_t", ScalarType::Int16},         {"ushort", ScalarType::Uint16},
      {"unsigned short", ScalarType::Uint16}, {"unsigned short int", ScalarType::Uint16},
      {"uint16", ScalarType::Uint16},         {"uint16_t", ScalarType::Uint16},
      {"int", ScalarType::Int32},             {"signed int", ScalarType::Int32},
      {"int32", ScalarType::Int32},           {"int32_t", ScalarType::Int32},
      {"uint", ScalarType::Uint32},           {"unsigned int", ScalarType::Uint32},
      {"uint32", ScalarType::Uint32},         {"uint32_t", ScalarType::Uint32},
      {"float", ScalarType::Float32},         {"double", ScalarType::Float64},
  };
  auto it = types.find(t);
  return it == types.end() ? std::nullopt : std::optional(it->second);
}

//! "(1,0,0) (0,1,0) (0,0,2)" -> lengths of the three vectors (a reversed axis still has its length:
//! kdswap ignores orientation). Checked by checkSpacing.
glm::vec3 spacingFromDirections(std::string_view value, const glm::ivec3& dims, const std::string& where) {
  glm::dvec3 spacing(1.0);
  int axis = 0;
  std::size_t pos = 0;
  while (axis < 3) {
    const std::size_t open = value.find('(', pos);
    if (open == std::string_view::npos) break;
    const std::size_t close = value.find(')', open);
    if (close == std::string_view::npos) break;
    std::string_view inside = value.substr(open + 1, close - open - 1);
    glm::dvec3 v(0.0);
    int n = 0;
    while (!inside.empty() && n < 4) {
      const std::size_t comma = inside.find(',');
      const auto number = parseNumber(inside.substr(0, comma));
      if (!number) throw Error(where + ": space directions " + quote(value) + ": expected (x,y,z) vectors of numbers");
      if (n < 3) v[n] = *number;
      ++n;
      inside = comma == std::string_view::npos ? std::string_view() : inside.substr(comma + 1);
    }
    if (n != 3) throw Error(where + ": space directions " + quote(value) + ": expected 3 components per vector");
    spacing[axis++] = glm::length(v);
    pos = close + 1;
  }
  if (axis != 3) throw Error(where + ": space directions " + quote(value) + ": expected 3 vectors (x,y,z)");
  checkSpacing(dims, spacing, where, "space directions " + quote(value));
  return glm::vec3(spacing);
}

//! "spacings: 0.5 -0.5 nan": NaN is the format's "unknown" (teem's own check accepts it and refuses
//! only Inf and 0), read as 1 like a missing field; a negative spacing, which NRRD allows for a
//! reversed axis, is read as its size (kdswap ignores orientation, as for every format). Inf, 0 and
//! spacings outside checkSpacing's bounds are refused.
glm::vec3 spacingFromSpacings(std::string_view value, const glm::ivec3& dims, const std::string& where) {
  const auto words = splitWords(value);
  if (words.size() != 3) throw Error(where + ": spacings " + quote(value) + ": expected 3 numbers");
  glm::dvec3 spacing(1.0);
  for (int a = 0; a < 3; ++a) {
    const auto v = parseNumber(words[a]);
    if (!v) throw Error(where + ": spacings " + quote(value) + ": expected 3 numbers");
    if (!std::isnan(*v)) spacing[a] = std::abs(*v);
  }
  checkSpacing(dims, spacing, where, "spacings " + quote(value));
  return glm::vec3(spacing);
}

//! Byte offset just after `lines` newlines from `start` in `path`.
std::uint64_t skipLines(const std::string& path, std::uint64_t start, std::int64_t lines) {
  if (lines <= 0) return start;
  const std::string text = readFilePrefix(path, std::size_t(start) + kMaxHeaderBytes);
  std::size_t pos = std::size_t(start);
  std::string_view line;
  for (std::int64_t i = 0; i < lines; ++i)
    if (!nextLine(text, pos, line)) throw Error(path + ": line skip " + std::to_string(lines) + ": the file has fewer lines");
  return pos;
}

struct NrrdHeader {
  std::map<std::string, std::string> fields;  //!< lower-case field name -> value
  bool blankLine = false;                     //!< the header ended with an empty line
  std::size_t end = 0;                        //!< byte after the header: attached data start here

  const std::string* find(const char* key) const {
    auto it = fields.find(key);
    return it == fields.end() ? nullptr : &it->second;
  }
  const std::string& require(const char* key, const std::string& where) const {
    if (const std::string* v = find(key)) return *v;
    throw Error(where + ": no \"" + key + "\" field: a NRRD header needs type, dimension, sizes, encoding");
  }
};

//! Reads the magic line and the "field: value" lines up to a blank line or the end of the file;
//! comments and "key:=value" pairs are skipped.
NrrdHeader readHeader(const std::string& path) {
  const std::string text = readFilePrefix(path, kMaxHeaderBytes);
  const bool wholeFile = text.size() < kMaxHeaderBytes;
  std::size_t pos = 0;
  std::string_view line;
  const bool magicLine = nextLine(text, pos, line);
  if (!magicLine || line.substr(0, 4) != "NRRD")
    throw Error(path + ": not a NRRD file: first line " + quote(text.substr(0, text.find('\n'))) +
                ": expected NRRD0001 .. NRRD0005");
  // Format versions 1 to 5 are what this reader (and teem today) knows; a later one may mean fields it cannot read.
  if (line.size() != 8 || line.substr(0, 7) != "NRRD000" || line[7] < '1' || line[7] > '5')
    throw Error(path + ": NRRD magic " + quote(line) + ": unsupported format version (expected NRRD0001 .. NRRD0005)");
  NrrdHeader header;
  for (;;) {
    if (!nextLine(text, pos, line)) {
      if (!wholeFile) throw Error(path + ": header longer than 1 MiB: expected a blank line before the data");
      line = std::string_view(text).substr(pos);  // a last line without newline
      pos = text.size();
      if (line.empty()) break;
    }
    if (line.empty()) {
      header.blankLine = true;
      break;
    }
    if (line.front() == '#' || line.find(":=") != std::string_view::npos) continue;
    const std::size_t colon = line.find(": ");
    if (colon == std::string_view::npos) throw Error(path + ": header line " + quote(line) + ": expected \"field: value\"");
    header.fields[lowercase(trim(line.substr(0, colon)))] = std::string(trim(line.substr(colon + 2)));
    if (pos == text.size()) break;
  }
  header.end = pos;
  return header;
}

//! Where the voxels are: the data file (or this file after the header), then line and byte skips.
void locateData(const NrrdHeader& header, const std::string& path, const VolumeInfo& info, StoredData& data) {
  const std::string* dataFile = header.find("data file");
  if (!dataFile) dataFile = header.find("datafile");
  std::uint64_t start = 0;
  if (dataFile) {
    const auto words = splitWords(*dataFile);
    if (words.size() != 1 || words[0] == "LIST")
      throw Error(path + ": data file " + quote(*dataFile) + ": only a single data file is supported");
    data.path = siblingPath(path, *dataFile);
    checkDataFile(data.path, path, "data file " + quote(*dataFile));
  } else {
    if (!header.blankLine) throw Error(path + ": no \"data file\" field and no blank line before attached data");
    data.path = path;
    start = header.end;
  }

  std::int64_t lineSkip = 0, byteSkip = 0;
  if (const std::string* v = header.find("line skip")) {
    const auto n = parseInteger(*v);
    if (!n || *n < 0) throw Error(path + ": line skip " + quote(*v) + ": expected a whole number >= 0");
    lineSkip = *n;
  }
  if (const std::string* v = header.find("byte skip")) {
    const auto n = parseInteger(*v);
    if (!n || *n < -1) throw Error(path + ": byte skip " + quote(*v) + ": expected a whole number >= -1");
    byteSkip = *n;
  }
  data.offset = skipLines(data.path, start, lineSkip);
  if (data.compressed) {  // NRRD applies byte skip to the decompressed bytes
    if (byteSkip < 0) throw Error(path + ": byte skip -1: only allowed with raw encoding");
    data.skipDecoded = std::uint64_t(byteSkip);
  } else if (byteSkip == -1) {  // the data are the last bytes of the file
    data.offset = trailingDataOffset(info, data);
  } else {
    data.offset += std::uint64_t(byteSkip);
  }
}

}  // namespace

bool NrrdReader::accepts(const std::string& path) const {
  const std::string ext = lowercase(std::filesystem::path(path).extension().string());
  return ext == ".nrrd" || ext == ".nhdr";
}

std::unique_ptr<VolumeSource> NrrdReader::open(const std::string& path, const RawLayout&) const {
  const NrrdHeader header = readHeader(path);
  const std::string& dimension = header.require("dimension", path);
  if (dimension != "3")
    throw Error(path + ": dimension " + quote(dimension) + ": only 3D volumes are supported (dimension: 3)");
  const std::string& sizesText = header.require("sizes", path);
  const auto sizes = parseSizes(sizesText, 3);
  if (!sizes) throw Error(path + ": sizes " + quote(sizesText) + ": expected 3 whole numbers");
  VolumeInfo info;
  info.name = path;
  info.dims = dimsFromSizes(*sizes, path, "sizes");

  StoredData data;
  const std::string& type = header.require("type", path);
  const auto scalar = nrrdType(lowercase(type));
  if (!scalar)
    throw Error(path + ": type " + quote(type) + ": unsupported (expected one of " + scalarTypeList() + ")");
  data.type = *scalar;

  const std::string encoding = lowercase(header.require("encoding", path));
  if (encoding == "gzip" || encoding == "gz")
    data.compressed = true;
  else if (encoding != "raw")
    throw Error(path + ": encoding " + quote(encoding) + ": unsupported (expected raw or gzip)");

  if (const std::string* endian = header.find("endian")) {
    if (*endian != "little" && *endian != "big")
      throw Error(path + ": endian " + quote(*endian) + ": expected little or big");
    data.bigEndian = *endian == "big";
  } else if (scalarTypeSize(data.type) > 1) {
    throw Error(path + ": no \"endian\" field: expected endian: little or big for " +
                std::string(scalarTypeName(data.type)) + " data");
  }

  if (const std::string* dirs = header.find("space directions"))
    info.spacing = spacingFromDirections(*dirs, info.dims, path);
  else if (const std::string* spacings = header.find("spacings"))
    info.spacing = spacingFromSpacings(*spacings, info.dims, path);

  locateData(header, path, info, data);
  return openStoredData(std::move(info), data);
}

}  // namespace kdswap
