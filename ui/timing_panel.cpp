// Timing: per-node time split of the newest full frame (render, then wait and composite per
// phase, durations end to end: the stats carry no start times), the paper-style table (maximum
// over nodes), and the speedup over node counts (Figures 7-8).
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <thread>

#include "ui/panels.h"
#include "ui/printable_text.h"

namespace kdswap {
namespace {

const ImU32 kRenderColour = IM_COL32(80, 150, 230, 255);
const ImU32 kWaitColour = IM_COL32(95, 95, 105, 255);
const ImU32 kCompositeColour = IM_COL32(240, 150, 60, 255);
const std::vector<int> kSweepCounts = {1, 2, 4, 8, 16, 32, 64};

// A legend entry after the previous one, or on the next line when the line is full.
void legendSwatch(ImU32 colour, const char* text, bool first) {
  if (!first) sameLineIfFits(12 + ImGui::GetStyle().ItemSpacing.x + ImGui::CalcTextSize(text).x);
  const ImVec2 p = ImGui::GetCursorScreenPos();
  ImGui::GetWindowDrawList()->AddRectFilled(ImVec2(p.x, p.y + 3), ImVec2(p.x + 10, p.y + 13), colour);
  ImGui::Dummy(ImVec2(12, 14));
  ImGui::SameLine();
  ImGui::TextUnformatted(text);
}

double nodeTotal(const NodeReport& n) { return n.renderSeconds + n.waitSeconds() + n.compositeSeconds(); }

void drawTimeSplit(const FrameStats& stats) {
  legendSwatch(kRenderColour, "render", true);
  legendSwatch(kWaitColour, "wait", false);
  legendSwatch(kCompositeColour, "composite", false);
  sameLineIfFits(ImGui::CalcTextSize("(?)").x);
  // The frame stats hold each node's durations, not when its work started: bars laid end to end
  // from 0 would read as a timeline, which they are not (say so, and why the waits are long).
  ImGui::TextDisabled("(?)");
  if (ImGui::IsItemHovered()) {
    ImGui::BeginTooltip();
    ImGui::PushTextWrapPos(ImGui::GetFontSize() * 30.0f);
    ImGui::TextUnformatted(
        "Each bar is one node's measured durations laid end to end: render, then per compositing "
        "phase the time it waited for its partner's message and the time it composited. They are "
        "not start times: a node's work did not begin at 0, and nodes may wait while another "
        "finishes.");
    ImGui::Spacing();
    ImGui::Text("The %s share this machine's %u cores: a wait includes the time the partner spent "
                "waiting for a core, and render is the node's ray-casting work summed over its image "
                "tiles (its time on one processor).",
                counted(stats.nodes, "virtual node").c_str(), std::max(1u, std::thread::hardware_concurrency()));
    ImGui::PopTextWrapPos();
    ImGui::EndTooltip();
  }
  ImGui::PushTextWrapPos(0.0f);
  ImGui::TextDisabled("Per-node time split (durations end to end), not a timeline.");
  ImGui::PopTextWrapPos();
  double longest = 1e-9;
  for (const NodeReport& n : stats.perNode) longest = std::max(longest, nodeTotal(n));
  const int nodes = int(stats.perNode.size());
  ImGui::BeginChild("timeline", ImVec2(0, 0), false);
  const float rowH = std::clamp((ImGui::GetContentRegionAvail().y - 24) / float(std::max(nodes, 1)), 4.0f, 18.0f);
  const float labelW = rowH >= 12 ? 34.0f : 0.0f;
  const float barW = std::max(ImGui::GetContentRegionAvail().x - labelW - 4, 20.0f);
  const ImVec2 origin = ImGui::GetCursorScreenPos();
  ImDrawList* draw = ImGui::GetWindowDrawList();
  const float scale = barW / float(longest);
  for (int r = 0; r < nodes; ++r) {
    const NodeReport& n = stats.perNode[std::size_t(r)];
    const float y0 = origin.y + float(r) * rowH, y1 = y0 + rowH - (rowH > 6 ? 2.0f : 1.0f);
    if (labelW > 0) draw->AddText(ImVec2(origin.x, y0 + 0.5f * (rowH - 14)), nodeColour(r), std::to_string(r).c_str());
    float x = origin.x + labelW;
    auto bar = [&](double seconds, ImU32 colour) {
      const float x1 = x + float(seconds) * scale;
      if (x1 > x) draw->AddRectFilled(ImVec2(x, y0), ImVec2(std::max(x1, x + 1), y1), colour);
      x = x1;
    };
    bar(n.renderSeconds, kRenderColour);
    for (const PhaseStats& p : n.phases) {
      bar(p.waitSeconds, kWaitColour);
      const float start = x;
      bar(p.computeSeconds, kCompositeColour);
      if (rowH >= 8) draw->AddLine(ImVec2(start, y0), ImVec2(start, y1), IM_COL32(0, 0, 0, 160));
    }
    const ImVec2 m = ImGui::GetIO().MousePos;
    if (ImGui::IsWindowHovered() && m.y >= y0 && m.y < y0 + rowH && m.x >= origin.x) {
      ImGui::BeginTooltip();
      ImGui::Text("node %d: render %.2f ms", r, n.renderSeconds * 1e3);
      for (std::size_t k = 0; k < n.phases.size(); ++k)
        ImGui::Text("phase %zu %s (partner %d): wait %.2f ms, composite %.2f ms", k + 1, n.phases[k].label.c_str(),
                    n.phases[k].partner, n.phases[k].waitSeconds * 1e3, n.phases[k].computeSeconds * 1e3);
      ImGui::EndTooltip();
    }
  }
  const float axisY = origin.y + float(nodes) * rowH + 4;
  char text[48];
  std::snprintf(text, sizeof text, "%.1f ms (longest sum)", longest * 1e3);
  const float textX = std::max(origin.x, origin.x + labelW + barW - ImGui::CalcTextSize(text).x);
  if (textX > origin.x + labelW + ImGui::CalcTextSize("0").x + 8)
    draw->AddText(ImVec2(origin.x + labelW, axisY), IM_COL32(160, 160, 160, 255), "0");
  draw->AddText(ImVec2(textX, axisY), IM_COL32(160, 160, 160, 255), text);
  ImGui::Dummy(ImVec2(barW + labelW, float(nodes) * rowH + 20));
  ImGui::EndChild();
}

void tableRow(const char* name, const char* format, double value, bool indented = false) {
  ImGui::TableNextRow();
  ImGui::TableNextColumn();
  if (indented) ImGui::Indent(10);
  ImGui::TextWrapped("%s", name);  // wraps in a narrow panel rather than being cut
  if (indented) ImGui::Unindent(10);
  ImGui::TableNextColumn();
  ImGui::Text(format, value);
}

void drawTable(const FrameSnapshot& frame) {
  const FrameStats& s = frame.stats;
  ImGui::PushTextWrapPos(0.0f);
  ImGui::Text("%s, %dx%d, %s, %s partition; render and composite rows: maximum over nodes", counted(s.nodes, "node").c_str(), s.width,
              s.height, s.strategy.c_str(), s.partition.c_str());
  ImGui::PopTextWrapPos();
  if (!ImGui::BeginTable("paper", 2, ImGuiTableFlags_RowBg | ImGuiTableFlags_BordersInnerV | ImGuiTableFlags_ScrollY)) return;
  ImGui::TableSetupColumn("quantity");
  ImGui::TableSetupColumn("value", ImGuiTableColumnFlags_WidthFixed, ImGui::CalcTextSize("00000.00 ms").x + 8);
  ImGui::TableHeadersRow();
  tableRow("render", "%.2f ms", s.renderMax() * 1e3);
  tableRow("composite", "%.2f ms", s.compositeMax() * 1e3);
  for (int p = 0; p < s.phaseCount(); ++p) {
    std::string label = "phase " + std::to_string(p + 1);
    if (!s.perNode.empty() && p < int(s.perNode.front().phases.size())) label += " (" + s.perNode.front().phases[std::size_t(p)].label + ")";
    tableRow(label.c_str(), "%.2f ms", s.phaseComputeMax(p) * 1e3, true);
  }
  tableRow("modelled parallel time", "%.2f ms", s.modelledParallelSeconds() * 1e3);
  tableRow("wall time (this machine)", "%.2f ms", s.wallSeconds * 1e3);
  tableRow("gather on host", "%.2f ms", s.gatherSeconds * 1e3);
  tableRow("data distribution (once)", "%.2f ms", s.distributeSeconds * 1e3);
  tableRow("bytes sent (all nodes)", "%.0f KiB", double(s.bytesSent()) / 1024.0);
  tableRow("samples", "%.3g", double(s.samples()));
  ImGui::EndTable();
}

double speedupOf(const std::vector<SweepPoint>& points, double seconds) {
  return points.front().modelledSeconds / std::max(seconds, 1e-12);
}

void drawSpeedupChart(const std::vector<SweepPoint>& points, float height) {
  const ImVec2 p0 = ImGui::GetCursorScreenPos();
  const float width = std::max(ImGui::GetContentRegionAvail().x, 100.0f);
  ImGui::Dummy(ImVec2(width, height));
  ImDrawList* draw = ImGui::GetWindowDrawList();
  const float left = 34, bottom = 18;
  const ImVec2 a(p0.x + left, p0.y + 6), b(p0.x + width - 8, p0.y + height - bottom);
  draw->AddRectFilled(a, b, IM_COL32(24, 24, 30, 255));
  const int maxLog = int(kSweepCounts.size()) - 1;
  double maxSpeedup = 2;
  for (const SweepPoint& p : points) maxSpeedup = std::max(maxSpeedup, speedupOf(points, p.modelledMin));
  maxSpeedup = std::min(maxSpeedup * 1.15, double(kSweepCounts.back()));
  auto at = [&](double nodes, double speedup) {
    return ImVec2(a.x + float(std::log2(nodes) / maxLog) * (b.x - a.x), b.y - float(std::log2(speedup) / std::log2(maxSpeedup)) * (b.y - a.y));
  };
  for (int k = 0; k <= maxLog; ++k) {
    const ImVec2 t = at(double(1 << k), 1);
    draw->AddLine(ImVec2(t.x, a.y), ImVec2(t.x, b.y), IM_COL32(255, 255, 255, 20));
    const std::string label = std::to_string(1 << k);
    draw->AddText(ImVec2(t.x - 0.5f * ImGui::CalcTextSize(label.c_str()).x, b.y + 2), IM_COL32(170, 170, 170, 255),
                  label.c_str());
  }
  for (double s = 1; s <= maxSpeedup; s *= 2) {
    const ImVec2 t = at(1, s);
    draw->AddText(ImVec2(p0.x + 2, t.y - 7), IM_COL32(170, 170, 170, 255), std::to_string(int(s)).c_str());
  }
  draw->PushClipRect(a, b, true);
  draw->AddLine(at(1, 1), at(maxSpeedup, maxSpeedup), IM_COL32(255, 255, 255, 70), 1.0f);  // ideal
  for (std::size_t i = 0; i < points.size(); ++i) {
    const SweepPoint& p = points[i];
    const ImVec2 q = at(p.nodes, speedupOf(points, p.modelledSeconds));
    // The spread over the measured frames: the fastest and slowest frame's speedup.
    draw->AddLine(at(p.nodes, speedupOf(points, p.modelledMax)), at(p.nodes, speedupOf(points, p.modelledMin)),
                  IM_COL32(240, 150, 60, 130), 1.0f);
    if (i > 0) draw->AddLine(at(points[i - 1].nodes, speedupOf(points, points[i - 1].modelledSeconds)), q, kCompositeColour, 2.0f);
    draw->AddCircleFilled(q, 3.5f, kCompositeColour);
  }
  draw->PopClipRect();
}

void drawSpeedup(GuiState& state) {
  SweepWorker& sweep = *state.sweep;
  if (sweep.running()) {
    if (ImGui::Button("Cancel")) sweep.cancel();
  } else if (ImGui::Button("Run sweep 1..64 nodes") && state.sceneShown && state.fullFrame) {
    sweep.start(state.sceneShown->source, state.sceneShown->spec.cluster, state.fullFrame->request, kSweepCounts);
  }
  ImGui::SameLine();
  ImGui::ProgressBar(sweep.progress(), ImVec2(-1, 0), sweep.running() ? "sweeping..." : nullptr);
  ImGui::PushTextWrapPos(0.0f);
  if (!sweep.error().empty()) ImGui::TextColored(ImVec4(1, 0.45f, 0.4f, 1), "%s", printableText(sweep.error()).c_str());
  const std::vector<SweepPoint> points = sweep.points();
  const int frames = sweep.framesPerPoint();
  if (points.empty()) {
    ImGui::TextDisabled("Modelled parallel time = max render + per phase max composite, one processor per node; "
                        "per node count one warm-up frame, then the median of %d frames.", frames);
    ImGui::PopTextWrapPos();
    return;
  }
  ImGui::TextDisabled("Speedup T(1)/T(P) of the modelled parallel time, median of %d frames after a warm-up "
                      "(bars: fastest to slowest frame); grey line: ideal.", frames);
  ImGui::PopTextWrapPos();
  // One entry per node count, never split across lines; the chart takes what they leave, so
  // nothing scrolls.
  std::vector<std::string> entries;
  char cell[64];
  for (const SweepPoint& p : points) {
    std::snprintf(cell, sizeof cell, "P=%d: %.1f ms (x%.1f)", p.nodes, p.modelledSeconds * 1e3,
                  speedupOf(points, p.modelledSeconds));
    entries.push_back(cell);
  }
  const float wrap = ImGui::GetContentRegionAvail().x, gap = ImGui::GetStyle().ItemSpacing.x * 2;
  int lines = 1;
  for (float x = -gap; const std::string& e : entries) {
    const float w = ImGui::CalcTextSize(e.c_str()).x;
    if (x + gap + w > wrap && x > 0) ++lines, x = w;
    else x += gap + w;
  }
  const float entriesH = float(lines) * ImGui::GetTextLineHeightWithSpacing() + ImGui::GetStyle().ItemSpacing.y;
  drawSpeedupChart(points, std::max(80.0f, ImGui::GetContentRegionAvail().y - entriesH));
  for (std::size_t i = 0; i < entries.size(); ++i) {
    if (i > 0) {
      ImGui::SameLine(0, gap);
      if (ImGui::GetContentRegionAvail().x < ImGui::CalcTextSize(entries[i].c_str()).x) ImGui::NewLine();
    }
    ImGui::TextUnformatted(entries[i].c_str());
  }
}

}  // namespace

void drawTimingPanel(GuiState& state) {
  if (!ImGui::Begin("Timing")) {
    ImGui::End();
    return;
  }
  if (ImGui::BeginTabBar("timing")) {
    if (ImGui::BeginTabItem("Time split")) {
      if (state.fullFrame) drawTimeSplit(state.fullFrame->stats);
      else ImGui::TextDisabled("Waiting for the first full frame...");
      ImGui::EndTabItem();
    }
    if (ImGui::BeginTabItem("Table")) {
      if (state.fullFrame) drawTable(*state.fullFrame);
      ImGui::EndTabItem();
    }
    if (ImGui::BeginTabItem("Speedup")) {
      drawSpeedup(state);
      ImGui::EndTabItem();
    }
    ImGui::EndTabBar();
  }
  ImGui::End();
}

}  // namespace kdswap
