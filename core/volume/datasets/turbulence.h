// "turbulence": a dense, smooth, vortical field standing in for the paper's CFD data: the
// vorticity magnitude of a random divergence-free velocity field.
#pragma once

#include <memory>

#include <glm/vec3.hpp>

#include "core/volume/volume_source.h"

namespace kdswap {

std::unique_ptr<VolumeSource> makeTurbulence(const glm::ivec3& dims);

}  // namespace kdswap
