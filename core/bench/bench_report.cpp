// Bench tables, CSV and JSON.
#include "core/bench/bench_report.h"

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <functional>
#include <set>

#include <nlohmann/json.hpp>

#include "core/util/error.h"

namespace kdswap {
namespace {

struct Axes {
  std::vector<std::string> strategies;  //!< in first-seen order
  std::vector<int> sizes, nodes;        //!< ascending
};

Axes axesOf(const std::vector<BenchCell>& cells) {
  Axes a;
  std::set<int> sizes, nodes;
  for (const BenchCell& c : cells) {
    if (std::find(a.strategies.begin(), a.strategies.end(), c.strategy) == a.strategies.end())
      a.strategies.push_back(c.strategy);
    sizes.insert(c.width);
    nodes.insert(c.nodes);
  }
  a.sizes.assign(sizes.begin(), sizes.end());
  a.nodes.assign(nodes.begin(), nodes.end());
  return a;
}

const BenchCell* find(const std::vector<BenchCell>& cells, const std::string& strategy, int size, int nodes) {
  for (const BenchCell& c : cells)
    if (c.strategy == strategy && c.width == size && c.nodes == nodes) return &c;
  return nullptr;
}

std::string header(const Axes& a, const std::string& title) {
  std::string out = title + "\n";
  char buf[64];
  std::snprintf(buf, sizeof buf, "%-22s", "image / nodes");
  out += buf;
  for (int n : a.nodes) {
    std::snprintf(buf, sizeof buf, "%10d", n);
    out += buf;
  }
  return out + "\n";
}

using Figure = std::function<double(const BenchCell&)>;

std::string row(const std::vector<BenchCell>& cells, const Axes& a, const std::string& strategy, int size,
                const std::string& label, const char* format, const Figure& figure) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%-22s", (std::to_string(size) + "x" + std::to_string(size) + " " + label).c_str());
  std::string out = buf;
  for (int n : a.nodes) {
    const BenchCell* c = find(cells, strategy, size, n);
    if (c) std::snprintf(buf, sizeof buf, format, figure(*c));
    else std::snprintf(buf, sizeof buf, "%10s", "-");
    out += buf;
  }
  return out + "\n";
}

std::string csvField(const std::string& s) {
  if (s.find_first_of(",\"\n") == std::string::npos) return s;
  std::string q = "\"";
  for (char ch : s) q += ch == '"' ? std::string("\"\"") : std::string(1, ch);
  return q + "\"";
}

}  // namespace

std::string formatPaperLayout(const std::vector<BenchCell>& cells) {
  const Axes a = axesOf(cells);
  std::string out;
  for (const std::string& s : a.strategies) {
    out += header(a, "Times in ms, maximum over nodes (paper Tables 1-3 layout), " + s + " compositing:");
    for (int size : a.sizes) {
      out += row(cells, a, s, size, "render", "%10.2f", [](const BenchCell& c) { return c.renderSeconds * 1e3; });
      out += row(cells, a, s, size, "composite", "%10.2f", [](const BenchCell& c) { return c.compositeSeconds * 1e3; });
    }
    out += "\n";
  }
  return out;
}

std::string formatCellDetails(const std::vector<BenchCell>& cells) {
  const Axes a = axesOf(cells);
  std::string out;
  for (const std::string& s : a.strategies) {
    out += header(a, "Per cell, " + s + " (wall = whole frame on this machine; modelled = max render (with "
                     "--waves: the longest chain of renders that waited for each other) + per-phase max composite, "
                     "as if each node had its own processor):");
    for (int size : a.sizes) {
      out += row(cells, a, s, size, "wall ms", "%10.2f", [](const BenchCell& c) { return c.wallSeconds * 1e3; });
      out += row(cells, a, s, size, "Msamples/s", "%10.1f", [](const BenchCell& c) { return c.samplesPerSecond * 1e-6; });
      out += row(cells, a, s, size, "culled %", "%10.1f",
                 [](const BenchCell& c) { return c.rays > 0 ? 100.0 * c.raysOccluded / c.rays : 0.0; });
      out += row(cells, a, s, size, "of wall: map ms", "%10.2f",
                 [](const BenchCell& c) { return c.occlusionMapSeconds * 1e3; });
      out += row(cells, a, s, size, "MB sent", "%10.2f", [](const BenchCell& c) { return double(c.bytesSent) * 1e-6; });
      out += row(cells, a, s, size, "render max/mean", "%10.2f", [](const BenchCell& c) { return c.renderImbalance; });
      if (std::any_of(cells.begin(), cells.end(), [](const BenchCell& c) { return c.commSeconds > 0; }))
        out += row(cells, a, s, size, "comm ms", "%10.2f", [](const BenchCell& c) { return c.commSeconds * 1e3; });
      out += row(cells, a, s, size, "modelled ms", "%10.2f", [](const BenchCell& c) { return c.modelledSeconds * 1e3; });
      out += row(cells, a, s, size, "speedup", "%10.2f", [](const BenchCell& c) { return c.speedup; });
    }
    out += "\n";
  }
  if (!a.nodes.empty() && a.nodes.front() != 1)
    out += "note: speedup is relative to P=" + std::to_string(a.nodes.front()) +
           " (P0 * T(P0) / T(P)); include 1 in --nodes for the paper's T(1) / T(P)\n";
  return out;
}

std::string benchCsv(const BenchContext& ctx, const std::vector<BenchCell>& cells) {
  std::string out =
      "dataset,strategy,nodes,width,height,frames,render_s,composite_s,wall_s,modelled_s,speedup,samples,"
      "samples_per_s,bytes_sent,peak_rss_bytes,distribute_s,balance,comm_s,render_imbalance,bricks_per_node,rays,"
      "rays_occluded,occlusion_map_s\n";
  char buf[512];
  for (const BenchCell& c : cells) {
    std::snprintf(buf, sizeof buf,
                  "%s,%s,%d,%d,%d,%d,%.9g,%.9g,%.9g,%.9g,%.6g,%.0f,%.6g,%llu,%llu,%.9g,%s,%.9g,%.6g,%d,%.0f,%.0f,%.9g\n",
                  csvField(ctx.dataset).c_str(), csvField(c.strategy).c_str(), c.nodes, c.width, c.height, c.frames,
                  c.renderSeconds, c.compositeSeconds, c.wallSeconds, c.modelledSeconds, c.speedup, c.samples,
                  c.samplesPerSecond, (unsigned long long)c.bytesSent, (unsigned long long)c.peakRssBytes,
                  c.distributeSeconds, c.balance.c_str(), c.commSeconds, c.renderImbalance,
                  c.bricksPerNode, c.rays, c.raysOccluded, c.occlusionMapSeconds);
    out += buf;
  }
  return out;
}

nlohmann::json benchJson(const BenchContext& ctx, const BenchResult& result) {
  nlohmann::json j;
  j["command"] = ctx.commandLine;
  j["dataset"] = ctx.dataset;
  j["volume"] = {{"dims", {ctx.dims[0], ctx.dims[1], ctx.dims[2]}}, {"type", ctx.volumeType}, {"voxels", ctx.voxels}};
  j["settings"] = {{"step_voxels", ctx.stepVoxels},
                   {"shading", ctx.shading},
                   {"frames", ctx.frames},
                   {"degrees_per_frame", ctx.degreesPerFrame},
                   {"view_distance", ctx.viewDistance},
                   {"interleaved", ctx.interleaved}};
  j["machine"] = machineJson(ctx.machine);
  j["statistic"] = "median over frames (warm-up frame excluded); render and composite are maxima over nodes";
  j["interrupted"] = result.interrupted;
  nlohmann::json cells = nlohmann::json::array();
  for (const BenchCell& c : result.cells)
    cells.push_back({{"strategy", c.strategy},
                     {"nodes", c.nodes},
                     {"image", {c.width, c.height}},
                     {"frames", c.frames},
                     {"render_s", c.renderSeconds},
                     {"composite_s", c.compositeSeconds},
                     {"wall_s", c.wallSeconds},
                     {"modelled_s", c.modelledSeconds},
                     {"speedup", c.speedup},
                     {"samples", c.samples},
                     {"samples_per_s", c.samplesPerSecond},
                     {"rays", c.rays},
                     {"rays_occluded", c.raysOccluded},
                     {"occlusion_map_s", c.occlusionMapSeconds},
                     {"bytes_sent", c.bytesSent},
                     {"peak_rss_bytes", c.peakRssBytes},
                     {"distribute_s", c.distributeSeconds},
                     {"balance", c.balance},
                     {"comm_s", c.commSeconds},
                     {"render_imbalance", c.renderImbalance},
                     {"bricks_per_node", c.bricksPerNode}});
  j["cells"] = std::move(cells);
  return j;
}

}  // namespace kdswap
