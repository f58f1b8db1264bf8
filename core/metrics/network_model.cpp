// Network presets and the per-phase communication time.
#include "core/metrics/network_model.h"

#include <algorithm>

#include "core/metrics/node_report.h"
#include "core/util/error.h"

namespace kdswap {

NetworkModel networkModel(const std::string& name) {
  NetworkModel m;
  m.name = name;
  if (name == "ideal") return m;
  if (name == "cm5") {
    // CM-5 data network (a fat tree): 20 MB/s between nodes of one group of 4, 10 MB/s within a
    // group of 16, 5 MB/s beyond (Leiserson et al. 1992; TOP500 CM-5 description). The per-message
    // software latency of CMMD is an order-of-magnitude assumption (tens of microseconds).
    m.latencySeconds = 80e-6;
    m.bandwidth = {20e6, 10e6, 5e6};
    return m;
  }
  if (name == "ethernet10") {
    // 10 Mbit/s Ethernet shared by every workstation, as in the paper's workstation runs; about a
    // millisecond per message through the kernel's TCP stack and PVM (an assumption).
    m.latencySeconds = 1e-3;
    m.bandwidth = {10e6 / 8.0};
    m.sharedMedium = true;
    return m;
  }
  throw Error("network model \"" + name + "\": expected " + networkModelNames());
}

std::string networkModelNames() { return "ideal, cm5 or ethernet10"; }

double NetworkModel::bandwidthBetween(int a, int b) const {
  if (bandwidth.empty()) return 0.0;
  if (a < 0 || b < 0) return bandwidth.back();
  std::size_t level = 0;
  for (int group = 4; level + 1 < bandwidth.size() && a / group != b / group; group *= 4) ++level;
  return bandwidth[level];
}

double NetworkModel::phaseSeconds(const std::vector<NodeReport>& nodes, int phase) const {
  if (ideal()) return 0.0;
  double slowest = 0.0, totalWire = 0.0, mostMessages = 0.0;
  for (const NodeReport& n : nodes) {
    if (phase >= int(n.phases.size())) continue;
    const PhaseStats& p = n.phases[std::size_t(phase)];
    const double bw = bandwidthBetween(n.rank, p.partner);
    // Full duplex links: a node's phase takes as long as the larger of what it sends and receives.
    const double bytes = double(std::max(p.bytesSent, p.bytesReceived));
    const double wire = bw > 0.0 ? bytes / bw : 0.0;
    const double messages = double(std::max(p.messagesSent, p.messagesReceived));
    slowest = std::max(slowest, messages * latencySeconds + wire);
    totalWire += bw > 0.0 ? double(p.bytesSent) / bw : 0.0;
    mostMessages = std::max(mostMessages, messages);
  }
  // A shared segment serialises every node's bytes.
  return sharedMedium ? mostMessages * latencySeconds + totalWire : slowest;
}

}  // namespace kdswap
