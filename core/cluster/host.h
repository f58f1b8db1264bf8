// The host program of the paper's host/node model: the data distributor (reads the volume one
// brick at a time and sends each node its brick) and the image gatherer (assembles the tiles).
#pragma once

#include <vector>

#include "core/comm/communicator.h"
#include "core/image/image.h"
#include "core/partition/brick_layout.h"
#include "core/partition/kd_tree.h"
#include "core/volume/volume_source.h"
#include "core/volume/voxel_storage.h"

namespace kdswap {

//! Sends node r the voxels of its brick with the replicated layers. Only one brick's voxels are
//! held by the host at a time; for uncompressed files only that brick's bytes are read.
//! `storage`: how every node stores the volume's voxels (VoxelStorage::forVolume).
void distributeBricks(const VolumeSource& source, const KdTree& tree, const VoxelStorage& storage, Communicator& host);
//! Over-decomposition: sends every sub-brick to its home node, one brick in memory at a time.
void distributePieces(const VolumeSource& source, const BrickLayout& layout, const VoxelStorage& storage,
                      Communicator& host);

//! Assembles the final frame from the nodes' tile messages (one per node). Checks that the tiles'
//! regions partition the frame (every pixel comes from exactly one tile); throws kdswap::Error
//! naming the node otherwise. `regions` receives each node's region.
Image assembleTiles(std::vector<Message>& tiles, const Rect& frame, std::vector<Rect>* regions = nullptr);

}  // namespace kdswap
