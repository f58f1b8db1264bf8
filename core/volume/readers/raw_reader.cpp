// Raw volume files: layout from RawLayout, else from the name pattern NAME_WxHxD_TYPE.raw.
#include "core/volume/readers/raw_reader.h"

#include <filesystem>
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

//! Reads "_WxHxD_TYPE" at the end of the file name's stem, if present.
NamedLayout layoutFromName(const std::string& path) {
  static const std::regex pattern(R"(_(\d+)x(\d+)x(\d+)_([a-z0-9]+)$)", std::regex::icase);
  const std::string stem = std::filesystem::path(path).stem().string();
  std::smatch m;
  NamedLayout named;
  if (!std::regex_search(stem, m, pattern)) return named;
  for (int i = 1; i <= 3; ++i) {
    const auto v = parseInteger(m[i].str());
    if (!v) throw Error(path + ": dimensions in the name overflow: expected sizes from 2 to 2147483647");
    named.sizes.push_back(*v);
  }
  named.type = lowercase(m[4].str());
  return named;
}

//! What is missing and the ways to give it with the command at hand.
std::string missingLayout(bool noDims, bool noType, bool rawOptions) {
  const std::string types = "TYPE: " + scalarTypeList();
  const std::string name = "NAME_WxHxD_TYPE.raw, e.g. head_256x256x113_uint16.raw (" + types + ")";
  if (!rawOptions)  // a file opened in the desktop app's panel: no --raw-* options there
    return std::string(noDims && noType ? "no dimensions and no sample type" : noDims ? "no dimensions" : "no sample type") +
           ": rename it " + name + ", or describe it with a .nhdr header";
  if (noDims && noType) return "give --raw-dims WxHxD and --raw-type TYPE, or name it " + name;
  if (noDims) return "--raw-dims WxHxD is missing (--raw-type alone is not enough)";
  return "--raw-type TYPE is missing (" + types + ")";
}

}  // namespace

bool RawReader::accepts(const std::string& path) const {
  return lowercase(std::filesystem::path(path).extension().string()) == ".raw";
}

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
