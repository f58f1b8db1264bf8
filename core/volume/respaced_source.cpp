// A volume source with its spacing replaced.
#include "core/volume/respaced_source.h"

#include <cmath>
#include <cstdio>

#include "core/util/error.h"

namespace kdswap {
namespace {

bool validSpacing(const glm::vec3& s) {
  for (int a = 0; a < 3; ++a)
    if (!(std::isfinite(s[a]) && s[a] >= float(kMinSpacing) && s[a] <= float(kMaxSpacing))) return false;
  return true;
}

}  // namespace

RespacedSource::RespacedSource(std::unique_ptr<VolumeSource> inner, const glm::vec3& spacing)
    : inner_(std::move(inner)), info_(inner_->info()) {
  char text[96];
  std::snprintf(text, sizeof text, "spacing %g %g %g (replacing the data's)", double(spacing.x), double(spacing.y),
                double(spacing.z));
  checkSpacing(info_.dims, glm::dvec3(spacing), info_.name, text);
  info_.spacing = spacing;
  checkValueRange(info_, info_.name);  // its gradient bound depends on the spacing
}

glm::vec3 parseSpacing(const std::string& text, const std::string& option) {
  glm::vec3 s(0.0f);
  char extra = 0;
  if (std::sscanf(text.c_str(), "%f,%f,%f%c", &s.x, &s.y, &s.z, &extra) != 3 || !validSpacing(s)) {
    char bounds[64];
    std::snprintf(bounds, sizeof bounds, "each a number from %g to %g", kMinSpacing, kMaxSpacing);
    throw Error(option + " \"" + text + "\": expected SX,SY,SZ, " + bounds);
  }
  return s;
}

}  // namespace kdswap
