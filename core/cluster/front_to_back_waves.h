// Front-to-back waves (RenderSettings::frontToBackWaves): every node's brick rendered before the
// nodes composite, each brick's pixels after those of the bricks in front of it, so it reads, at
// each of its pixels, the light those bricks left (FrontTransmittance). Bricks render in pieces,
// one screen cell each (ScreenPieceGraph): pieces that share no pixel render at once; a pixel's
// bricks render it one after another, nearest first, so its transmittance is multiplied in the
// same order every frame (the same image bits).
#pragma once

#include <vector>

#include "core/cluster/frame_request.h"
#include "core/cluster/node_program.h"

namespace kdswap {

//! Renders nodes[rank]'s brick for every rank of plan.order, on the current arena's threads;
//! result[rank] is its image and counters.
std::vector<RenderedBrick> renderInWaves(std::vector<NodeState>& nodes, const FramePlan& plan);

//! Waves render each node's one brick: with over-decomposition (bricksPerNode > 1, bricks handed
//! out on demand) the cluster keeps the occlusion map instead, so the command line and the GUI
//! refuse the pair with this check's one-line error rather than ignore --waves.
void checkWavesWithBricksPerNode(bool waves, int bricksPerNode);

}  // namespace kdswap
