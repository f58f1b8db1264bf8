// Sequential (pipelined) compositing along the front-to-back order; any P. Only one node works
// at a time, which is why the paper uses it as a baseline.
#include "core/composite/sequential.h"

#include "core/composite/image_message.h"

namespace kdswap {
namespace {

constexpr int kChainTag = 400;

}  // namespace

Tile Sequential::compose(Image image, const Rect& frame, const VisibilityOrder& order, Communicator& comm,
                         PhaseObserver& phases) const {
  const int nodes = comm.size(), me = comm.rank();
  const int position = order.position[me];
  const int previous = position > 0 ? order.frontToBack[position - 1] : -1;
  const int next = position + 1 < nodes ? order.frontToBack[position + 1] : -1;
  phases.beginPhase("chain", previous >= 0 ? previous : next);
  std::int64_t pixels = 0;
  if (previous >= 0) {
    // Everything received lies in front of this node's brick.
    Message in = comm.receive(previous, kChainTag);
    image = mergeImages(std::move(image), imageFromMessage(in), true, pixels);
  }
  if (next >= 0) {
    comm.send(next, kChainTag, imageToMessage(options_.sparse ? trimToContent(std::move(image)) : std::move(image)));
    phases.endPhase(Rect{}, Image{}, pixels);
    return Tile{};
  }
  Image finished = image.crop(frame);
  phases.endPhase(frame, finished, pixels);
  return Tile::owning(frame, std::move(finished));
}

}  // namespace kdswap
