// Viewport: the final frame, orbit / zoom / pan with the mouse, and the k-d bricks overlaid in
// node colours with their front-to-back order for the current view.
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <string>

#include <GLFW/glfw3.h>
#include <glm/common.hpp>

#include "ui/ui_scale.h"
#include "ui/panels.h"
#include "core/util/printable_text.h"
#include "core/camera/camera.h"

namespace kdswap {
namespace {

constexpr float kOrbitDegPerPixel = 0.4f;
constexpr float kZoomPerWheelStep = 0.9f;

// Display rectangle of a w x h frame fitted (centred, aspect kept) into [pos, pos + avail).
ImVec4 fitRect(ImVec2 pos, ImVec2 avail, int w, int h) {
  const float scale = std::min(avail.x / float(w), avail.y / float(h));
  const float dw = float(w) * scale, dh = float(h) * scale;
  return ImVec4(pos.x + 0.5f * (avail.x - dw), pos.y + 0.5f * (avail.y - dh), dw, dh);
}

void drawStatusLine(GuiState& state) {
  ImGui::Checkbox("Bricks", &state.showBricks);
  // The numbers are not ranks (the other panels label nodes 0..P-1): say so where they are shown.
  if (ImGui::IsItemHovered())
    ImGui::SetTooltip("each node's subvolume in its colour, numbered in front-to-back order for this view\n"
                      "(1 = nearest the eye: the order binary swap composites in)");
  ImGui::SameLine();
  if (ImGui::Button("Reset view (R)")) {
    state.request.view = resetView(state.request.view);
    state.requestFrame(false);
  }
  ImGui::SameLine();
  if (state.building) {
    ImGui::TextColored(ImVec4(1, 0.8f, 0.3f, 1), "building the scene...");
  } else if (state.rendering && state.frame && !state.frame->preview && state.frame->id == state.lastSubmitted &&
             state.frame->passes < state.frame->passesRequested) {
    ImGui::TextColored(ImVec4(1, 0.8f, 0.3f, 1), "refining: %d of %d passes", state.frame->passes,
                       state.frame->passesRequested);
  } else if (state.rendering) {
    ImGui::TextColored(ImVec4(1, 0.8f, 0.3f, 1), "rendering...");
  } else if (state.frame) {
    // The frame's own wall time (the Table's), and apart from it the wait from the request to
    // the finished frame, which also holds a scene build or an earlier frame still rendering.
    const FrameSnapshot& f = *state.frame;
    // Times first: a narrow panel cuts the scene description (the Settings panel has it) first.
    char text[256];
    const std::string passes = f.passes > 1 ? "mean of " + std::to_string(f.passes) + " passes, " : "";
    std::snprintf(text, sizeof text, "%s%.0f ms wall (request to frame %.0f ms), %s%dx%d, %s, %s",
                  f.preview ? "preview " : "", f.stats.wallSeconds * 1e3, f.seconds * 1e3, passes.c_str(),
                  f.request.width, f.request.height, counted(f.stats.nodes, "node").c_str(), f.stats.strategy.c_str());
    const std::string full = text, shown = fitText(full, ImGui::GetContentRegionAvail().x);
    ImGui::TextDisabled("%s", shown.c_str());
    if (ImGui::IsItemHovered()) {
      ImGui::BeginTooltip();
      ImGui::PushTextWrapPos(ImGui::GetFontSize() * 28.0f);
      ImGui::TextUnformatted(full.c_str());
      ImGui::TextDisabled("wall: the frame as the cluster timed it, host to host (Timing > Table). Request to "
                          "frame: from asking for it to the finished frame, including any scene build and "
                          "waiting for an earlier frame (and, once refined, the passes so far). Passes: the "
                          "picture is the mean of frames on shifted sampling lattices (refine passes, under "
                          "Rendering); the times and stages are the first pass's.");
      ImGui::PopTextWrapPos();
      ImGui::EndTooltip();
    }
  }
}

void drawErrors(GuiState& state) {
  for (std::size_t i = 0; i < state.errors.size(); ++i) {
    ImGui::PushID(int(i));
    if (ImGui::SmallButton("x")) {
      state.errors.erase(state.errors.begin() + std::ptrdiff_t(i));
      ImGui::PopID();
      break;
    }
    ImGui::SameLine();
    ImGui::PushTextWrapPos(0.0f);
    ImGui::TextColored(ImVec4(1.0f, 0.45f, 0.4f, 1.0f), "%s", printableText(state.errors[i]).c_str());
    ImGui::PopTextWrapPos();
    ImGui::PopID();
  }
}

// Orbit (left drag), pan (right drag), zoom (wheel); R resets. Movement asks for previews.
void handleInput(GuiState& state, ImVec4 shown) {
  ImGuiIO& io = ImGui::GetIO();
  View& view = state.request.view;
  const bool active = ImGui::IsItemActive();
  if (active && ImGui::IsMouseDragging(ImGuiMouseButton_Left, 0.0f) && (io.MouseDelta.x != 0 || io.MouseDelta.y != 0)) {
    view.azimuthDeg = std::fmod(view.azimuthDeg - io.MouseDelta.x * kOrbitDegPerPixel, 360.0f);
    view.elevationDeg = std::clamp(view.elevationDeg + io.MouseDelta.y * kOrbitDegPerPixel, -89.0f, 89.0f);
    state.requestFrame(true);
  }
  if (active && ImGui::IsMouseDragging(ImGuiMouseButton_Right, 0.0f) && (io.MouseDelta.x != 0 || io.MouseDelta.y != 0)) {
    // The frame spans 2 tan(fov/2) * distance radii vertically at the orbit centre.
    const float radiiPerPixel = 2.0f * std::tan(view.fovDeg * 0.5f * 3.14159265f / 180.0f) * view.distance / shown.w;
    view.pan.x += io.MouseDelta.x * radiiPerPixel;
    view.pan.y -= io.MouseDelta.y * radiiPerPixel;
    state.requestFrame(true);
  }
  if (ImGui::IsItemHovered() && io.MouseWheel != 0.0f) {
    view.distance = std::clamp(view.distance * std::pow(kZoomPerWheelStep, io.MouseWheel), 1.05f, 20.0f);
    state.requestFrame(true);
  }
  if (ImGui::IsWindowFocused() && !io.WantTextInput && ImGui::IsKeyPressed(GLFW_KEY_R, false)) {
    view = resetView(view);
    state.requestFrame(false);
  }
}

// The bricks of the shown scene, projected with the view of the request being edited (so they
// follow the mouse even before the frame catches up).
void drawBricks(const GuiState& state, ImVec4 shown) {
  const SceneSnapshot& scene = *state.sceneShown;
  const int w = state.request.width, h = state.request.height;
  const glm::vec3 worldMax = scene.info.worldMax();
  const Camera camera(state.request.view, glm::vec3(0.0f), worldMax, w, h);
  const VisibilityOrder order = scene.tree.order(camera, scene.info.spacing);
  const float sx = shown.z / float(w), sy = shown.w / float(h);
  ImDrawList* draw = ImGui::GetWindowDrawList();
  draw->PushClipRect(ImVec2(shown.x, shown.y), ImVec2(shown.x + shown.z, shown.y + shown.w), true);
  const int ranks = scene.tree.ranks();
  const float thickness = scaled(ranks > 32 ? 1.0f : 1.5f);
  for (int rank = 0; rank < ranks; ++rank) {
    const VoxelBox& box = scene.tree.brick(rank);
    const glm::vec3 lo = glm::vec3(box.lo) * scene.info.spacing;
    const glm::vec3 hi = glm::min(glm::vec3(box.hi), glm::vec3(scene.info.dims - 1)) * scene.info.spacing;
    std::array<ImVec2, 8> corner;
    bool visible = true;
    for (int c = 0; c < 8; ++c) {
      const auto p = camera.project(glm::vec3(c & 1 ? hi.x : lo.x, c & 2 ? hi.y : lo.y, c & 4 ? hi.z : lo.z));
      if (!p) visible = false;
      else corner[std::size_t(c)] = ImVec2(shown.x + p->x * sx, shown.y + p->y * sy);
    }
    if (!visible) continue;
    const ImU32 colour = nodeColour(rank, 0.9f);
    for (int c = 0; c < 8; ++c)
      for (int bit = 1; bit < 8; bit <<= 1)
        if (!(c & bit)) draw->AddLine(corner[std::size_t(c)], corner[std::size_t(c | bit)], colour, thickness);
    if (ranks <= 64) {
      const auto centre = camera.project(0.5f * (lo + hi));
      if (!centre) continue;
      const std::string label = std::to_string(order.position[std::size_t(rank)] + 1);
      const ImVec2 at(shown.x + centre->x * sx - ImGui::CalcTextSize(label.c_str()).x * 0.5f, shown.y + centre->y * sy - 7);
      draw->AddText(ImVec2(at.x + 1, at.y + 1), IM_COL32(0, 0, 0, 220), label.c_str());
      draw->AddText(at, colour, label.c_str());
    }
  }
  draw->PopClipRect();
}

}  // namespace

View resetView(const View& current) {
  View fresh;
  fresh.projection = current.projection;
  fresh.up = current.up;
  return fresh;
}

void drawViewportPanel(GuiState& state) {
  if (!ImGui::Begin("Viewport")) {
    ImGui::End();
    return;
  }
  drawStatusLine(state);
  drawErrors(state);
  const ImVec2 pos = ImGui::GetCursorScreenPos();
  const ImVec2 avail(std::max(ImGui::GetContentRegionAvail().x, 16.0f), std::max(ImGui::GetContentRegionAvail().y, 16.0f));
  ImGui::InvisibleButton("image", avail, ImGuiButtonFlags_MouseButtonLeft | ImGuiButtonFlags_MouseButtonRight);
  const ImVec4 shown = fitRect(pos, avail, state.request.width, state.request.height);
  handleInput(state, shown);
  ImDrawList* draw = ImGui::GetWindowDrawList();
  draw->AddRectFilled(ImVec2(shown.x, shown.y), ImVec2(shown.x + shown.z, shown.y + shown.w),
                      IM_COL32(20, 20, 26, 255));
  if (state.frameTexture.valid())
    draw->AddImage(state.frameTexture.imguiId(), ImVec2(shown.x, shown.y), ImVec2(shown.x + shown.z, shown.y + shown.w));
  else
    draw->AddText(ImVec2(shown.x + 10, shown.y + 10), IM_COL32(200, 200, 200, 255),
                  !state.nothingToShow()  ? "Waiting for the first frame..."
                  : state.errors.empty() ? "Nothing to show: the last request failed. Choose other data or settings."
                                         : "Nothing to show: the error above says why. Choose other data or settings.");
  if (state.showBricks && state.sceneShown) drawBricks(state, shown);
  if (ImGui::IsItemHovered() && !ImGui::IsItemActive())
    draw->AddText(ImVec2(shown.x + 6, shown.y + shown.w - 20), IM_COL32(200, 200, 200, 160),
                  "drag: orbit   right-drag: pan   wheel: zoom   R: reset");
  state.layout.viewport = shown;
  ImGui::End();
}

}  // namespace kdswap
