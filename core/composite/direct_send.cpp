// Direct-send compositing (Hsu 1993; Neumann 1994); any P, any partition, one round.
//
// The frame is cut into P near-square tiles, one per node. Every node sends every other node the
// part of its partial image over that node's tile, then composites the P pieces of its own tile
// in the front-to-back order of the view. Only the visibility order of single bricks is used, so
// the k-d tree's shape does not matter. The price is P * (P - 1) messages per frame, most of them
// small: the reason binary swap and radix-k exist.
//
// Tiles that are empty (more nodes than pixels) are known to every node, so nobody sends to them;
// every other tile receives exactly one message from every other node, empty or not, since its
// owner cannot know in advance which partial images miss it.
#include "core/composite/direct_send.h"

#include <algorithm>
#include <cmath>

#include "core/composite/image_message.h"
#include "core/composite/working_image.h"

namespace kdswap {
namespace {

constexpr int kDirectTag = 500;

//! Tile `index` of `count` near-square tiles of `frame`: rows of tiles whose number matches the
//! frame's aspect ratio, the first `count % rows` rows holding one tile more. Empty tiles appear
//! only when there are more tiles than pixels along a side.
Rect tileOf(const Rect& frame, int count, int index) {
  const double ideal = std::sqrt(double(count) * std::max(frame.h, 1) / std::max(frame.w, 1));
  const int rows = std::clamp(int(std::lround(ideal)), 1, std::max(1, std::min(count, frame.h)));
  const int perRow = count / rows, longRows = count % rows;
  // Rows 0 .. longRows-1 hold perRow + 1 tiles, the others perRow.
  const int inLongRows = longRows * (perRow + 1);
  const int row = index < inLongRows ? index / (perRow + 1) : longRows + (index - inLongRows) / perRow;
  const int column = index < inLongRows ? index % (perRow + 1) : (index - inLongRows) % perRow;
  const int columns = row < longRows ? perRow + 1 : perRow;
  const auto cut = [](int length, int part, int parts) { return int(std::int64_t(length) * part / parts); };
  Rect tile;
  tile.x = frame.x + cut(frame.w, column, columns);
  tile.w = frame.x + cut(frame.w, column + 1, columns) - tile.x;
  tile.y = frame.y + cut(frame.h, row, rows);
  tile.h = frame.y + cut(frame.h, row + 1, rows) - tile.y;
  return tile;
}

}  // namespace

Tile DirectSend::compose(Image partial, const Rect& frame, const VisibilityOrder& order, Communicator& comm,
                         PhaseObserver& phases) const {
  const int nodes = comm.size(), me = comm.rank();
  WorkingImage image(std::move(partial));
  const Rect mine = tileOf(frame, nodes, me);
  // The partner shown is the front-most node this one hears from, else the first it sends to.
  int partner = -1;
  for (int n : order.frontToBack)
    if (n != me && !mine.empty()) {
      partner = n;
      break;
    }
  if (partner < 0 && nodes > 1) partner = (me + 1) % nodes;
  phases.beginPhase("direct-send", partner);

  // Staggered start (me + 1, me + 2, ...) so that not every node sends to node 0 first.
  for (int step = 1; step < nodes; ++step) {
    const int dest = (me + step) % nodes;
    const Rect tile = tileOf(frame, nodes, dest);
    if (!tile.empty()) comm.send(dest, kDirectTag, image.lend(tile, options_.sparse));
  }

  // Every node's part of our tile, front to back, blended in one pass.
  std::int64_t pixels = 0;
  if (!mine.empty()) {
    std::vector<Message> received;
    std::vector<ImageView> layers;
    int self = -1;
    for (int n : order.frontToBack) {
      if (n == me) {
        self = int(layers.size());
        layers.push_back(image.view(mine));
      } else {
        received.push_back(comm.receive(n, kDirectTag));
        layers.push_back(viewOfMessage(received.back()));
      }
    }
    image.composeLayers(mine, layers, self, pixels);
  }
  phases.endPhase(mine, image.image(), pixels);
  return image.finish(mine);
}

}  // namespace kdswap
