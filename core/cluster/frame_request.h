// FrameRequest: what the host broadcasts to every node for one frame (view, image size,
// transfer function, render settings). FramePlan: what a node derives from it before rendering.
#pragma once

#include <atomic>
#include <string>

#include <glm/vec2.hpp>

#include "core/camera/camera.h"
#include "core/camera/view.h"
#include "core/cluster/brick_schedule.h"
#include "core/composite/strategy.h"
#include "core/partition/kd_tree.h"
#include "core/render/occlusion_map.h"
#include "core/render/render_settings.h"
#include "core/transfer/transfer_function.h"

namespace kdswap {

struct FrameRequest {
  View view;
  int width = 512, height = 512;
  TransferFunction transfer;
  RenderSettings settings;
  bool recordPhases = false;  //!< keep every node's image after each phase (Figure 6)
};

struct RenderedBrick;  // node_program.h

//! Immutable per-frame data every node computes identically from the request and the partition.
struct FramePlan {
  FramePlan(const FrameRequest& request, const KdTree& tree, const glm::vec3& spacing, glm::vec2 valueRange,
            const Strategy& strategy);

  const FrameRequest& request;
  Camera camera;
  TransferTable table;
  VisibilityOrder order;
  glm::vec2 valueRange;
  const Strategy& strategy;
  glm::vec3 spacing;
  const BrickSchedule* bricks = nullptr;  //!< over-decomposition: who renders which brick
  const OcclusionMap* occlusion = nullptr;  //!< cross-brick occlusion culling, when available
  //! When set, each node adds 1 as its render step ends (before compositing): a progress display
  //! on a long frame reads it while the nodes work.
  std::atomic<int>* nodesRendered = nullptr;
  //! Front-to-back waves: every rank's brick, rendered nearest first beside the nodes (a node takes
  //! its own once the host's kBrickRenderedTag message says it is done, then composites it); null
  //! when each node renders its own brick as its first step.
  std::vector<RenderedBrick>* waves = nullptr;
  Rect frame() const { return camera.frame(); }
};

}  // namespace kdswap
