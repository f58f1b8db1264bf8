// Front-to-back waves: a dependency graph over pieces of the bricks' screen rectangles (one
// cell of a screen grid each; a piece waits for the pieces in front that share a pixel with it),
// run as tasks that release their dependents.
#include "core/cluster/front_to_back_waves.h"

#include <algorithm>
#include <atomic>
#include <functional>
#include <limits>
#include <memory>
#include <mutex>

#include <oneapi/tbb/parallel_for_each.h>

#include "core/cluster/screen_piece_graph.h"
#include "core/render/front_transmittance.h"
#include "core/util/check.h"
#include "core/util/clock.h"
#include "core/util/error.h"

namespace kdswap {
namespace {

// Screen cells of the waves' pieces, in pixels: small enough that a brick's cell rarely waits for
// bricks in front that only touch its rectangle elsewhere, large enough that a piece's rays fill
// the caster's batches and its set-up and scheduling stay small beside them (the phantom 256^3 at
// 512^2, P = 64: ~330 pieces a frame). With 32-pixel cells (~830 pieces there) the paper cell
// (turbulence 256^3, P = 512) with waves took 298 against 284 ms a frame.
constexpr int kWaveCell = 64;

//! One brick's state shared by its pieces: its caster and image are made by the first piece to
//! run, each piece adds its counters and bounds, and the last piece to finish hands the brick over.
struct BrickInWaves {
  std::once_flag made;
  std::unique_ptr<RayCaster> caster;
  CellCoverage coverage;  //!< the pixels whose rays can meet the brick's visible cells
  std::atomic<int> piecesLeft{0};
  std::mutex summing;  //!< guards the rest (pieces of a brick finish on different threads)
  RenderCounters counters;
  Rect content;  //!< its pixels with opacity above 0
  //! Its first piece's start and its last one's end (each brick with pieces has one at least).
  double start = std::numeric_limits<double>::infinity(), end = -std::numeric_limits<double>::infinity();
};

}  // namespace

void renderInWaves(std::vector<NodeState>& nodes, const FramePlan& plan, std::vector<RenderedBrick>& rendered,
                   const std::function<void(int rank)>& brickDone) {
  const std::vector<int>& order = plan.order.frontToBack;  // ranks, nearest brick first
  const std::size_t n = order.size();
  KDSWAP_CHECK_EQ(rendered.size(), nodes.size());
  std::vector<Rect> rects(n);
  for (std::size_t i = 0; i < n; ++i) rects[i] = ownBrickScreenRect(nodes[std::size_t(order[i])], plan);

  // renderedAfter: the ranks of the bricks nearer the eye whose rectangles meet brick j's, for the
  // modelled time (FrameStats::renderSpan: nodes of a real machine wait for whole bricks).
  // Pairs are compared once per frame: P^2 / 2 rectangle tests (~1 ms at 1024).
  for (std::size_t j = 0; j < n; ++j) {
    std::vector<int>& after = rendered[std::size_t(order[j])].renderedAfter;
    after.clear();
    if (!rects[j].empty())
      for (std::size_t i = 0; i < j; ++i)
        if (!rects[i].intersect(rects[j]).empty()) after.push_back(order[i]);
  }

  const ScreenPieceGraph graph(rects, plan.frame(), kWaveCell);
  const std::vector<ScreenPiece>& pieces = graph.pieces();
  std::unique_ptr<BrickInWaves[]> bricks(new BrickInWaves[n]);
  for (std::size_t i = 0; i < n; ++i) bricks[i].piecesLeft.store(graph.piecesOf(i), std::memory_order_relaxed);
  std::unique_ptr<std::atomic<int>[]> waiting(new std::atomic<int>[pieces.size()]);
  for (std::size_t p = 0; p < pieces.size(); ++p) waiting[p].store(graph.waitsFor(p), std::memory_order_relaxed);

  FrontTransmittance front(plan.frame());
  const double begin = nowSeconds();
  // A brick without pieces covers no pixel: done before the first piece starts.
  for (std::size_t i = 0; i < n; ++i)
    if (graph.piecesOf(i) == 0) {
      RenderedBrick& r = rendered[std::size_t(order[i])];
      r.start = r.end = begin;
      if (plan.nodesRendered) plan.nodesRendered->fetch_add(1, std::memory_order_relaxed);
      brickDone(order[i]);
    }
  const std::vector<std::size_t> ready = graph.ready();
  tbb::parallel_for_each(ready.begin(), ready.end(), [&](std::size_t p, tbb::feeder<std::size_t>& feeder) {
    const ScreenPiece& piece = pieces[p];
    const int rank = order[piece.brick];
    RenderedBrick& out = rendered[std::size_t(rank)];
    BrickInWaves& brick = bricks[piece.brick];
    const double start = nowSeconds();
    std::call_once(brick.made, [&] {
      brick.caster = ownBrickCaster(nodes[std::size_t(rank)], plan, &front);
      brick.coverage = brick.caster->coverage(plan.camera);
      out.image = Image(rects[piece.brick]);
    });
    // Dims `front` where it rendered (only pieces waiting for this one read those pixels).
    RenderCounters counters;
    const Rect content = brick.caster->renderRegion(plan.camera, piece.rect, out.image, counters, &brick.coverage);
    const double end = nowSeconds();
    {
      std::lock_guard<std::mutex> lock(brick.summing);
      brick.start = std::min(brick.start, start);
      brick.end = std::max(brick.end, end);
      brick.counters += counters;
      brick.content = brick.content.unite(content);
    }
    // The last piece in front to finish releases the one behind; acq_rel orders every earlier
    // piece's writes to `front` before its reads.
    for (const std::size_t* q = graph.dependentsBegin(p); q != graph.dependentsEnd(p); ++q)
      if (waiting[*q].fetch_sub(1, std::memory_order_acq_rel) == 1) feeder.add(*q);
    // The brick's last piece hands it to its node, which composites while other bricks render.
    if (brick.piecesLeft.fetch_sub(1, std::memory_order_acq_rel) == 1) {
      {
        std::lock_guard<std::mutex> lock(brick.summing);
        out.counters = brick.counters;
        out.content = brick.content;
        out.start = brick.start;
        out.end = brick.end;
      }
      if (plan.nodesRendered) plan.nodesRendered->fetch_add(1, std::memory_order_relaxed);  // progress display
      brickDone(rank);
    }
  });
}

void checkWavesWithBricksPerNode(bool waves, int bricksPerNode) {
  if (waves && bricksPerNode > 1)
    throw Error("--waves renders each node's one brick in visibility order: give --bricks-per-node 1 (over-decomposed "
                "bricks are handed out on demand and keep the occlusion map)");
}

}  // namespace kdswap
