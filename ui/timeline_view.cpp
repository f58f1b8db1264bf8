// Timing > Timeline: a Gantt chart of the newest full frame, one row per node, x the time since
// the host started the frame: when each node rendered, and per compositing phase when it waited
// and when it composited. "durations only" (and frames whose reports carry no times) lays each
// node's durations end to end instead. Geometry comes from timeline_layout.h.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <thread>

#include "ui/ui_scale.h"
#include "ui/panels.h"
#include "ui/timeline_layout.h"

namespace kdswap {
namespace {

using Kind = TimelineBar::Kind;

const ImU32 kRenderColour = IM_COL32(80, 150, 230, 255);
const ImU32 kRenderStepColour = IM_COL32(45, 80, 125, 255);  //!< render step around its bricks
const ImU32 kWaitColour = IM_COL32(95, 95, 105, 255);
const ImU32 kCompositeColour = IM_COL32(240, 150, 60, 255);
const ImU32 kNotStartedColour = IM_COL32(120, 120, 130, 110);
const ImU32 kGridColour = IM_COL32(255, 255, 255, 22);
const ImU32 kAxisColour = IM_COL32(160, 160, 160, 255);
constexpr float kMinRow = 2.0f, kMaxRow = 28.0f;
constexpr float kMinTickPixels = 56.0f;

ImU32 colourOf(const TimelineBar& bar, bool hasBricks) {
  switch (bar.kind) {
    case Kind::NotStarted: return kNotStartedColour;
    case Kind::Render: return hasBricks ? kRenderStepColour : kRenderColour;
    case Kind::Brick: return kRenderColour;
    case Kind::Wait: return kWaitColour;
    case Kind::Composite: return kCompositeColour;
  }
  return kRenderColour;
}

// A legend entry after the previous one, or on the next line when the line is full.
void legendSwatch(ImU32 colour, const char* text, bool first, bool thin = false) {
  if (!first) sameLineIfFits(scaled(12) + ImGui::GetStyle().ItemSpacing.x + ImGui::CalcTextSize(text).x);
  const ImVec2 p = ImGui::GetCursorScreenPos();
  ImGui::GetWindowDrawList()->AddRectFilled(ImVec2(p.x, p.y + scaled(thin ? 7 : 3)),
                                            ImVec2(p.x + scaled(10), p.y + scaled(thin ? 9 : 13)), colour);
  ImGui::Dummy(ImVec2(scaled(12), scaled(14)));
  ImGui::SameLine();
  ImGui::TextUnformatted(text);
}

void helpMarker(const FrameSnapshot& frame, bool timeline) {
  sameLineIfFits(ImGui::CalcTextSize("(?)").x);
  ImGui::TextDisabled("(?)");
  if (!ImGui::IsItemHovered()) return;
  const int threads = frame.scene && frame.scene->spec.cluster.threads > 0 ? frame.scene->spec.cluster.threads
                                                                           : int(std::max(1u, std::thread::hardware_concurrency()));
  ImGui::BeginTooltip();
  ImGui::PushTextWrapPos(ImGui::GetFontSize() * 32.0f);
  if (timeline) {
    ImGui::TextUnformatted(
        "Each row is one node; x is the time since the host started the frame, on one clock for all nodes. "
        "Render runs from the node's task starting to its partial image being ready; then each compositing "
        "phase runs from its start to its end, its wait drawn first and its compositing after (the stats hold "
        "the two totals of a phase, not their order inside it). The line before a render bar is time the node "
        "had not started: the host preparing the frame, or the node's task waiting for a core. The white line "
        "is the frame's end on the host (after the gather).");
  } else {
    ImGui::TextUnformatted(
        "Each bar is one node's measured durations laid end to end: render work, then per compositing "
        "phase the time it waited for its partner's message and the time it composited. They are not "
        "start times.");
  }
  ImGui::Spacing();
  ImGui::Text("The %s run on %s: a node often waits for a core, and a wait includes the time its partner "
              "spent waiting for one. Render work (in the tooltips) is the ray casting summed over the "
              "node's image tiles, its time on one processor.",
              counted(frame.stats.nodes, "virtual node").c_str(), counted(threads, "worker thread").c_str());
  ImGui::PopTextWrapPos();
  ImGui::EndTooltip();
}

void barTooltip(const NodeReport& n, const TimelineBar& bar, bool timeline) {
  ImGui::BeginTooltip();
  auto interval = [&](const char* what) {
    if (timeline)
      ImGui::Text("%s %.2f to %.2f ms (%.2f ms)", what, bar.start * 1e3, bar.end * 1e3, (bar.end - bar.start) * 1e3);
    else
      ImGui::Text("%s %.2f ms", what, (bar.end - bar.start) * 1e3);
  };
  switch (bar.kind) {
    case Kind::NotStarted:
      ImGui::Text("node %d: not started until %.2f ms", n.rank, bar.end * 1e3);
      ImGui::TextDisabled("the host preparing the frame, or the node's task waiting for a core");
      break;
    case Kind::Render:
      ImGui::Text("node %d: render", n.rank);
      interval(timeline ? "step" : "work");
      ImGui::Text("ray-casting work %.2f ms, %.3g rays (%.3g culled: matter in front), %.3g samples",
                  n.renderSeconds * 1e3, double(n.rays), double(n.occluded), double(n.samples));
      if (!n.bricks.empty()) ImGui::Text("%s rendered", counted(long(n.bricks.size()), "brick").c_str());
      if (!n.renderedAfter.empty()) {
        ImGui::PushTextWrapPos(ImGui::GetFontSize() * 24.0f);
        ImGui::TextDisabled("waves: rendered one screen cell at a time, each cell after the pieces there of the %s "
                            "in front; the step spans its first cell to its last, between other nodes' cells",
                            counted(long(n.renderedAfter.size()), "brick").c_str());
        ImGui::PopTextWrapPos();
      }
      break;
    case Kind::Brick: {
      const NodeReport::BrickRender& b = n.bricks[std::size_t(bar.brick)];
      ImGui::Text("node %d: brick %d", n.rank, b.brick);
      interval("ray casting");
      ImGui::Text("work %.2f ms, %.3g samples", b.seconds * 1e3, double(b.samples));
      break;
    }
    case Kind::Wait:
    case Kind::Composite: {
      const PhaseStats& p = n.phases[std::size_t(bar.phase)];
      ImGui::Text("node %d, phase %d (%s)", n.rank, bar.phase + 1, p.label.c_str());
      if (p.partner >= 0) ImGui::Text("partner: node %d", p.partner);
      else ImGui::TextDisabled("no partner");
      interval(bar.kind == Kind::Wait ? "waited" : "composited");
      if (timeline)
        ImGui::Text("phase %.2f to %.2f ms: wait %.2f ms, composite %.2f ms", p.start * 1e3, p.end * 1e3,
                    p.waitSeconds * 1e3, p.computeSeconds * 1e3);
      ImGui::Text("%.1f KiB sent, %.1f KiB received, %lld pixels composited", double(p.bytesSent) / 1024.0,
                  double(p.bytesReceived) / 1024.0, static_cast<long long>(p.pixels));
      break;
    }
  }
  ImGui::EndTooltip();
}

//! Ticks and labels under the rows, in ms; the frame's end marked in the rows by the caller.
void drawAxis(ImDrawList* draw, float x0, float barW, float y, double span, double step) {
  draw->AddLine(ImVec2(x0, y), ImVec2(x0 + barW, y), kAxisColour);
  const double scale = double(barW) / span;
  float lastRight = -1e9f;
  for (int i = 0;; ++i) {
    const double t = double(i) * step;
    if (t > span * (1 + 1e-9)) break;
    const float x = x0 + float(t * scale);
    draw->AddLine(ImVec2(x, y), ImVec2(x, y + 4), kAxisColour);
    char text[32];
    std::snprintf(text, sizeof text, "%g", t * 1e3);
    const float w = ImGui::CalcTextSize(text).x;
    const float left = std::clamp(x - 0.5f * w, x0, x0 + barW - w);
    if (left > lastRight + 6) {
      draw->AddText(ImVec2(left, y + 5), kAxisColour, text);
      lastRight = left + w;
    }
  }
}

//! Where the rows' time axis lies in the window: x = x0 + t * scale.
struct Chart {
  float x0 = 0;
  double scale = 1;
  bool timeline = true;   //!< real start times (else durations end to end)
  bool hasBricks = false;
  float xOf(double t) const { return x0 + float(t * scale); }
};

// Legend, help and the "durations only" switch; a note when the bars are not a timeline.
void drawHeader(const FrameSnapshot& frame, TimelineUi& ui, bool timed, const Chart& chart) {
  const bool bricks = chart.hasBricks && chart.timeline;
  legendSwatch(kRenderColour, bricks ? "brick" : "render", true);
  if (bricks) legendSwatch(kRenderStepColour, "render step", false);
  legendSwatch(kWaitColour, "wait", false);
  legendSwatch(kCompositeColour, "composite", false);
  if (chart.timeline) legendSwatch(kNotStartedColour, "not started", false, true);
  helpMarker(frame, chart.timeline);
  if (timed) {
    sameLineIfFits(labelledWidth(ImGui::GetFrameHeight(), "durations only"));
    ImGui::Checkbox("durations only", &ui.durationsOnly);
  }
  if (chart.timeline) return;
  ImGui::PushTextWrapPos(0.0f);
  ImGui::TextDisabled(timed ? "Per-node durations laid end to end, not a timeline."
                            : "This frame's reports carry no start times: durations laid end to end, not a timeline.");
  ImGui::PopTextWrapPos();
}

// One node's row between y0 and y1, with the tooltip of the bar under the mouse.
void drawRow(ImDrawList* draw, const Chart& chart, const NodeReport& n, float y0, float y1, bool hovered) {
  const std::vector<TimelineBar> bars = timelineBars(n, !chart.timeline);
  for (const TimelineBar& b : bars) {
    const float a = chart.xOf(b.start), e = std::max(chart.xOf(b.end), a + 1);
    if (b.kind == Kind::NotStarted) {
      const float mid = std::floor(0.5f * (y0 + y1));
      draw->AddLine(ImVec2(a, mid), ImVec2(e, mid), kNotStartedColour);
    } else {
      draw->AddRectFilled(ImVec2(a, y0), ImVec2(e, y1), colourOf(b, chart.hasBricks));
    }
  }
  // Phase boundaries: one phase's wait would otherwise run into the next one's.
  if (y1 - y0 >= 5)
    for (const TimelineBar& b : bars)
      if (b.phase >= 0 && (b.kind == Kind::Wait || n.phases[std::size_t(b.phase)].waitSeconds <= 0))
        draw->AddLine(ImVec2(chart.xOf(b.start), y0), ImVec2(chart.xOf(b.start), y1), IM_COL32(0, 0, 0, 170));
  if (!hovered) return;
  // A bar thinner than a pixel is still found within two pixels of the mouse.
  const int at = barAt(bars, (ImGui::GetIO().MousePos.x - chart.x0) / chart.scale, 2.0 / chart.scale);
  if (at < 0) return;
  const TimelineBar& b = bars[std::size_t(at)];
  const float a = chart.xOf(b.start), e = std::max(chart.xOf(b.end), a + 1);
  draw->AddRect(ImVec2(a - 1, y0 - 1), ImVec2(e + 1, y1 + 1), IM_COL32(255, 255, 255, 230));
  barTooltip(n, b, chart.timeline);
}

}  // namespace

void drawTimelineTab(const FrameSnapshot& frame, TimelineUi& ui) {
  const FrameStats& stats = frame.stats;
  const bool timed = hasTimeline(stats);
  Chart chart;
  chart.timeline = timed && !ui.durationsOnly;
  for (const NodeReport& n : stats.perNode) chart.hasBricks = chart.hasBricks || !n.bricks.empty();
  drawHeader(frame, ui, timed, chart);

  const int nodes = int(stats.perNode.size());
  const float lineH = ImGui::GetTextLineHeight();
  const float axisH = 2 * lineH + 10;
  const ImVec2 avail = ImGui::GetContentRegionAvail();
  const float childH = std::max(avail.y - axisH - ImGui::GetStyle().ItemSpacing.y, 2 * kMinRow);
  const TimelineRows rows = timelineRows(nodes, childH, kMinRow, scaled(kMaxRow), lineH + 2);
  const float labelW = ImGui::CalcTextSize(std::to_string(std::max(nodes - 1, 0)).c_str()).x + 6;
  const float scrollbar = rows.total > childH ? ImGui::GetStyle().ScrollbarSize : 0.0f;
  const float barW = std::max(avail.x - labelW - 4 - scrollbar, 20.0f);
  const double span = timelineSpan(stats, !chart.timeline);
  const double step = tickStep(span, barW, scaled(kMinTickPixels));
  chart.scale = double(barW) / span;

  ImGui::BeginChild("timeline", ImVec2(0, childH), false);
  const ImVec2 origin = ImGui::GetCursorScreenPos();
  chart.x0 = origin.x + labelW;
  ImDrawList* draw = ImGui::GetWindowDrawList();
  const float top = origin.y + ImGui::GetScrollY(), bottom = top + ImGui::GetWindowHeight();
  for (double t = step; t <= span * (1 + 1e-9); t += step)
    draw->AddLine(ImVec2(chart.xOf(t), top), ImVec2(chart.xOf(t), bottom), kGridColour);
  const ImVec2 mouse = ImGui::GetIO().MousePos;
  const auto [first, last] = visibleRows(rows, nodes, ImGui::GetScrollY(), ImGui::GetWindowHeight());
  for (int r = first; r < last; ++r) {  // only the rows in view: 4096 rows scroll
    const float y0 = origin.y + float(r) * rows.height, y1 = std::max(y0 + rows.height - rows.gap, y0 + 1);
    if (r % rows.labelEvery == 0) {
      const std::string label = std::to_string(r);
      const float ty = std::max(y0 + 0.5f * (rows.height - lineH), top);
      draw->AddText(ImVec2(chart.x0 - 4 - ImGui::CalcTextSize(label.c_str()).x, ty), nodeColour(r), label.c_str());
    }
    const bool hovered = ImGui::IsWindowHovered() && mouse.y >= y0 && mouse.y < y0 + rows.height && mouse.x >= chart.x0 - 2;
    drawRow(draw, chart, stats.perNode[std::size_t(r)], y0, y1, hovered);
  }
  if (chart.timeline)  // the frame's end on the host: after the last tile arrived and was assembled
    draw->AddLine(ImVec2(chart.xOf(stats.wallSeconds), top), ImVec2(chart.xOf(stats.wallSeconds), bottom),
                  IM_COL32(255, 255, 255, 140));
  ImGui::Dummy(ImVec2(labelW + barW, rows.total));
  ImGui::EndChild();

  const ImVec2 axisAt = ImGui::GetCursorScreenPos();
  drawAxis(ImGui::GetWindowDrawList(), axisAt.x + labelW, barW, axisAt.y + 2, span, step);
  char caption[96];
  if (chart.timeline)
    std::snprintf(caption, sizeof caption, "ms since frame start (wall %.2f ms)", stats.wallSeconds * 1e3);
  else
    std::snprintf(caption, sizeof caption, "ms, durations end to end (longest %.2f ms)", span * 1e3);
  ImGui::GetWindowDrawList()->AddText(ImVec2(axisAt.x + labelW, axisAt.y + 4 + lineH), kAxisColour,
                                      fitText(caption, barW).c_str());
  ImGui::Dummy(ImVec2(labelW + barW, axisH));
}

}  // namespace kdswap
