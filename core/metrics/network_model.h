// NetworkModel: the time messages would take on a real interconnect, added to the modelled
// parallel time so the in-process cluster (where a message is a pointer move) can replay the
// communication trends of the paper's Tables 4 (CM-5) and 9 (workstations on shared Ethernet).
//
// Point-to-point networks: every node sends at once over its own link, so a phase costs the
// slowest node's messages (per message: latency + bytes / bandwidth of the path to its partner).
// A shared medium (one Ethernet segment) carries one frame at a time, so a phase costs the sum of
// every node's bytes over the one bandwidth.
#pragma once

#include <string>
#include <vector>

namespace kdswap {

struct NodeReport;

struct NetworkModel {
  std::string name = "ideal";
  double latencySeconds = 0.0;  //!< per message (software + wire)
  //! Bytes per second, by tree distance between partners: bandwidth[l] applies when the two ranks
  //! share an aligned group of 4^(l+1) ranks (the CM-5's fat tree); the last entry applies beyond.
  //! Empty: infinite bandwidth.
  std::vector<double> bandwidth;
  bool sharedMedium = false;  //!< all nodes share one link (bus Ethernet)

  bool ideal() const { return latencySeconds == 0.0 && bandwidth.empty(); }
  //! Bandwidth between two ranks (-1 = unknown partner: the slowest level).
  double bandwidthBetween(int a, int b) const;
  //! Modelled communication time of compositing phase `phase` across all nodes.
  double phaseSeconds(const std::vector<NodeReport>& nodes, int phase) const;
};

//! Presets: "ideal" (no cost, the default), "cm5", "ethernet10". Throws kdswap::Error otherwise.
NetworkModel networkModel(const std::string& name);
//! The preset names, for --help and errors.
std::string networkModelNames();

}  // namespace kdswap
