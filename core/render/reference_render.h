// The single-node reference: the whole volume as one brick, rendered by the same RayCaster. Every
// distributed image is checked against this (the central invariant).
#pragma once

#include "core/camera/view.h"
#include "core/image/image.h"
#include "core/render/ray_caster.h"
#include "core/transfer/transfer_function.h"
#include "core/volume/volume_source.h"

namespace kdswap {

struct ReferenceResult {
  Image image;  //!< full frame
  RenderCounters counters;
  double wallSeconds = 0.0;
};

//! The brick that owns the whole domain of `source` (reads every voxel).
//! `cellShift` as Brick's (kCellShiftByVolume: by the volume's size).
Brick wholeVolumeBrick(const VolumeSource& source, int cellShift = Brick::kCellShiftByVolume,
                       VoxelChoice voxels = VoxelChoice::Auto);

ReferenceResult renderReference(const Brick& whole, const View& view, int width, int height,
                                const TransferFunction& tf, const RenderSettings& settings, glm::vec2 valueRange);

//! The range mapped to [0, 1]: the user's if given, else the volume's.
glm::vec2 resolveValueRange(const RenderSettings& settings, const VolumeInfo& info);

}  // namespace kdswap
