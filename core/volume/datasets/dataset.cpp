// The registry of built-in data sets: the only list of them.
#include "core/volume/datasets/dataset.h"

#include <algorithm>
#include <functional>
#include <map>
#include <optional>

#include "core/util/error.h"
#include "core/util/text_items.h"
#include "core/volume/datasets/phantom.h"
#include "core/volume/datasets/turbulence.h"
#include "core/volume/datasets/vessels.h"

namespace kdswap {
namespace {

using Factory = std::function<std::unique_ptr<VolumeSource>(const glm::ivec3&)>;

struct Entry {
  Factory make;
  glm::ivec3 defaultDims;
};

const std::map<std::string, Entry>& registry() {
  static const std::map<std::string, Entry> entries = {
      {"phantom", {makePhantom, glm::ivec3(128)}},
      {"vessels", {makeVessels, glm::ivec3(128)}},
      {"turbulence", {makeTurbulence, glm::ivec3(128)}},
  };
  return entries;
}

glm::ivec3 parseSize(const std::string& text, const std::string& spec) {
  std::vector<std::int64_t> parts;
  for (const std::string& item : splitItems(text, 'x')) {
    const std::optional<std::int64_t> v = parseWholeNumber(item);
    if (!v) throw Error("data set \"" + spec + "\": size \"" + text + "\" is not N or WxHxD");
    parts.push_back(*v);
  }
  if (parts.size() == 1) parts = {parts[0], parts[0], parts[0]};
  if (parts.size() != 3) throw Error("data set \"" + spec + "\": size \"" + text + "\" is not N or WxHxD");
  for (std::int64_t v : parts)
    if (v < 2 || v > 8192)
      throw Error("data set \"" + spec + "\": each size must be between 2 and 8192 voxels");
  return glm::ivec3(int(parts[0]), int(parts[1]), int(parts[2]));
}

}  // namespace

std::vector<std::string> datasetNames() {
  std::vector<std::string> names;
  for (const auto& [name, entry] : registry()) names.push_back(name);
  return names;
}

std::string datasetNameList() {
  std::string list;
  for (const std::string& n : datasetNames()) list += (list.empty() ? "" : ", ") + n;
  return list;
}

bool isDatasetSpec(const std::string& spec) {
  const std::vector<std::string> names = datasetNames();
  return std::find(names.begin(), names.end(), spec.substr(0, spec.find(':'))) != names.end();
}

std::unique_ptr<VolumeSource> openDataset(const std::string& spec) {
  const std::size_t colon = spec.find(':');
  const std::string name = spec.substr(0, colon);
  auto it = registry().find(name);
  if (it == registry().end()) {
    throw Error("data set \"" + name + "\": unknown (built-in data sets: " + datasetNameList() + ")");
  }
  const glm::ivec3 dims = colon == std::string::npos ? it->second.defaultDims : parseSize(spec.substr(colon + 1), spec);
  auto source = it->second.make(dims);
  return source;
}

}  // namespace kdswap
