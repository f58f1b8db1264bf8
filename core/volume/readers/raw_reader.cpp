// Raw volume files: layout from RawLayout, else from the name pattern NAME_WxHxD_TYPE.raw.
#include "core/volume/readers/raw_reader.h"

#include <array>
#include <filesystem>
#include <limits>
#include <optional>
#include <regex>

#include "core/util/error.h"
#include "core/volume/readers/header_text.h"
#include "core/volume/readers/stored_data.h"

namespace kdswap {
namespace {

struct NamedLayout {
  std::vector<std::int64_t> sizes;  // empty when the name has no WxHxD part
  std::string type;
};

//! The "_WxHxD_TYPE" at the end of the file name's stem, if present: W, H, D, TYPE as written.
std::optional<std::array<std::string, 4>> namePattern(const std::string& path) {
  static const std::regex pattern(R"(_(\d+)x(\d+)x(\d+)_([a-z0-9]+)$)", std::regex::icase);
  const std::string stem = std::filesystem::path(path).stem().string();
  std::smatch m;
  if (!std::regex_search(stem, m, pattern)) return std::nullopt;
  return std::array<std::string, 4>{m[1].str(), m[2].str(), m[3].str(), lowercase(m[4].str())};
}

//! The name's layout for opening: sizes beyond 64 bits are an error (others are checked later).
NamedLayout layoutFromName(const std::string& path) {
  NamedLayout named;
  const auto parts = namePattern(path);
  if (!parts) return named;
  for (int i = 0; i < 3; ++i) {
    const auto v = parseInteger((*parts)[i]);
    if (!v) throw Error(path + ": dimensions in the name overflow: expected sizes from 2 to 2147483647");
    named.sizes.push_back(*v);
  }
  named.type = (*parts)[3];
  return named;
}

//! What is missing and the ways to give it with the command at hand.
std::string missingLayout(bool noDims, bool noType, bool rawOptions) {
  const std::string types = "TYPE: " + scalarTypeList();
  const std::string name = "NAME_WxHxD_TYPE.raw, e.g. head_256x256x113_uint16.raw (" + types + ")";
  if (!rawOptions)  // a caller without --raw-* options (a library user; the desktop app gives the
                    // layout of a raw file from its data panel's fields)
    return std::string(noDims && noType ? "no dimensions and no sample type" : noDims ? "no dimensions" : "no sample type") +
           ": rename it " + name + ", or describe it with a .nhdr header";
  if (noDims && noType) return "give --raw-dims WxHxD and --raw-type TYPE, or name it " + name;
  if (noDims) return "--raw-dims WxHxD is missing (--raw-type alone is not enough)";
  return "--raw-type TYPE is missing (" + types + ")";
}

}  // namespace

bool isRawFile(const std::string& path) { return lowercase(std::filesystem::path(path).extension().string()) == ".raw"; }

RawLayout rawLayoutFromName(const std::string& path) {
  RawLayout layout;
  const auto parts = namePattern(path);
  if (!parts) return layout;
  glm::ivec3 dims;
  bool fits = true;
  for (int i = 0; i < 3; ++i) {
    const auto v = parseInteger((*parts)[i]);
    fits = fits && v && *v <= std::numeric_limits<int>::max();
    if (fits) dims[i] = int(*v);
  }
  if (fits) layout.dims = dims;
  layout.type = (*parts)[3];
  return layout;
}

bool RawReader::accepts(const std::string& path) const { return isRawFile(path); }

std::unique_ptr<VolumeSource> RawReader::open(const std::string& path, const RawLayout& layout) const {
  const NamedLayout named = layoutFromName(path);
  const bool noDims = !layout.dims && named.sizes.empty(), noType = !layout.type && named.type.empty();
  if (noDims || noType) throw Error(path + ": raw file layout unknown: " + missingLayout(noDims, noType, layout.rawOptions));
  VolumeInfo info;
  info.name = path;
  info.dims = layout.dims ? dimsFromSizes({layout.dims->x, layout.dims->y, layout.dims->z}, path, "dimensions")
                          : dimsFromSizes(named.sizes, path, "dimensions in the name");
  if (layout.spacing) {
    checkSpacing(info.dims, glm::dvec3(*layout.spacing), path, "spacing from the command line");
    info.spacing = *layout.spacing;
  }
  const std::string typeName = layout.type ? *layout.type : named.type;
  const auto type = parseScalarType(typeName);
  if (!type) throw Error(path + ": type \"" + typeName + "\": unsupported (expected one of " + scalarTypeList() + ")");

  StoredData data;
  data.path = path;
  data.type = *type;
  data.bigEndian = layout.bigEndian.value_or(false);
  data.offset = layout.headerBytes;
  return openStoredData(std::move(info), data);
}

}  // namespace kdswap
