// The 3D Shepp-Logan head phantom (Kak & Slaney; "modified" intensities), a stand-in for the
// paper's CT head: a bright skull shell around dim tissue, much empty space around it.
#pragma once

#include <memory>

#include <glm/vec3.hpp>

#include "core/volume/volume_source.h"

namespace kdswap {

std::unique_ptr<VolumeSource> makePhantom(const glm::ivec3& dims);

}  // namespace kdswap
