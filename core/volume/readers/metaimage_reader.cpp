// MetaImage header parsing (MetaIO "Key = Value" lines; ElementDataFile is always the last).
#include "core/volume/readers/metaimage_reader.h"

#include <cmath>
#include <filesystem>
#include <map>

#include "core/util/error.h"
#include "core/volume/readers/header_text.h"
#include "core/volume/readers/stored_data.h"

namespace kdswap {
namespace {

constexpr std::size_t kMaxHeaderBytes = 1 << 16;

std::optional<ScalarType> metaType(const std::string& t) {
  static const std::map<std::string, ScalarType> types = {
      {"met_char", ScalarType::Int8},   {"met_uchar", ScalarType::Uint8},  {"met_short", ScalarType::Int16},
      {"met_ushort", ScalarType::Uint16}, {"met_int", ScalarType::Int32},  {"met_uint", ScalarType::Uint32},
      {"met_float", ScalarType::Float32}, {"met_double", ScalarType::Float64},
  };
  auto it = types.find(t);
  return it == types.end() ? std::nullopt : std::optional(it->second);
}

bool parseBool(const std::string& value, const std::string& where, const std::string& key) {
  const std::string v = lowercase(value);
  if (v == "true" || v == "1") return true;
  if (v == "false" || v == "0") return false;
  throw Error(where + ": " + key + " = " + printable(value) + ": expected True or False");
}

//! A negative spacing is read as its size, as in every format (kdswap ignores orientation; MetaIO
//! keeps direction in TransformMatrix). NaN, Inf, 0 and spacings outside checkSpacing's bounds are refused.
glm::vec3 parseSpacing(const std::string& value, const glm::ivec3& dims, const std::string& where, const std::string& key) {
  const auto words = splitWords(value);
  glm::dvec3 spacing(1.0);
  for (int a = 0; a < 3; ++a) {
    const auto v = a < int(words.size()) ? parseNumber(words[a]) : std::nullopt;
    if (words.size() != 3 || !v) throw Error(where + ": " + key + " = " + printable(value) + ": expected 3 numbers");
    spacing[a] = std::abs(*v);
  }
  checkSpacing(dims, spacing, where, key + " = " + printable(value));
  return glm::vec3(spacing);
}

}  // namespace

bool MetaImageReader::accepts(const std::string& path) const {
  const std::string ext = lowercase(std::filesystem::path(path).extension().string());
  return ext == ".mhd" || ext == ".mha";
}

std::unique_ptr<VolumeSource> MetaImageReader::open(const std::string& path, const RawLayout&) const {
  const std::string text = readFilePrefix(path, kMaxHeaderBytes);
  std::map<std::string, std::string> fields;  // lower-case key -> value
  std::size_t pos = 0;
  std::string_view line;
  bool haveDataFile = false;
  while (!haveDataFile) {
    if (!nextLine(text, pos, line)) {
      if (text.size() == kMaxHeaderBytes || pos == text.size()) break;
      line = std::string_view(text).substr(pos);  // last line without newline
      pos = text.size();
    }
    const std::string_view trimmed = trim(line);
    if (trimmed.empty() || trimmed.front() == '#') continue;
    const std::size_t eq = trimmed.find('=');
    if (eq == std::string_view::npos)
      throw Error(path + ": header line " + quote(trimmed) + ": expected \"Key = Value\"");
    const std::string key = lowercase(trim(trimmed.substr(0, eq)));
    fields[key] = std::string(trim(trimmed.substr(eq + 1)));
    haveDataFile = key == "elementdatafile";
  }
  if (!haveDataFile) throw Error(path + ": no ElementDataFile line: expected it as the last header line");
  auto field = [&](const char* key) -> const std::string* {
    auto it = fields.find(key);
    return it == fields.end() ? nullptr : &it->second;
  };

  if (const std::string* object = field("objecttype"); object && lowercase(*object) != "image")
    throw Error(path + ": ObjectType = " + printable(*object) + ": expected Image");
  const std::string* ndims = field("ndims");
  if (!ndims) throw Error(path + ": no NDims line: expected NDims = 3");
  if (*ndims != "3") throw Error(path + ": NDims = " + printable(*ndims) + ": only 3D volumes are supported (NDims = 3)");
  const std::string* dimSize = field("dimsize");
  if (!dimSize) throw Error(path + ": no DimSize line: expected DimSize = W H D");
  const auto sizes = parseSizes(*dimSize, 3);
  if (!sizes) throw Error(path + ": DimSize = " + printable(*dimSize) + ": expected 3 whole numbers");
  VolumeInfo info;
  info.name = path;
  info.dims = dimsFromSizes(*sizes, path, "DimSize");

  StoredData data;
  const std::string* elementType = field("elementtype");
  if (!elementType) throw Error(path + ": no ElementType line: expected e.g. ElementType = MET_UCHAR");
  const auto scalar = metaType(lowercase(*elementType));
  if (!scalar)
    throw Error(path + ": ElementType = " + printable(*elementType) +
                ": unsupported (expected MET_CHAR MET_UCHAR MET_SHORT MET_USHORT MET_INT MET_UINT MET_FLOAT MET_DOUBLE)");
  data.type = *scalar;
  if (const std::string* channels = field("elementnumberofchannels"); channels && *channels != "1")
    throw Error(path + ": ElementNumberOfChannels = " + printable(*channels) + ": only scalar volumes are supported (1)");
  if (const std::string* binary = field("binarydata"); binary && !parseBool(*binary, path, "BinaryData"))
    throw Error(path + ": BinaryData = " + printable(*binary) + ": only binary data is supported (True)");
  if (const std::string* msb = field("binarydatabyteordermsb"))
    data.bigEndian = parseBool(*msb, path, "BinaryDataByteOrderMSB");
  else if (const std::string* msb2 = field("elementbyteordermsb"))
    data.bigEndian = parseBool(*msb2, path, "ElementByteOrderMSB");
  if (const std::string* compressed = field("compresseddata"))
    data.compressed = parseBool(*compressed, path, "CompressedData");
  if (const std::string* spacing = field("elementspacing"))
    info.spacing = parseSpacing(*spacing, info.dims, path, "ElementSpacing");
  else if (const std::string* size = field("elementsize"))
    info.spacing = parseSpacing(*size, info.dims, path, "ElementSize");

  const std::string& dataFile = *field("elementdatafile");
  const auto words = splitWords(dataFile);
  if (dataFile == "LOCAL") {
    data.path = path;
    data.offset = pos;
  } else {
    if (words.size() != 1 || words[0] == "LIST")
      throw Error(path + ": ElementDataFile = " + printable(dataFile) + ": only LOCAL or a single file is supported");
    data.path = siblingPath(path, dataFile);
    checkDataFile(data.path, path, "ElementDataFile " + printable(dataFile));
  }
  if (const std::string* headerSize = field("headersize")) {
    const auto n = parseInteger(*headerSize);
    if (!n || *n < -1) throw Error(path + ": HeaderSize = " + printable(*headerSize) + ": expected a whole number >= -1");
    if (*n == -1) {  // the data are the last bytes of the file
      if (data.compressed) throw Error(path + ": HeaderSize = -1: not allowed with CompressedData");
      data.offset = trailingDataOffset(info, data);
    } else {
      data.offset += std::uint64_t(*n);
    }
  }
  return openStoredData(std::move(info), data);
}

}  // namespace kdswap
