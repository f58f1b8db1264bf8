// The node program (SPMD): the same code runs on every virtual node, and on every MPI rank.
// A node receives its brick once, then per frame renders its brick, composites with the chosen
// strategy and sends its finished tile to the host. It touches only its own NodeState.
#pragma once

#include <map>
#include <memory>
#include <vector>

#include "core/cluster/frame_request.h"
#include "core/cluster/phase_record.h"
#include "core/comm/communicator.h"
#include "core/metrics/node_report.h"
#include "core/render/empty_space_cache.h"
#include "core/render/ray_caster.h"
#include "core/volume/brick.h"

namespace kdswap {

//! Message tags of the host/node protocol.
inline constexpr int kBrickTag = 10;
inline constexpr int kTileTag = 11;
inline constexpr int kPieceImageTag = 12;  //!< over-decomposition: a brick's image sent to its home
inline constexpr int kBrickRenderedTag = 13;  //!< front-to-back waves: host -> node, its brick is rendered

//! One node's private memory, alive across frames: the data, once distributed, is left intact.
struct NodeState {
  int rank = -1;
  Brick brick;
  //! Over-decomposition: sub-bricks by global brick number, its own ones and those shipped to it
  //! to render (kept for later frames, so a brick travels to a node once).
  std::map<int, Brick> pieces;
  //! Each brick's empty-space map, kept while the transfer function's visible entries stay
  //! (cleared when the brick is received again).
  EmptySpaceCache brickEmptySpace;
  std::map<int, EmptySpaceCache> pieceEmptySpace;
};

//! A brick message: the voxels of Brick::storedBoxFor(owned, dims), with `piece` >= 0 for an
//! over-decomposed sub-brick (its global number), -1 for a node's one brick. `storage` travels
//! with it, so every node stores the volume's voxels alike.
Message brickMessage(const VoxelBox& owned, const glm::ivec3& dims, const glm::vec3& spacing,
                     const VoxelStorage& storage, std::vector<float> storedValues, int piece = -1);

//! Receives one brick message (from the host, or `source`) and builds its gradients in the node's
//! own memory: node.brick, or node.pieces[piece] for a sub-brick.
void receiveBrick(NodeState& node, Communicator& comm, int source = Communicator::kHost);

//! A node's brick rendered for one frame, with its counters and when it was rendered.
struct RenderedBrick {
  Image image;
  Rect content;  //!< image.opaqueBounds(), found while rendering
  RenderCounters counters;
  double start = 0.0, end = 0.0;
  std::vector<int> renderedAfter;  //!< waves: the ranks in front of this brick (NodeReport::renderedAfter)
};

//! Renders the node's own brick for `plan` (with its occlusion map, if any). The node's first step
//! each frame, except in front-to-back waves, where the cluster renders every brick in visibility
//! order (renderInWaves) and the node waits for the message that its brick is done.
RenderedBrick renderOwnBrick(NodeState& node, const FramePlan& plan, FrontTransmittance* front = nullptr);

//! The caster renderOwnBrick uses: waves make it once a frame and render the brick one screen
//! cell at a time with it (RayCaster::renderRegion). It keeps references to node and plan.
std::unique_ptr<RayCaster> ownBrickCaster(NodeState& node, const FramePlan& plan, FrontTransmittance* front);

//! The screen rectangle renderOwnBrick's image will cover (RayCaster::screenRect of the node's brick).
Rect ownBrickScreenRect(NodeState& node, const FramePlan& plan);

//! Renders and composites one frame; sends the tile to the host. With `record` non-null, fills
//! record->cells[rank] (this node's row only).
NodeReport runNodeFrame(NodeState& node, Communicator& comm, const FramePlan& plan, PhaseRecord* record);

}  // namespace kdswap
