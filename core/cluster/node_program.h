// The node program (SPMD): the same code runs on every virtual node, and on every MPI rank.
// A node receives its brick once, then per frame renders its brick, composites with the chosen
// strategy and sends its finished tile to the host. It touches only its own NodeState.
#pragma once

#include "core/cluster/frame_request.h"
#include "core/cluster/phase_record.h"
#include "core/comm/communicator.h"
#include "core/metrics/node_report.h"
#include "core/volume/brick.h"

namespace kdswap {

//! Message tags of the host/node protocol.
inline constexpr int kBrickTag = 10;
inline constexpr int kTileTag = 11;

//! One node's private memory, alive across frames: the data, once distributed, is left intact.
struct NodeState {
  int rank = -1;
  Brick brick;
};

//! Receives this node's brick from the host and builds its gradients (node's own memory).
void receiveBrick(NodeState& node, Communicator& comm);

//! Renders and composites one frame; sends the tile to the host. With `record` non-null, fills
//! record->cells[rank] (this node's row only).
NodeReport runNodeFrame(NodeState& node, Communicator& comm, const FramePlan& plan, PhaseRecord* record);

}  // namespace kdswap
