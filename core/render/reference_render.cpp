// Single-node reference rendering.
#include "core/render/reference_render.h"

#include "core/util/clock.h"

namespace kdswap {

Brick wholeVolumeBrick(const VolumeSource& source, int cellShift, VoxelChoice voxels) {
  const VolumeInfo& info = source.info();
  const VoxelBox owned{glm::ivec3(0), info.dims - 1};
  const VoxelBox stored = Brick::storedBoxFor(owned, info.dims);
  std::vector<float> raw(std::size_t(stored.count()));
  source.read(stored, raw.data());
  return Brick(owned, info.dims, info.spacing, std::move(raw), Brick::Shipping::No, cellShift,
               VoxelStorage::forVolume(info, voxels));
}

glm::vec2 resolveValueRange(const RenderSettings& settings, const VolumeInfo& info) {
  return settings.valueRange.value_or(glm::vec2(info.minValue, info.maxValue));
}

ReferenceResult renderReference(const Brick& whole, const View& view, int width, int height,
                                const TransferFunction& tf, const RenderSettings& settings, glm::vec2 valueRange) {
  ReferenceResult result;
  const double start = nowSeconds();
  const Camera camera(view, glm::vec3(0.0f), glm::vec3(whole.volumeDims() - 1) * whole.spacing(), width, height);
  const TransferTable table(tf, settings.stepVoxels);
  const RayCaster caster(whole, table, settings, valueRange);
  Image partial = caster.render(camera, result.counters);
  result.image = partial.extendedTo(camera.frame());
  result.wallSeconds = nowSeconds() - start;
  return result;
}

}  // namespace kdswap
