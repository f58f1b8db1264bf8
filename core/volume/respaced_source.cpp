// A volume source with its spacing replaced.
#include "core/volume/respaced_source.h"

#include <cmath>
#include <cstdio>

#include "core/util/error.h"

namespace kdswap {
namespace {

bool validSpacing(const glm::vec3& s) {
  for (int a = 0; a < 3; ++a)
    if (!(std::isfinite(s[a]) && s[a] > 0.0f)) return false;
  return true;
}

}  // namespace

RespacedSource::RespacedSource(std::unique_ptr<VolumeSource> inner, const glm::vec3& spacing)
    : inner_(std::move(inner)), info_(inner_->info()) {
  if (!validSpacing(spacing)) throw Error(info_.name + ": spacing must be three finite numbers > 0");
  info_.spacing = spacing;
}

glm::vec3 parseSpacing(const std::string& text, const std::string& option) {
  glm::vec3 s(0.0f);
  char extra = 0;
  if (std::sscanf(text.c_str(), "%f,%f,%f%c", &s.x, &s.y, &s.z, &extra) != 3 || !validSpacing(s))
    throw Error(option + " \"" + text + "\": expected SX,SY,SZ, each a finite number > 0");
  return s;
}

}  // namespace kdswap
