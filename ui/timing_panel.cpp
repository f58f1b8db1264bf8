// Timing: the newest full frame's per-node timeline (timeline_view.cpp), the paper-style table
// (maximum over nodes), and the speedup over node counts (Figures 7-8).
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

#include "ui/panels.h"
#include "core/util/printable_text.h"

namespace kdswap {
namespace {

const ImU32 kCompositeColour = IM_COL32(240, 150, 60, 255);
const std::vector<int> kSweepCounts = {1, 2, 4, 8, 16, 32, 64};

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
  tableRow("occlusion map (in wall time)", "%.2f ms", s.occlusionMapSeconds * 1e3);
  tableRow("data distribution (once)", "%.2f ms", s.distributeSeconds * 1e3);
  tableRow("bytes sent (all nodes)", "%.0f KiB", double(s.bytesSent()) / 1024.0);
  tableRow("samples", "%.3g", double(s.samples()));
  // Ray-brick pairs skipped because matter in front ends them (occlusion map, or the waves' light).
  const double culled = s.rays() > 0 ? 100.0 * double(s.raysOccluded()) / double(s.rays()) : 0.0;
  tableRow("rays culled (matter in front)", "%.1f %%", culled);
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
    ImGui::TextDisabled("Modelled parallel time = max render (with waves: the longest chain of renders that waited for "
                        "each other) + per phase max composite, one processor per node; "
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
    if (ImGui::BeginTabItem("Timeline")) {
      if (state.fullFrame) drawTimelineTab(*state.fullFrame, state.timeline);
      else drawNoFullFrameText(state);
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
