// Averaged passes on shifted lattices: one renderFrame per pass, a running sum of the images.
#include "core/cluster/lattice_passes.h"

#include "core/image/image_average.h"
#include "core/render/voxel_ray.h"

namespace kdswap {

PassesResult renderPasses(VirtualCluster& cluster, const FrameRequest& request, int passes,
                          const std::function<void()>& passDone) {
  PassesResult out;
  out.passes = std::max(1, passes);
  ImageAverage average(Rect{0, 0, request.width, request.height});
  for (int pass = 0; pass < out.passes; ++pass) {
    FrameRequest shifted = request;
    shifted.settings.phaseShift = latticePassShift(pass);
    shifted.recordPhases = request.recordPhases && pass == 0;  // the stages are the first pass's
    FrameResult result = cluster.renderFrame(shifted);
    out.wallSeconds += result.stats.wallSeconds;
    if (out.passes > 1) average.add(result.image);
    if (pass == 0) out.frame = std::move(result);
    if (passDone) passDone();
  }
  if (out.passes > 1) out.frame.image = average.mean();
  return out;
}

}  // namespace kdswap
