// Front-to-back waves: a dependency graph over pieces of the bricks' screen rectangles (one
// cell of a screen grid each; a piece waits for the pieces in front that share a pixel with it),
// run as tasks that release their dependents.
#include "core/cluster/front_to_back_waves.h"

#include <algorithm>
#include <atomic>
#include <memory>
#include <mutex>

#include <oneapi/tbb/parallel_for_each.h>

#include "core/cluster/screen_piece_graph.h"
#include "core/render/front_transmittance.h"
#include "core/util/clock.h"
#include "core/util/error.h"

namespace kdswap {
namespace {

// Screen cells of the waves' pieces, in pixels: small enough that a brick's cell rarely waits for
// bricks in front that only touch its rectangle elsewhere, large enough that a piece's rays fill
// the caster's batches and the graph stays small (a 512^2 frame at P = 64: about 1500 pieces).
constexpr int kWaveCell = 32;

//! One brick's state shared by its pieces: its caster and image are made by the first piece to
//! run, and the last piece to finish counts the brick as rendered.
struct BrickInWaves {
  std::once_flag made;
  std::unique_ptr<RayCaster> caster;
  CellCoverage coverage;  //!< the pixels whose rays can meet the brick's visible cells
  std::atomic<int> piecesLeft{0};
};

}  // namespace

std::vector<RenderedBrick> renderInWaves(std::vector<NodeState>& nodes, const FramePlan& plan) {
  const std::vector<int>& order = plan.order.frontToBack;  // ranks, nearest brick first
  const std::size_t n = order.size();
  std::vector<RenderedBrick> rendered(nodes.size());
  std::vector<Rect> rects(n);
  for (std::size_t i = 0; i < n; ++i) rects[i] = ownBrickScreenRect(nodes[std::size_t(order[i])], plan);

  // waitsFor[j]: the ranks of the bricks nearer the eye whose rectangles meet brick j's, for the
  // modelled time (FrameStats::renderSpan: nodes of a real machine wait for whole bricks).
  // Pairs are compared once per frame: P^2 / 2 rectangle tests (~1 ms at 1024).
  std::vector<std::vector<int>> waitsFor(n);
  for (std::size_t j = 0; j < n; ++j)
    if (!rects[j].empty())
      for (std::size_t i = 0; i < j; ++i)
        if (!rects[i].intersect(rects[j]).empty()) waitsFor[j].push_back(order[i]);

  const ScreenPieceGraph graph(rects, plan.frame(), kWaveCell);
  const std::vector<ScreenPiece>& pieces = graph.pieces();
  std::unique_ptr<BrickInWaves[]> bricks(new BrickInWaves[n]);
  for (std::size_t i = 0; i < n; ++i) bricks[i].piecesLeft.store(graph.piecesOf(i), std::memory_order_relaxed);
  std::unique_ptr<std::atomic<int>[]> waiting(new std::atomic<int>[pieces.size()]);
  for (std::size_t p = 0; p < pieces.size(); ++p) waiting[p].store(graph.waitsFor(p), std::memory_order_relaxed);
  struct PieceTimes {
    RenderCounters counters;
    Rect content;  // its pixels with opacity above 0
    double start = 0.0, end = 0.0;
  };
  std::vector<PieceTimes> times(pieces.size());

  FrontTransmittance front(plan.frame());
  const double begin = nowSeconds();
  const std::vector<std::size_t> ready = graph.ready();
  tbb::parallel_for_each(ready.begin(), ready.end(), [&](std::size_t p, tbb::feeder<std::size_t>& feeder) {
    const ScreenPiece& piece = pieces[p];
    const std::size_t rank = std::size_t(order[piece.brick]);
    BrickInWaves& brick = bricks[piece.brick];
    times[p].start = nowSeconds();
    std::call_once(brick.made, [&] {
      brick.caster = ownBrickCaster(nodes[rank], plan, &front);
      brick.coverage = brick.caster->coverage(plan.camera);
      rendered[rank].image = Image(rects[piece.brick]);
    });
    // Dims `front` where it rendered (only pieces waiting for this one read those pixels).
    times[p].content =
        brick.caster->renderRegion(plan.camera, piece.rect, rendered[rank].image, times[p].counters, &brick.coverage);
    times[p].end = nowSeconds();
    if (brick.piecesLeft.fetch_sub(1, std::memory_order_acq_rel) == 1 && plan.nodesRendered)
      plan.nodesRendered->fetch_add(1, std::memory_order_relaxed);  // progress display
    // The last piece in front to finish releases the one behind; acq_rel orders every earlier
    // piece's writes to `front` before its reads.
    for (const std::size_t* q = graph.dependentsBegin(p); q != graph.dependentsEnd(p); ++q)
      if (waiting[*q].fetch_sub(1, std::memory_order_acq_rel) == 1) feeder.add(*q);
  });

  // Per brick: its pieces' counters summed and content bounds united, its time from its first
  // piece's start to its last's end.
  for (std::size_t i = 0; i < n; ++i) {
    RenderedBrick& r = rendered[std::size_t(order[i])];
    r.start = r.end = begin;
    r.renderedAfter = std::move(waitsFor[i]);
    if (graph.piecesOf(i) == 0 && plan.nodesRendered) plan.nodesRendered->fetch_add(1, std::memory_order_relaxed);
  }
  std::vector<bool> seen(n, false);
  for (std::size_t p = 0; p < pieces.size(); ++p) {
    const std::size_t i = pieces[p].brick;
    RenderedBrick& r = rendered[std::size_t(order[i])];
    const PieceTimes& t = times[p];
    r.start = seen[i] ? std::min(r.start, t.start) : t.start;
    r.end = seen[i] ? std::max(r.end, t.end) : t.end;
    seen[i] = true;
    r.content = r.content.unite(t.content);
    r.counters += t.counters;
  }
  return rendered;
}

void checkWavesWithBricksPerNode(bool waves, int bricksPerNode) {
  if (waves && bricksPerNode > 1)
    throw Error("--waves renders each node's one brick in visibility order: give --bricks-per-node 1 (over-decomposed "
                "bricks are handed out on demand and keep the occlusion map)");
}

}  // namespace kdswap
