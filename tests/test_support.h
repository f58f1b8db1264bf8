// Helpers shared by the test suites: small volumes, reference renders, reproduce lines.
#pragma once

#include <cmath>

#include <glm/geometric.hpp>
#include <functional>
#include <memory>
#include <random>
#include <string>

#include "core/cluster/virtual_cluster.h"
#include "core/render/reference_render.h"
#include "core/transfer/transfer_function.h"
#include "core/volume/memory_volume.h"

namespace kdswap::test {

//! A volume whose voxel (x, y, z) is f(x, y, z).
inline std::unique_ptr<MemoryVolume> makeVolume(glm::ivec3 dims, const std::function<float(int, int, int)>& f,
                                                glm::vec3 spacing = glm::vec3(1.0f)) {
  std::vector<float> v(std::size_t(dims.x) * dims.y * dims.z);
  for (int z = 0; z < dims.z; ++z)
    for (int y = 0; y < dims.y; ++y)
      for (int x = 0; x < dims.x; ++x) v[(std::size_t(z) * dims.y + y) * dims.x + x] = f(x, y, z);
  VolumeInfo info;
  info.dims = dims;
  info.spacing = spacing;
  info.name = "test volume";
  return std::make_unique<MemoryVolume>(info, std::move(v));
}

//! The brick owning `owned` of `source`, with its replicated and ghost layers read from it.
//! `cellShift` as Brick's (kCellShiftByVolume: by the volume's size).
inline Brick brickOf(const VolumeSource& source, const VoxelBox& owned, int cellShift = Brick::kCellShiftByVolume,
                     VoxelChoice voxels = VoxelChoice::Auto) {
  const VoxelBox stored = Brick::storedBoxFor(owned, source.info().dims);
  std::vector<float> raw(std::size_t(stored.count()));
  source.read(stored, raw.data());
  return Brick(owned, source.info().dims, source.info().spacing, std::move(raw), Brick::Shipping::No, cellShift,
               VoxelStorage::forVolume(source.info(), voxels));
}

//! A smooth blobby volume with structure at every scale the tests use.
inline std::unique_ptr<MemoryVolume> makeBlobs(glm::ivec3 dims, glm::vec3 spacing = glm::vec3(1.0f)) {
  return makeVolume(
      dims,
      [dims](int x, int y, int z) {
        const float u = float(x) / float(dims.x - 1), v = float(y) / float(dims.y - 1), w = float(z) / float(dims.z - 1);
        const float r = std::sqrt((u - 0.5f) * (u - 0.5f) + (v - 0.5f) * (v - 0.5f) + (w - 0.5f) * (w - 0.5f));
        const float ripple = 0.5f + 0.5f * std::sin(9.0f * u + 4.0f * v) * std::cos(7.0f * w - 3.0f * u);
        return std::max(0.0f, 1.0f - 2.0f * r) * ripple;
      },
      spacing);
}

//! A colourful, moderately opaque transfer function that exercises colour and opacity.
inline TransferFunction testTransfer() {
  return TransferFunction({{0.0f, {0.1f, 0.2f, 0.9f}}, {0.4f, {0.9f, 0.5f, 0.1f}}, {1.0f, {1.0f, 1.0f, 0.8f}}},
                          {{0.0f, 0.0f}, {0.05f, 0.0f}, {0.3f, 0.08f}, {0.6f, 0.3f}, {1.0f, 0.7f}}, "test");
}

//! The largest channel difference between `image` and the single-node reference render of
//! `request` (the whole of `volume` as one brick): the central invariant, distributed == single.
//! Returned, not checked, so the CHECK, its tolerance and its message stay at the call site.
inline float diffAgainstReference(const VolumeSource& volume, const FrameRequest& request, const Image& image) {
  const ReferenceResult ref = renderReference(wholeVolumeBrick(volume), request.view, request.width, request.height,
                                              request.transfer, request.settings,
                                              resolveValueRange(request.settings, volume.info()));
  return maxAbsDifference(image, ref.image, ref.image.rect());
}

inline std::string reproduce(int nodes, const std::string& strategy, const std::string& partition, int w, int h,
                             const View& v) {
  return "kdswap render --dataset <test volume> --nodes " + std::to_string(nodes) + " --composite " + strategy +
         " --partition " + partition + " --size " + std::to_string(w) + "x" + std::to_string(h) + " --view " +
         std::to_string(v.azimuthDeg) + "," + std::to_string(v.elevationDeg) + " --projection " +
         toString(v.projection) + " --ert 1 --verify";
}

//! `count` orbit views at random azimuth, elevation (within 80 degrees of the horizon) and
//! distance, alternately perspective and orthographic.
inline std::vector<View> randomViews(std::mt19937& rng, int count) {
  std::uniform_real_distribution<float> az(-180.0f, 180.0f), el(-80.0f, 80.0f), dist(1.8f, 4.0f);
  std::vector<View> views;
  for (int i = 0; i < count; ++i) {
    View v;
    v.azimuthDeg = az(rng);
    v.elevationDeg = el(rng);
    v.distance = dist(rng);
    v.projection = i % 2 ? Projection::Orthographic : Projection::Perspective;
    views.push_back(v);
  }
  return views;
}

}  // namespace kdswap::test
