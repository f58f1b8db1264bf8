// VoxelRay: a camera ray as the ray caster walks it, in voxel coordinates with its sample lattice.
// Every brick, and the occlusion map, derive it from the same Ray by this one definition, so they
// agree on which lattice index k a sample has.
#pragma once

#include <algorithm>

#include <glm/vec3.hpp>

#include "core/camera/camera.h"
#include "core/render/render_settings.h"

namespace kdswap {

struct VoxelRay {
  glm::vec3 origin;     //!< voxel coordinates
  glm::vec3 direction;  //!< voxel coordinates per unit of the world ray's t
  float step;           //!< t between samples: sample k sits at t = (k + phase) * step
  float phase;
  float inverseStep;    //!< 1 / step, for index estimates that a rounding either way cannot spoil

  //! What turns world rays into voxel rays for one volume and settings, computed once: a ray then
  //! costs multiplies only (three divisions per ray and brick were a large part of the setup).
  struct Scale {
    glm::vec3 inverseSpacing;
    float step, inverseStep;
    bool jitter;
    Scale(const glm::vec3& spacing, const RenderSettings& settings)
        : inverseSpacing(1.0f / spacing),
          step(worldStep(spacing, settings)),
          inverseStep(1.0f / step),
          jitter(settings.jitter) {}
  };

  VoxelRay(const Ray& ray, const Scale& scale)
      : origin(ray.origin * scale.inverseSpacing),
        direction(ray.direction * scale.inverseSpacing),
        step(scale.step),
        phase(scale.jitter ? ray.offset : 0.0f),
        inverseStep(scale.inverseStep) {}
  VoxelRay(const Ray& ray, const glm::vec3& spacing, const RenderSettings& settings)
      : VoxelRay(ray, Scale(spacing, settings)) {}

  //! Sample spacing along world rays: stepVoxels times the smallest voxel spacing.
  static float worldStep(const glm::vec3& spacing, const RenderSettings& settings) {
    return settings.stepVoxels * std::min({spacing.x, spacing.y, spacing.z});
  }
};

}  // namespace kdswap
