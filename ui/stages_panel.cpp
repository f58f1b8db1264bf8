// Compositing stages (Ma et al. 1993, Figure 6), live: one column per node, one row per phase
// (after rendering, after each compositing phase); each cell is the node's image with its region
// outlined and the rest dimmed. A phase slider / play button reveal the phases in turn.
#include <algorithm>
#include <cstdio>
#include <string>

#include "ui/ui_scale.h"
#include "ui/panels.h"

namespace kdswap {
namespace {

constexpr double kSecondsPerPhase = 0.8;
constexpr float kMinCell = 20.0f, kGap = 3.0f, kHeaderRow = 18.0f;  // pixels at scale 1 (ui_scale.h)
const ImU32 kOutline = IM_COL32(255, 204, 26, 255);

std::string phaseName(const PhaseRecord& record, int phase) {
  const std::string& label = record.cells.front()[std::size_t(phase)].label;
  return phase == 0 ? label : std::to_string(phase) + " " + label;
}

void cellTooltip(GuiState& state, const PhaseRecord& record, int node, int phase) {
  const PhaseCell& cell = record.cells[std::size_t(node)][std::size_t(phase)];
  ImGui::BeginTooltip();
  const ImVec2 at = ImGui::GetWindowPos(), size = ImGui::GetWindowSize();
  state.layout.tooltip = {node, phase, ImVec4(at.x, at.y, size.x, size.y)};
  ImGui::Text("node %d, phase %d (%s)", node, phase, cell.label.c_str());
  if (cell.partner >= 0) ImGui::Text("partner: node %d", cell.partner);
  else ImGui::TextDisabled("no partner");
  if (cell.region.empty()) ImGui::Text("region: empty");
  else ImGui::Text("region: %dx%d at (%d, %d)", cell.region.w, cell.region.h, cell.region.x, cell.region.y);
  ImGui::Text("exchanged: %.1f KiB", double(cell.bytesExchanged) / 1024.0);
  ImGui::EndTooltip();
}

void drawControls(GuiState& state, const PhaseRecord& record) {
  StagesUi& ui = state.stages;
  const int last = record.phaseCount() - 1;
  if (ui.phase < 0 || ui.phase > last) ui.phase = last;
  if (ImGui::Button(ui.playing ? "Pause" : "Play", ImVec2(scaled(60), 0))) {
    ui.playing = !ui.playing;
    if (ui.playing && ui.phase >= last) ui.phase = 0;
    ui.nextStepAt = ImGui::GetTime() + kSecondsPerPhase;
  }
  if (ui.playing && ImGui::GetTime() >= ui.nextStepAt) {
    ui.nextStepAt = ImGui::GetTime() + kSecondsPerPhase;
    if (++ui.phase >= last) ui.phase = last, ui.playing = false;
  }
  const std::string name = phaseName(record, ui.phase);
  float sliderW = 180;
  for (int p = 0; p <= last; ++p)
    sliderW = std::max(sliderW, ImGui::CalcTextSize(phaseName(record, p).c_str()).x + 2 * ImGui::GetStyle().FramePadding.x + 8);
  sameLineIfFits(labelledWidth(sliderW, "phase"));
  ImGui::SetNextItemWidth(sliderW);
  if (ImGui::SliderInt("phase", &ui.phase, 0, last, name.c_str())) ui.playing = false;
  sameLineIfFits(labelledWidth(scaled(110), "zoom"));
  ImGui::SetNextItemWidth(scaled(110));
  ImGui::SliderFloat("zoom", &ui.cellScale, 0.5f, 4.0f, "%.1fx");
  // Appended piece by piece: GCC 12 warns (-Wrestrict, a false positive) on the chained operator+.
  std::string size = "(";
  size += counted(long(record.cells.size()), "node");
  size += " x ";
  size += counted(record.phaseCount(), "phase");
  size += ")";
  sameLineIfFits(ImGui::CalcTextSize(size.c_str()).x);
  ImGui::TextDisabled("%s", size.c_str());
}

// The enlarged cell below the grid, with its details beside it.
void drawSelection(GuiState& state, const PhaseRecord& record, const StageAtlas& atlas) {
  StagesUi& ui = state.stages;
  if (ui.selectedNode < 0 || ui.selectedNode >= atlas.columns || ui.selectedPhase >= atlas.rows) return;
  const float side = std::min(ImGui::GetContentRegionAvail().x * 0.6f, ImGui::GetContentRegionAvail().y - 4.0f);
  if (side < 32) return;
  const float w = side * float(atlas.cellWidth) / float(std::max(atlas.cellWidth, atlas.cellHeight));
  const float h = side * float(atlas.cellHeight) / float(std::max(atlas.cellWidth, atlas.cellHeight));
  const ImVec2 aw(float(atlas.pixels.width), float(atlas.pixels.height));
  const ImVec2 uv0(float(ui.selectedNode * atlas.cellWidth) / aw.x, float(ui.selectedPhase * atlas.cellHeight) / aw.y);
  const ImVec2 uv1(uv0.x + float(atlas.cellWidth) / aw.x, uv0.y + float(atlas.cellHeight) / aw.y);
  const ImVec2 at = ImGui::GetCursorScreenPos();
  ImGui::Image(state.stagesTexture.imguiId(), ImVec2(w, h), uv0, uv1);
  state.layout.enlarged = {ui.selectedNode, ui.selectedPhase, ImVec4(at.x, at.y, w, h)};
  const PhaseCell& cell = record.cells[std::size_t(ui.selectedNode)][std::size_t(ui.selectedPhase)];
  if (!cell.region.empty()) {
    const float s = w / float(record.frame.w);
    ImGui::GetWindowDrawList()->AddRect(ImVec2(at.x + cell.region.x * s, at.y + cell.region.y * s),
                                        ImVec2(at.x + cell.region.right() * s, at.y + cell.region.bottom() * s), kOutline,
                                        0.0f, 0, scaled(2.0f));
  }
  ImGui::SameLine();
  ImGui::BeginGroup();
  ImGui::TextColored(ImColor(nodeColour(ui.selectedNode)), "node %d", ui.selectedNode);
  ImGui::Text("phase %d: %s", ui.selectedPhase, cell.label.c_str());
  if (cell.partner >= 0) ImGui::Text("partner: node %d", cell.partner);
  if (!cell.region.empty())
    ImGui::Text("region: %dx%d\n  at (%d, %d)", cell.region.w, cell.region.h, cell.region.x, cell.region.y);
  ImGui::Text("exchanged: %.1f KiB", double(cell.bytesExchanged) / 1024.0);
  if (ImGui::SmallButton("close")) ui.selectedNode = -1;
  ImGui::EndGroup();
}

// Below the grid when no cell is enlarged: the final frame with the tile each node finished
// outlined in its colour (the last row of the grid, assembled).
void drawFinalTiles(GuiState& state, const PhaseRecord& record) {
  ImGui::PushTextWrapPos(0.0f);
  ImGui::TextDisabled("Final image: the tile each node finished. Hover a cell for details; click to enlarge.");
  ImGui::PopTextWrapPos();
  const ImVec2 avail = ImGui::GetContentRegionAvail();
  const float side = std::min(avail.x, avail.y - 4.0f);
  if (side < 48 || !state.fullTexture.valid()) return;
  const float w = side, h = side * float(record.frame.h) / float(record.frame.w);
  const ImVec2 at(ImGui::GetCursorScreenPos().x + 0.5f * (avail.x - w), ImGui::GetCursorScreenPos().y);
  ImDrawList* draw = ImGui::GetWindowDrawList();
  draw->AddImage(state.fullTexture.imguiId(), at, ImVec2(at.x + w, at.y + h));
  const float s = w / float(record.frame.w);
  for (std::size_t node = 0; node < record.cells.size(); ++node) {
    const Rect& r = record.cells[node].back().region;
    if (r.empty()) continue;
    const ImVec2 a(at.x + r.x * s, at.y + r.y * s), b(at.x + r.right() * s, at.y + r.bottom() * s);
    draw->AddRect(a, b, nodeColour(int(node), 0.9f));
    if (record.cells.size() <= 64) {
      const std::string label = std::to_string(node);
      const ImVec2 size = ImGui::CalcTextSize(label.c_str());
      const ImVec2 c(0.5f * (a.x + b.x - size.x), 0.5f * (a.y + b.y - size.y));
      if (b.x - a.x > size.x + 2 && b.y - a.y > size.y) {
        draw->AddRectFilled(ImVec2(c.x - 3, c.y - 1), ImVec2(c.x + size.x + 3, c.y + size.y + 1), IM_COL32(0, 0, 0, 150), 3.0f);
        draw->AddText(c, nodeColour(int(node)), label.c_str());
      }
    }
  }
  ImGui::Dummy(ImVec2(avail.x, h));
}

}  // namespace

void drawStagesPanel(GuiState& state) {
  state.layout.cells.clear();
  state.layout.tooltip = state.layout.enlarged = {};
  state.layout.columns = state.layout.rows = 0;
  if (!ImGui::Begin("Compositing stages")) {
    ImGui::End();
    return;
  }
  const FrameSnapshot* frame = state.fullFrame.get();
  if (!frame || !frame->phases || frame->stages.pixels.empty() || !state.stagesTexture.valid()) {
    drawNoFullFrameText(state);
    ImGui::End();
    return;
  }
  const PhaseRecord& record = *frame->phases;
  const StageAtlas& atlas = frame->stages;
  StagesUi& ui = state.stages;
  drawControls(state, record);

  // Row labels as wide as the widest phase name (at most a third of the panel, then shortened).
  float labelWidth = 0;
  for (int phase = 0; phase < atlas.rows; ++phase)
    labelWidth = std::max(labelWidth, ImGui::CalcTextSize(phaseName(record, phase).c_str()).x + 8);
  labelWidth = std::min(labelWidth, std::max(40.0f, ImGui::GetContentRegionAvail().x / 3));
  // Cells fit the width, then the zoom scales them; the child scrolls when they do not fit.
  const float gap = scaled(kGap), header = scaled(kHeaderRow);
  const float availW = ImGui::GetContentRegionAvail().x - labelWidth - 2 * gap - ImGui::GetStyle().ScrollbarSize;
  const float cellW = std::max(scaled(kMinCell), (availW / float(atlas.columns) - gap) * ui.cellScale);
  const float cellH = cellW * float(atlas.cellHeight) / float(atlas.cellWidth);
  const float gridH = header + float(atlas.rows) * (cellH + gap) + ImGui::GetStyle().ScrollbarSize + 4;
  const bool selection = ui.selectedNode >= 0;
  const float childH = std::min(gridH, ImGui::GetContentRegionAvail().y * (selection ? 0.55f : 1.0f));
  ImGui::BeginChild("grid", ImVec2(0, childH), false, ImGuiWindowFlags_HorizontalScrollbar);
  const ImVec2 origin = ImGui::GetCursorScreenPos();
  ImDrawList* draw = ImGui::GetWindowDrawList();
  const ImVec2 aw(float(atlas.pixels.width), float(atlas.pixels.height));
  for (int node = 0; node < atlas.columns; ++node) {
    const std::string label = std::to_string(node);
    const float x = origin.x + labelWidth + float(node) * (cellW + gap);
    draw->AddText(ImVec2(x + 0.5f * (cellW - ImGui::CalcTextSize(label.c_str()).x), origin.y), nodeColour(node),
                  label.c_str());
  }
  state.layout.columns = atlas.columns;
  state.layout.rows = atlas.rows;
  for (int phase = 0; phase < atlas.rows; ++phase) {
    const float y = origin.y + header + float(phase) * (cellH + gap);
    const bool revealed = phase <= ui.phase;
    const std::string name = fitText(phaseName(record, phase), labelWidth - 6);
    draw->AddText(ImVec2(origin.x, y + 0.5f * cellH - 7), revealed ? IM_COL32(220, 220, 220, 255) : IM_COL32(110, 110, 110, 255),
                  name.c_str());
    for (int node = 0; node < atlas.columns; ++node) {
      const ImVec2 p0(origin.x + labelWidth + float(node) * (cellW + gap), y), p1(p0.x + cellW, p0.y + cellH);
      ImGui::SetCursorScreenPos(p0);
      ImGui::PushID(phase * atlas.columns + node);
      ImGui::InvisibleButton("cell", ImVec2(cellW, cellH));
      ImGui::PopID();
      if (!revealed) {
        draw->AddRectFilled(p0, p1, IM_COL32(28, 28, 34, 255));
        continue;
      }
      const ImVec2 uv0(float(node * atlas.cellWidth) / aw.x, float(phase * atlas.cellHeight) / aw.y);
      const ImVec2 uv1(uv0.x + float(atlas.cellWidth) / aw.x, uv0.y + float(atlas.cellHeight) / aw.y);
      draw->AddImage(state.stagesTexture.imguiId(), p0, p1, uv0, uv1);
      const PhaseCell& cell = record.cells[std::size_t(node)][std::size_t(phase)];
      if (!cell.region.empty()) {
        const float s = cellW / float(record.frame.w);
        draw->AddRect(ImVec2(p0.x + cell.region.x * s, p0.y + cell.region.y * s),
                      ImVec2(p0.x + cell.region.right() * s, p0.y + cell.region.bottom() * s), kOutline);
      }
      if (phase == ui.phase && ui.playing) draw->AddRect(p0, p1, IM_COL32(255, 255, 255, 120));
      if (ImGui::IsItemHovered()) {
        draw->AddRect(p0, p1, IM_COL32(255, 255, 255, 255), 0.0f, 0, scaled(2.0f));
        cellTooltip(state, record, node, phase);
      }
      if (ImGui::IsItemClicked()) ui.selectedNode = node, ui.selectedPhase = phase;
      if (node == ui.selectedNode && phase == ui.selectedPhase) draw->AddRect(p0, p1, IM_COL32(90, 200, 255, 255), 0, 0, scaled(2.0f));
      state.layout.cells.push_back({node, phase, ImVec4(p0.x, p0.y, cellW, cellH)});
    }
  }
  ImGui::SetCursorScreenPos(ImVec2(origin.x, origin.y + gridH - ImGui::GetStyle().ScrollbarSize - 4));
  ImGui::Dummy(ImVec2(labelWidth + float(atlas.columns) * (cellW + gap), 1));
  ImGui::EndChild();
  if (selection) drawSelection(state, record, atlas);
  else drawFinalTiles(state, record);
  ImGui::End();
}

}  // namespace kdswap
