// FramePlan construction: camera, step-corrected transfer table and the visibility order.
#include "core/cluster/frame_request.h"

namespace kdswap {

FramePlan::FramePlan(const FrameRequest& r, const KdTree& tree, const glm::vec3& spacing, glm::vec2 range,
                     const Strategy& s)
    : request(r),
      camera(r.view, glm::vec3(0.0f), glm::vec3(tree.dims() - 1) * spacing, r.width, r.height),
      table(r.transfer, r.settings.stepVoxels),
      order(tree.order(camera, spacing)),
      valueRange(range),
      strategy(s),
      spacing(spacing) {}

}  // namespace kdswap
