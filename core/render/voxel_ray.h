// VoxelRay: a camera ray as the ray caster walks it, in voxel coordinates with its sample lattice.
// Every brick, and the occlusion map, derive it from the same Ray by this one definition, so they
// agree on which lattice index k a sample has.
#pragma once

#include <algorithm>

#include <glm/vec3.hpp>

#include "core/camera/camera.h"
#include "core/render/render_settings.h"

namespace kdswap {

//! A ray's lattice phase in [0, 1): its pixel's offset (0 without jitter) plus the frame's shift,
//! wrapped. The SIMD ray setup repeats these two operations.
inline float latticePhase(float offset, float shift) {
  const float sum = offset + shift;
  return sum >= 1.0f ? sum - 1.0f : sum;
}

//! Pass `pass`'s phase shift: the fractional part of pass times the golden ratio's conjugate (the
//! R1 sequence), so the first n passes of any n spread their lattices evenly over one step. Pass 0
//! is unshifted, so a single pass is the ordinary frame.
inline float latticePassShift(int pass) {
  const double shift = double(pass) * 0.6180339887498949;
  return float(shift - double(long(shift)));
}

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
    float phaseShift;
    Scale(const glm::vec3& spacing, const RenderSettings& settings)
        : inverseSpacing(1.0f / spacing),
          step(worldStep(spacing, settings)),
          inverseStep(1.0f / step),
          jitter(settings.jitter),
          phaseShift(settings.phaseShift) {}
  };

  VoxelRay(const Ray& ray, const Scale& scale)
      : origin(ray.origin * scale.inverseSpacing),
        direction(ray.direction * scale.inverseSpacing),
        step(scale.step),
        phase(latticePhase(scale.jitter ? ray.offset : 0.0f, scale.phaseShift)),
        inverseStep(scale.inverseStep) {}
  VoxelRay(const Ray& ray, const glm::vec3& spacing, const RenderSettings& settings)
      : VoxelRay(ray, Scale(spacing, settings)) {}

  //! Sample spacing along world rays: stepVoxels times the smallest voxel spacing.
  static float worldStep(const glm::vec3& spacing, const RenderSettings& settings) {
    return settings.stepVoxels * std::min({spacing.x, spacing.y, spacing.z});
  }
};

}  // namespace kdswap
