// Averaged passes on shifted lattices: one renderFrame per pass, a running sum of the images.
#include "core/cluster/lattice_passes.h"

#include <algorithm>

#include "core/render/reference_render.h"
#include "core/render/voxel_ray.h"

namespace kdswap {

PassesResult renderPasses(VirtualCluster& cluster, const FrameRequest& request, int passes,
                          const PassObserver& afterPass) {
  PassesResult out;
  const int asked = std::max(1, passes);
  // One pass needs no sum: its image is the frame (the desktop app's previews come this way).
  ImageAverage average(asked > 1 ? Rect{0, 0, request.width, request.height} : Rect{});
  out.passes = 0;
  for (int pass = 0; pass < asked; ++pass) {
    FrameRequest shifted = request;
    shifted.settings.phaseShift = latticePassShift(pass);
    shifted.recordPhases = request.recordPhases && pass == 0;  // the stages are the first pass's
    FrameResult result = cluster.renderFrame(shifted);
    out.wallSeconds += result.stats.wallSeconds;
    ++out.passes;
    if (asked > 1) average.add(result.image);
    const bool goOn = !afterPass || afterPass(pass, result, average);
    if (pass == 0) out.frame = std::move(result);
    if (!goOn) break;
  }
  if (asked > 1) out.frame.image = average.mean();
  return out;
}

Image referencePasses(const Brick& whole, const FrameRequest& request, glm::vec2 valueRange, int passes) {
  const int asked = std::max(1, passes);
  ImageAverage average(Rect{0, 0, request.width, request.height});
  for (int pass = 0; pass < asked; ++pass) {
    RenderSettings settings = request.settings;
    settings.phaseShift = latticePassShift(pass);
    Image image = renderReference(whole, request.view, request.width, request.height, request.transfer, settings,
                                  valueRange)
                      .image;
    if (asked == 1) return image;
    average.add(image);
  }
  return average.mean();
}

}  // namespace kdswap
