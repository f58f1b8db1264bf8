// Shading of one sample (Levoy 1988): trilinear value and gradient, transfer function, Phong with
// the light at the eye. This is the reference arithmetic; the SIMD ray march (ray_march_avx2.cpp)
// does the same IEEE operations in the same order for eight samples at once, so both give the
// same bits.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstddef>

#include <glm/common.hpp>
#include <glm/geometric.hpp>
#include <glm/vec3.hpp>

#include "core/render/trilinear.h"
#include "core/transfer/transfer_function.h"

namespace kdswap {

constexpr int kSpecularEntries = 256;  //!< pow(x, shininess) is tabulated at x = i / kSpecularEntries

//! Constants of a brick's classification and shading (the light direction comes with each ray).
struct ShadingParameters {
  const TransferTable* table = nullptr;
  float scale = 1.0f, bias = 0.0f;  //!< normalised scalar = value * scale + bias
  bool shading = true;
  float ambient = 0.0f, diffuse = 0.0f, specular = 0.0f;
  const float* specularTable = nullptr;  //!< kSpecularEntries + 1 values
};

//! Colour (not premultiplied) and step-corrected opacity; colour is meaningful where a > 0.
struct ShadedSample {
  float r, g, b, a;
};

//! Shading of a sample whose value (lane 0) and gradient (lanes 1-3) are interpolated.
//! `toLight`: unit vector from the sample to the light.
inline ShadedSample shadeInterpolated(const ShadingParameters& params, const glm::vec3& toLight,
                                      const TrilinearCell::Lanes& both) {
  const glm::vec4 tf = params.table->lookup(both[0] * params.scale + params.bias);
  if (tf.a <= 0.0f || !params.shading) return ShadedSample{tf.r, tf.g, tf.b, tf.a};
  const glm::vec3 grad(both[1], both[2], both[3]);
  const float len2 = glm::dot(grad, grad);
  float lambert = 1.0f;  // no gradient (flat region): lit as if facing the light
  if (len2 > 0.0f) lambert = std::fabs(glm::dot(grad, toLight)) / std::sqrt(len2);
  const float fs = std::min(lambert, 1.0f) * float(kSpecularEntries);
  const int is = std::min(int(fs), kSpecularEntries - 1);
  const float* specular = params.specularTable;
  const float highlight = params.specular * (specular[is] + (fs - float(is)) * (specular[is + 1] - specular[is]));
  const glm::vec3 colour =
      glm::min(glm::vec3(tf.r, tf.g, tf.b) * (params.ambient + params.diffuse * lambert) + highlight, glm::vec3(1.0f));
  return ShadedSample{colour.r, colour.g, colour.b, tf.a};
}

//! Sample at p (voxel coordinates, inside the brick's owned box; floor = (int) p), float storage.
inline ShadedSample shadeSample(const ShadingParameters& params, const glm::vec3& toLight,
                                const VoxelAddressing& voxels, const glm::vec3& p, const glm::ivec3& floor) {
  return shadeInterpolated(params, toLight, TrilinearCell(voxels, p, floor).interpolate());
}

//! The same for compact storage (params' scale and bias then map stored values, see RayCaster).
inline ShadedSample shadeCompactSample(const ShadingParameters& params, const glm::vec3& toLight,
                                       const VoxelAddressing& voxels, const glm::vec3& p, const glm::ivec3& floor) {
  return shadeInterpolated(params, toLight, interpolateCompact(voxels, p, floor));
}

}  // namespace kdswap
