// Settings: data set, cluster (nodes, partition, strategy) and render settings. Scene changes
// rebuild the cluster in the background; the previous scene stays until the new one is ready.
#include <algorithm>
#include <cstdio>
#include <string>

#include <imgui.h>
#include <imgui_stdlib.h>

#include "core/composite/registry.h"
#include "core/util/error.h"
#include "ui/panels.h"

namespace kdswap {
namespace {

const int kImageSizes[] = {128, 256, 384, 512, 768, 1024};

void section(const char* title) {
  ImGui::Spacing();
  ImGui::TextColored(ImVec4(0.55f, 0.75f, 1.0f, 1.0f), "%s", title);
  ImGui::Separator();
}

void drawDataSection(GuiState& state) {
  SceneSpec& scene = state.scene;
  if (ImGui::BeginCombo("data", scene.data.c_str())) {
    for (const std::string& choice : state.dataChoices)
      if (ImGui::Selectable(choice.c_str(), choice == scene.data)) {
        scene.data = choice;
        state.tfEdited = false;  // a new data set brings its own preset
        state.requestFrame(false);
      }
    ImGui::EndCombo();
  }
  std::string& typed = state.settings.typedData;
  ImGui::SetNextItemWidth(ImGui::CalcItemWidth() - 52);
  const bool entered = ImGui::InputTextWithHint("##path", "file path or name:size", &typed, ImGuiInputTextFlags_EnterReturnsTrue);
  ImGui::SameLine();
  if ((ImGui::Button("Open") || entered) && !typed.empty()) {
    scene.data = typed;
    state.tfEdited = false;
    state.requestFrame(false);
  }
  if (state.sceneShown) {
    const VolumeInfo& info = state.sceneShown->info;
    ImGui::TextDisabled("%d x %d x %d %s, values %.4g..%.4g", info.dims.x, info.dims.y, info.dims.z, info.type.c_str(),
                        double(info.minValue), double(info.maxValue));
    ImGui::TextDisabled("built in %.2f s (distribution %.2f s)", state.sceneShown->buildSeconds,
                        state.sceneShown->distributeSeconds);
  }
}

void drawClusterSection(GuiState& state) {
  ClusterOptions& c = state.scene.cluster;
  int& nodes = state.settings.nodes;
  if (!ImGui::IsAnyItemActive()) nodes = c.nodes;
  ImGui::SliderInt("nodes", &nodes, 1, 256, "%d", ImGuiSliderFlags_Logarithmic | ImGuiSliderFlags_AlwaysClamp);
  if (ImGui::IsItemDeactivatedAfterEdit() && nodes != c.nodes) {
    c.nodes = nodes;
    state.requestFrame(false);
  }
  int partition = c.partition == PartitionKind::KdTree ? 0 : 1;
  if (ImGui::Combo("partition", &partition, "k-d tree\0slabs\0")) {
    c.partition = partition == 0 ? PartitionKind::KdTree : PartitionKind::Slab;
    state.requestFrame(false);
  }
  if (ImGui::BeginCombo("compositing", c.strategy.c_str())) {
    for (const std::string& name : strategyNames())
      if (ImGui::Selectable(name.c_str(), name == c.strategy)) {
        c.strategy = name;
        state.requestFrame(false);
      }
    ImGui::EndCombo();
  }
}

void drawRenderSection(GuiState& state) {
  FrameRequest& r = state.request;
  char current[32];
  std::snprintf(current, sizeof current, "%d x %d", r.width, r.height);
  if (ImGui::BeginCombo("image size", current)) {
    for (int s : kImageSizes) {
      const std::string label = std::to_string(s) + " x " + std::to_string(s);
      if (ImGui::Selectable(label.c_str(), s == r.width && s == r.height)) {
        r.width = r.height = s;
        state.requestFrame(false);
      }
    }
    ImGui::EndCombo();
  }
  RenderSettings& s = r.settings;
  if (ImGui::SliderFloat("step (voxels)", &s.stepVoxels, 0.1f, 2.0f, "%.2f", ImGuiSliderFlags_AlwaysClamp)) state.requestFrame(true);
  if (ImGui::IsItemDeactivatedAfterEdit()) state.requestFrame(false);
  if (ImGui::SliderFloat("early termination", &s.earlyTermination, 0.5f, 1.0f, "%.3f", ImGuiSliderFlags_AlwaysClamp))
    state.requestFrame(true);
  if (ImGui::IsItemDeactivatedAfterEdit()) state.requestFrame(false);
  if (ImGui::Checkbox("shading", &s.shading)) state.requestFrame(false);
  ImGui::SameLine();
  if (ImGui::Checkbox("jitter", &s.jitter)) state.requestFrame(false);
  int projection = r.view.projection == Projection::Perspective ? 0 : 1;
  if (ImGui::Combo("projection", &projection, "perspective\0orthographic\0")) {
    r.view.projection = projection == 0 ? Projection::Perspective : Projection::Orthographic;
    state.requestFrame(false);
  }
  int up = int(r.view.up);
  if (ImGui::Combo("up axis", &up, "+x\0-x\0+y\0-y\0+z\0-z\0")) {
    r.view.up = UpAxis(up);
    state.requestFrame(false);
  }
  if (ImGui::SliderFloat("field of view", &r.view.fovDeg, 10.0f, 90.0f, "%.0f deg")) state.requestFrame(true);
  if (ImGui::IsItemDeactivatedAfterEdit()) state.requestFrame(false);
}

}  // namespace

void drawSettingsPanel(GuiState& state) {
  if (!ImGui::Begin("Settings")) {
    ImGui::End();
    return;
  }
  ImGui::PushItemWidth(ImGui::GetContentRegionAvail().x * 0.62f);
  section("Data");
  drawDataSection(state);
  section("Virtual cluster");
  drawClusterSection(state);
  section("Rendering");
  drawRenderSection(state);
  ImGui::PopItemWidth();
  ImGui::End();
}

}  // namespace kdswap
