// FrameStats: one frame's figures, aggregated the way the paper reports them (maximum over
// nodes), plus the modelled parallel time: the render span + sum over phases of the max composite
// time, as if every virtual node had its own processor (behind the paper's Figures 7 and 8), of
// its modelled speed, with each phase's messages costed by the network model (zero when ideal).
// The render span is the max render for independent nodes; in front-to-back waves a node starts
// only when the nodes it waited for have finished, so the span is the longest such chain.
#pragma once

#include <string>
#include <vector>

#include <nlohmann/json_fwd.hpp>

#include "core/metrics/network_model.h"
#include "core/metrics/node_report.h"

namespace kdswap {

struct FrameStats {
  int nodes = 0;
  int width = 0, height = 0;
  std::string strategy, partition;
  double wallSeconds = 0;        //!< whole frame as measured, host to host
  double distributeSeconds = 0;  //!< data distribution (once per cluster), paper Table 5
  double gatherSeconds = 0;      //!< image gather on the host for this frame
  //! The occlusion map computed before the nodes render (part of wallSeconds; 0 without one).
  double occlusionMapSeconds = 0;
  std::uint64_t peakRssBytes = 0;
  NetworkModel network;          //!< costs messages in the modelled time
  //! Each node's report; where timed, its start and end times are seconds since the frame's
  //! start (the host starting the frame, the origin of wallSeconds).
  std::vector<NodeReport> perNode;

  double renderMax() const;      //!< max over nodes of render work / node speed
  double compositeMax() const;   //!< max over nodes of compositing work / node speed
  double renderMean() const;     //!< mean over nodes of render work / node speed
  //! Modelled time until the last node's render ends: renderMax() for independent nodes; with
  //! waves (NodeReport::renderedAfter) the longest chain of renders that waited for each other.
  double renderSpan() const;
  double modelledCommSeconds() const;  //!< sum over phases of the network model's phase time
  double modelledParallelSeconds() const;
  std::uint64_t samples() const;
  std::uint64_t rays() const;  //!< ray-brick pairs: a ray counts once per brick whose visible cells it may meet
  std::uint64_t raysOccluded() const;  //!< of rays(): skipped, matter in front ends them
  std::uint64_t bytesSent() const;
  int phaseCount() const;
  double phaseComputeMax(int phase) const;

  //! The stable JSON record (keys documented in README "Stats JSON").
  nlohmann::json toJson() const;
};

//! The paper-style summary: render and composite (max over nodes), modelled time, traffic.
std::string formatFrameTable(const FrameStats& stats);

}  // namespace kdswap
