// Transfer-function editor: the opacity curve's control points over the data's histogram (drag
// to move, double-click to add, right-click to remove), colour stops, presets, JSON save/load.
#include <algorithm>
#include <cmath>
#include <string>

#include <imgui.h>
#include <imgui_stdlib.h>

#include "core/transfer/presets.h"
#include "core/util/error.h"
#include "ui/ui_scale.h"
#include "ui/panels.h"

namespace kdswap {
namespace {

constexpr float kPointRadiusAt1 = 5.0f;  // pixels at scale 1 (ui_scale.h), as the two below
constexpr float kCurveHeightAt1 = 150.0f, kColourBarHeightAt1 = 14.0f;

// Opacities are per voxel and mostly small; a square-root axis makes 0.01 visible.
float alphaToY(float a) { return std::sqrt(std::clamp(a, 0.0f, 1.0f)); }
float yToAlpha(float y) { return std::clamp(y, 0.0f, 1.0f) * std::clamp(y, 0.0f, 1.0f); }

void changed(GuiState& state, bool continuous) {
  state.tfEdited = true;
  state.requestFrame(continuous);
}

void drawPresetRow(GuiState& state) {
  TransferFunction& tf = state.request.transfer;
  const std::vector<std::string> names = presetNames();
  float comboW = ImGui::CalcTextSize("(edited)").x;
  for (const std::string& name : names) comboW = std::max(comboW, ImGui::CalcTextSize(name.c_str()).x);
  comboW = std::min(comboW + ImGui::GetFrameHeight() + 2 * ImGui::GetStyle().FramePadding.x,
                    ImGui::GetContentRegionAvail().x * 0.45f);
  ImGui::SetNextItemWidth(comboW);
  if (ImGui::BeginCombo("preset", tf.name().empty() ? "(edited)" : tf.name().c_str())) {
    for (const std::string& name : names)
      if (ImGui::Selectable(name.c_str(), name == tf.name())) {
        try {
          tf = loadTransferFunction(name);
          changed(state, false);
        } catch (const Error& e) {
          state.errors.push_back(e.what());
        }
      }
    ImGui::EndCombo();
  }
  // The path field takes what the buttons leave; on a line of its own when that is too little.
  const float spacing = ImGui::GetStyle().ItemSpacing.x;
  const float buttons = buttonWidth("Save") + buttonWidth("Load") + 3 * spacing;
  sameLineIfFits(buttons + 120);
  ImGui::SetNextItemWidth(std::max(60.0f, ImGui::GetContentRegionAvail().x - buttons + spacing));
  ImGui::InputText("##path", &state.transfer.path);
  if (ImGui::IsItemHovered() && !ImGui::IsItemActive()) ImGui::SetTooltip("%s", state.transfer.path.c_str());
  ImGui::SameLine();
  if (ImGui::Button("Save")) {
    try {
      saveTransferFunction(tf, state.transfer.path);
    } catch (const Error& e) {
      state.errors.push_back(e.what());
    }
  }
  ImGui::SameLine();
  if (ImGui::Button("Load")) {
    try {
      tf = loadTransferFunction(state.transfer.path);
      changed(state, false);
    } catch (const Error& e) {
      state.errors.push_back(e.what());
    }
  }
}

void drawCurve(GuiState& state) {
  const float pointRadius = scaled(kPointRadiusAt1), curveHeight = scaled(kCurveHeightAt1),
              barHeight = scaled(kColourBarHeightAt1);
  TransferFunction& tf = state.request.transfer;
  const Histogram empty;
  const Histogram& histogram = state.sceneShown ? state.sceneShown->histogram : empty;
  const ImVec2 p0 = ImGui::GetCursorScreenPos();
  const float width = std::max(ImGui::GetContentRegionAvail().x, 50.0f);
  ImGui::InvisibleButton("curve", ImVec2(width, curveHeight), ImGuiButtonFlags_MouseButtonLeft | ImGuiButtonFlags_MouseButtonRight);
  const bool hovered = ImGui::IsItemHovered(), active = ImGui::IsItemActive();
  ImDrawList* draw = ImGui::GetWindowDrawList();
  const ImVec2 p1(p0.x + width, p0.y + curveHeight);
  draw->AddRectFilled(p0, p1, IM_COL32(24, 24, 30, 255));
  if (!histogram.bins.empty()) {
    // Integer data's bins are centred on whole values, so the outer ones reach half a bin past
    // the ends of the axis: clip them.
    draw->PushClipRect(p0, p1, true);
    const float n = float(histogram.bins.size()), span = histogram.x1 - histogram.x0;
    for (std::size_t i = 0; i < histogram.bins.size(); ++i) {
      const float a = histogram.x0 + span * float(i) / n, b = histogram.x0 + span * float(i + 1) / n;
      draw->AddRectFilled(ImVec2(p0.x + a * width, p1.y - histogram.bins[i] * curveHeight),
                          ImVec2(p0.x + b * width, p1.y), IM_COL32(90, 90, 110, 255));
    }
    draw->PopClipRect();
  }
  for (float a : {0.01f, 0.1f, 0.5f}) {
    const float y = p1.y - alphaToY(a) * curveHeight;
    draw->AddLine(ImVec2(p0.x, y), ImVec2(p1.x, y), IM_COL32(255, 255, 255, 30));
    draw->AddText(ImVec2(p0.x + 2, y - 14), IM_COL32(255, 255, 255, 80), a < 0.1f ? "0.01" : (a < 0.5f ? "0.1" : "0.5"));
  }
  auto toScreen = [&](const OpacityPoint& o) {
    return ImVec2(p0.x + o.x * width, p1.y - alphaToY(o.alpha) * curveHeight);
  };
  std::vector<OpacityPoint> points = tf.opacity();
  // The renderer interpolates opacity linearly between control points (and holds the end values
  // beyond them); on the square-root axis that is a curve, so each segment is sampled in opacity
  // every few pixels rather than joined by a straight screen line.
  if (!points.empty()) {
    std::vector<ImVec2> curve;
    auto add = [&](const OpacityPoint& o) {
      const ImVec2 q = toScreen(o);
      if (curve.empty() || std::abs(q.x - curve.back().x) + std::abs(q.y - curve.back().y) > 0.01f) curve.push_back(q);
    };
    add({0.0f, points.front().alpha});
    for (std::size_t i = 0; i + 1 < points.size(); ++i) {
      const OpacityPoint &a = points[i], &b = points[i + 1];
      const int steps = std::clamp(int((b.x - a.x) * width / 3.0f), 1, 512);
      for (int k = 0; k < steps; ++k) {
        const float t = float(k) / float(steps);
        add({a.x + t * (b.x - a.x), a.alpha + t * (b.alpha - a.alpha)});
      }
    }
    add(points.back());
    add({1.0f, points.back().alpha});
    draw->AddPolyline(curve.data(), int(curve.size()), IM_COL32(255, 255, 255, 230), 0, 2.0f);
  }

  const ImVec2 mouse = ImGui::GetIO().MousePos;
  int near = -1;
  for (std::size_t i = 0; i < points.size(); ++i) {
    const ImVec2 s = toScreen(points[i]);
    if (std::abs(s.x - mouse.x) <= pointRadius + 2 && std::abs(s.y - mouse.y) <= pointRadius + 2) near = int(i);
  }
  int& dragged = state.transfer.draggedPoint;
  if (hovered && ImGui::IsMouseClicked(ImGuiMouseButton_Left)) dragged = near;
  if (!active) dragged = -1;
  const float mx = std::clamp((mouse.x - p0.x) / width, 0.0f, 1.0f), my = yToAlpha((p1.y - mouse.y) / curveHeight);
  if (dragged >= 0 && dragged < int(points.size()) && ImGui::IsMouseDragging(ImGuiMouseButton_Left, 0.0f)) {
    OpacityPoint& o = points[std::size_t(dragged)];
    // End points keep their x; inner points stay between their neighbours so the order holds.
    if (dragged > 0 && dragged + 1 < int(points.size()))
      o.x = std::clamp(mx, points[std::size_t(dragged - 1)].x + 1e-3f, points[std::size_t(dragged + 1)].x - 1e-3f);
    o.alpha = my;
    tf.setOpacity(points);
    changed(state, true);
  } else if (hovered && near < 0 && ImGui::IsMouseDoubleClicked(ImGuiMouseButton_Left)) {
    points.push_back({mx, my});
    tf.setOpacity(points);
    changed(state, false);
  } else if (hovered && near >= 0 && ImGui::IsMouseClicked(ImGuiMouseButton_Right) && points.size() > 2) {
    points.erase(points.begin() + near);
    tf.setOpacity(points);
    changed(state, false);
  }
  if (ImGui::IsItemDeactivated() && ImGui::IsMouseReleased(ImGuiMouseButton_Left)) state.requestFrame(false);
  state.layout.tfPoints.clear();
  for (std::size_t i = 0; i < tf.opacity().size(); ++i) {
    const ImVec2 s = toScreen(tf.opacity()[i]);
    state.layout.tfPoints.push_back(s);
    const bool hot = int(i) == near || int(i) == dragged;
    draw->AddCircleFilled(s, hot ? pointRadius + 1.5f : pointRadius, hot ? IM_COL32(255, 210, 60, 255) : IM_COL32(240, 240, 240, 255));
  }
  if (hovered)
    ImGui::SetTooltip(near >= 0 ? "value %.3f, opacity %.4f\ndrag to move, right-click to remove"
                                : "value %.3f, opacity %.4f\ndouble-click to add a point",
                      near >= 0 ? double(tf.opacity()[std::size_t(near)].x) : double(mx),
                      near >= 0 ? double(tf.opacity()[std::size_t(near)].alpha) : double(my));

  // The colour map under the curve.
  const ImVec2 c0 = ImGui::GetCursorScreenPos();
  const int steps = 64;
  for (int i = 0; i < steps; ++i) {
    const glm::vec4 a = tf.evaluate(float(i) / steps), b = tf.evaluate(float(i + 1) / steps);
    draw->AddRectFilledMultiColor(ImVec2(c0.x + width * float(i) / steps, c0.y), ImVec2(c0.x + width * float(i + 1) / steps, c0.y + barHeight),
                                  ImColor(a.r, a.g, a.b), ImColor(b.r, b.g, b.b), ImColor(b.r, b.g, b.b), ImColor(a.r, a.g, a.b));
  }
  ImGui::Dummy(ImVec2(width, barHeight + 2));
}

void drawColourStops(GuiState& state) {
  TransferFunction& tf = state.request.transfer;
  std::vector<ColorStop> stops = tf.colors();
  bool edited = false, settled = false;
  int remove = -1;
  for (std::size_t i = 0; i < stops.size(); ++i) {
    ImGui::PushID(int(i));
    edited |= ImGui::ColorEdit3("##rgb", &stops[i].rgb.r, ImGuiColorEditFlags_NoInputs);
    settled |= ImGui::IsItemDeactivatedAfterEdit();
    ImGui::SameLine();
    ImGui::SetNextItemWidth(std::max(60.0f, ImGui::GetContentRegionAvail().x - 30));
    const float lo = i == 0 ? 0.0f : stops[i - 1].x, hi = i + 1 == stops.size() ? 1.0f : stops[i + 1].x;
    if (ImGui::SliderFloat("##x", &stops[i].x, 0.0f, 1.0f, "at %.3f")) {
      stops[i].x = std::clamp(stops[i].x, lo, hi);
      edited = true;
    }
    settled |= ImGui::IsItemDeactivatedAfterEdit();
    ImGui::SameLine();
    if (ImGui::SmallButton("x") && stops.size() > 1) remove = int(i);
    ImGui::PopID();
  }
  if (remove >= 0) stops.erase(stops.begin() + remove), edited = settled = true;
  if (ImGui::Button("Add colour stop")) {
    // In the middle of the widest gap.
    std::size_t at = 0;
    float gap = -1;
    for (std::size_t i = 0; i + 1 < stops.size(); ++i)
      if (stops[i + 1].x - stops[i].x > gap) gap = stops[i + 1].x - stops[i].x, at = i;
    const float x = stops.size() < 2 ? 0.5f : 0.5f * (stops[at].x + stops[at + 1].x);
    const glm::vec4 c = tf.evaluate(x);
    stops.push_back({x, glm::vec3(c)});
    edited = settled = true;
  }
  if (edited) {
    tf.setColors(stops);
    changed(state, !settled);
  }
  if (settled && !edited) state.requestFrame(false);
}

}  // namespace

void drawTransferPanel(GuiState& state) {
  if (!ImGui::Begin("Transfer function")) {
    ImGui::End();
    return;
  }
  drawPresetRow(state);
  drawCurve(state);
  if (ImGui::CollapsingHeader("Colour stops", ImGuiTreeNodeFlags_DefaultOpen)) drawColourStops(state);
  ImGui::End();
}

}  // namespace kdswap
