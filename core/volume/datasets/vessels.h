// "vessels": a synthetic MR angiogram, a branching tree of tubes with a smooth intensity profile
// in a dark background: thin, sparse structures, the paper's MRA data in kind.
#pragma once

#include <memory>

#include <glm/vec3.hpp>

#include "core/volume/volume_source.h"

namespace kdswap {

std::unique_ptr<VolumeSource> makeVessels(const glm::ivec3& dims);

}  // namespace kdswap
