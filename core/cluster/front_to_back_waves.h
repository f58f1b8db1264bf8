// Front-to-back waves (RenderSettings::frontToBackWaves): every node's brick rendered while the
// nodes wait for it (each starts compositing as soon as its own brick is done, while bricks
// behind still render), each brick's pixels after those of the bricks in front of it, so it reads, at
// each of its pixels, the light those bricks left (FrontTransmittance). Bricks render in pieces,
// one screen cell each (ScreenPieceGraph): pieces that share no pixel render at once; a pixel's
// bricks render it one after another, nearest first, so its transmittance is multiplied in the
// same order every frame (the same image bits).
#pragma once

#include <functional>
#include <vector>

#include "core/cluster/frame_request.h"
#include "core/cluster/node_program.h"

namespace kdswap {

//! Renders nodes[rank]'s brick for every rank of plan.order, on the current arena's threads, into
//! rendered[rank] (one per node): its image, counters and the ranks it rendered after. Calls
//! brickDone(rank) once per rank, as soon as that brick is complete (at once for a brick that
//! covers no pixel), from the thread that completed it; rendered[rank] is final by then.
void renderInWaves(std::vector<NodeState>& nodes, const FramePlan& plan, std::vector<RenderedBrick>& rendered,
                   const std::function<void(int rank)>& brickDone);

//! Waves render each node's one brick: with over-decomposition (bricksPerNode > 1, bricks handed
//! out on demand) the cluster keeps the occlusion map instead, so the command line and the GUI
//! refuse the pair with this check's one-line error rather than ignore --waves.
void checkWavesWithBricksPerNode(bool waves, int bricksPerNode);

}  // namespace kdswap
