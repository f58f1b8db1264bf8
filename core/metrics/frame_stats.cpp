// Frame statistics: aggregation, JSON and the printed table.
#include "core/metrics/frame_stats.h"

#include <algorithm>
#include <cstdio>
#include <unordered_map>

#include <nlohmann/json.hpp>

#include "core/util/memory.h"

namespace kdswap {

double FrameStats::renderMax() const {
  double m = 0;
  for (const NodeReport& n : perNode) m = std::max(m, n.modelledRenderSeconds());
  return m;
}

double FrameStats::renderMean() const {
  double sum = 0;
  for (const NodeReport& n : perNode) sum += n.modelledRenderSeconds();
  return perNode.empty() ? 0.0 : sum / double(perNode.size());
}

double FrameStats::compositeMax() const {
  double m = 0;
  for (const NodeReport& n : perNode) m = std::max(m, n.compositeSeconds() / n.speed);
  return m;
}

int FrameStats::phaseCount() const {
  int c = 0;
  for (const NodeReport& n : perNode) c = std::max(c, int(n.phases.size()));
  return c;
}

double FrameStats::phaseComputeMax(int phase) const {
  double m = 0;
  for (const NodeReport& n : perNode)
    if (phase < int(n.phases.size())) m = std::max(m, n.phases[std::size_t(phase)].computeSeconds / n.speed);
  return m;
}

double FrameStats::modelledCommSeconds() const {
  double t = 0;
  for (int p = 0; p < phaseCount(); ++p) t += network.phaseSeconds(perNode, p);
  return t;
}

double FrameStats::renderSpan() const {
  std::unordered_map<int, std::size_t> byRank;
  bool waited = false;
  for (std::size_t i = 0; i < perNode.size(); ++i) {
    byRank[perNode[i].rank] = i;
    waited = waited || !perNode[i].renderedAfter.empty();
  }
  if (!waited) return renderMax();
  // finish(n) = max over the nodes n waited for of finish + n's own render, by depth-first
  // search with an explicit stack (P may be thousands deep); a rank that is not reported, or a
  // wait that would close a cycle, adds nothing.
  enum : std::uint8_t { kNew, kOpen, kDone };
  std::vector<std::uint8_t> state(perNode.size(), kNew);
  std::vector<double> finish(perNode.size(), 0.0);
  double span = 0;
  for (std::size_t root = 0; root < perNode.size(); ++root) {
    std::vector<std::size_t> stack{root};
    while (!stack.empty()) {
      const std::size_t n = stack.back();
      if (state[n] == kDone) {
        stack.pop_back();
        continue;
      }
      bool ready = true;
      if (state[n] == kNew) {
        state[n] = kOpen;
        for (int rank : perNode[n].renderedAfter)
          if (auto it = byRank.find(rank); it != byRank.end() && state[it->second] == kNew) {
            stack.push_back(it->second);
            ready = false;
          }
      }
      if (!ready) continue;
      double start = 0;
      for (int rank : perNode[n].renderedAfter)
        if (auto it = byRank.find(rank); it != byRank.end() && state[it->second] == kDone)
          start = std::max(start, finish[it->second]);
      finish[n] = start + perNode[n].modelledRenderSeconds();
      span = std::max(span, finish[n]);
      state[n] = kDone;
      stack.pop_back();
    }
  }
  return span;
}

double FrameStats::modelledParallelSeconds() const {
  double t = renderSpan() + modelledCommSeconds();
  for (int p = 0; p < phaseCount(); ++p) t += phaseComputeMax(p);
  return t;
}

std::uint64_t FrameStats::samples() const {
  std::uint64_t s = 0;
  for (const NodeReport& n : perNode) s += n.samples;
  return s;
}

std::uint64_t FrameStats::rays() const {
  std::uint64_t s = 0;
  for (const NodeReport& n : perNode) s += n.rays;
  return s;
}

std::uint64_t FrameStats::raysOccluded() const {
  std::uint64_t s = 0;
  for (const NodeReport& n : perNode) s += n.occluded;
  return s;
}

std::uint64_t FrameStats::bytesSent() const {
  std::uint64_t s = 0;
  for (const NodeReport& n : perNode) s += n.bytesSent();
  return s;
}

nlohmann::json FrameStats::toJson() const {
  nlohmann::json j;
  j["nodes"] = nodes;
  j["image"] = {width, height};
  j["strategy"] = strategy;
  j["partition"] = partition;
  j["wall_s"] = wallSeconds;
  j["render_s_max"] = renderMax();
  j["composite_s_max"] = compositeMax();
  j["modelled_parallel_s"] = modelledParallelSeconds();
  j["modelled_comm_s"] = modelledCommSeconds();
  j["network"] = network.name;
  j["render_s_mean"] = renderMean();
  j["render_span_s"] = renderSpan();
  j["distribute_s"] = distributeSeconds;
  j["gather_s"] = gatherSeconds;
  j["occlusion_map_s"] = occlusionMapSeconds;
  j["samples"] = samples();
  j["rays"] = rays();
  j["rays_occluded"] = raysOccluded();
  j["samples_per_s"] = wallSeconds > 0 ? double(samples()) / wallSeconds : 0.0;
  j["bytes_sent"] = bytesSent();
  j["peak_rss_bytes"] = peakRssBytes;
  nlohmann::json nodesJson = nlohmann::json::array();
  for (const NodeReport& n : perNode) {
    nlohmann::json nj;
    nj["rank"] = n.rank;
    nj["render_s"] = n.renderSeconds;
    nj["speed"] = n.speed;
    nj["composite_s"] = n.compositeSeconds();
    nj["wait_s"] = n.waitSeconds();
    nj["rays"] = n.rays;
    nj["rays_occluded"] = n.occluded;
    nj["samples"] = n.samples;
    nj["bytes_sent"] = n.bytesSent();
    nj["private_bytes"] = n.privateBytes;
    if (!n.renderedAfter.empty()) nj["rendered_after"] = n.renderedAfter;
    // The timeline keys only where the report carries times: absent, not 0, where it does not.
    if (n.timed) {
      nj["render_start_s"] = n.renderStart;
      nj["render_end_s"] = n.renderEnd;
    }
    if (!n.bricks.empty()) {
      nlohmann::json bricks = nlohmann::json::array(), intervals = nlohmann::json::array();
      for (const NodeReport::BrickRender& b : n.bricks) {
        bricks.push_back(b.brick);
        intervals.push_back({b.start, b.end});
      }
      nj["bricks_rendered"] = std::move(bricks);
      if (n.timed) nj["brick_intervals_s"] = std::move(intervals);
    }
    nlohmann::json phases = nlohmann::json::array();
    for (const PhaseStats& p : n.phases) {
      nlohmann::json pj = {{"label", p.label},
                           {"partner", p.partner},
                           {"region", {p.region.x, p.region.y, p.region.w, p.region.h}},
                           {"composite_s", p.computeSeconds},
                           {"wait_s", p.waitSeconds},
                           {"pixels", p.pixels},
                           {"bytes_sent", p.bytesSent},
                           {"bytes_received", p.bytesReceived},
                           {"messages_sent", p.messagesSent}};
      if (n.timed) {
        pj["start_s"] = p.start;
        pj["end_s"] = p.end;
      }
      phases.push_back(std::move(pj));
    }
    nj["phases"] = std::move(phases);
    nodesJson.push_back(std::move(nj));
  }
  j["per_node"] = std::move(nodesJson);
  return j;
}

std::string formatFrameTable(const FrameStats& s) {
  std::uint64_t privateMax = 0;
  bool waited = false;  // front-to-back waves: the render span is a chain, not the max
  for (const NodeReport& n : s.perNode) {
    privateMax = std::max(privateMax, n.privateBytes);
    waited = waited || !n.renderedAfter.empty();
  }
  // Culled pairs only where there are some: one node, or a translucent scene, culls none.
  const std::string culled =
      s.raysOccluded() > 0 ? " (" + std::to_string(s.raysOccluded()) + " skipped: matter in front ends them)" : "";
  // The occlusion map's share of the wall time, where one was computed.
  char map[64] = "";
  if (s.occlusionMapSeconds > 0) std::snprintf(map, sizeof map, ", occlusion map %.2f ms", s.occlusionMapSeconds * 1e3);
  char text[1536];
  int n = std::snprintf(text, sizeof text,
                "%d node%s, %dx%d, %s compositing, %s partition\n"
                "  render     (max over nodes) %9.2f ms\n"
                "  composite  (max over nodes) %9.2f ms   over %d phase(s)\n"
                "  modelled parallel time      %9.2f ms   (%s + per-phase max composite)\n"
                "  wall time, this machine     %9.2f ms   (distribute %.2f ms once, gather %.2f ms%s)\n"
                "  samples %llu, rays %llu%s, bytes sent %s, node memory max %s, peak RSS %s\n",
                s.nodes, s.nodes == 1 ? "" : "s", s.width, s.height, s.strategy.c_str(), s.partition.c_str(),
                s.renderMax() * 1e3, s.compositeMax() * 1e3, s.phaseCount(), s.modelledParallelSeconds() * 1e3,
                waited ? "render chain of the waves" : "max render",
                s.wallSeconds * 1e3, s.distributeSeconds * 1e3, s.gatherSeconds * 1e3, map, (unsigned long long)s.samples(),
                (unsigned long long)s.rays(), culled.c_str(), formatBytes(s.bytesSent()).c_str(),
                formatBytes(privateMax).c_str(), formatBytes(s.peakRssBytes).c_str());
  if (!s.network.ideal() && n > 0 && n < int(sizeof text))
    std::snprintf(text + n, sizeof text - std::size_t(n),
                  "  modelled communication      %9.2f ms   (%s network, included in the modelled time)\n",
                  s.modelledCommSeconds() * 1e3, s.network.name.c_str());
  return text;
}

}  // namespace kdswap
