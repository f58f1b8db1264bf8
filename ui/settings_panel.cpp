// Settings: data set, cluster (nodes, partition, strategy) and render settings. Scene changes
// rebuild the cluster in the background; the previous scene stays until the new one is ready.
#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <string>
#include <system_error>
#include <vector>

#include <imgui.h>
#include <imgui_stdlib.h>

#include "core/cluster/virtual_cluster.h"
#include "core/composite/registry.h"
#include "core/util/error.h"
#include "core/volume/readers/raw_reader.h"
#include "ui/panels.h"
#include "ui/raw_layout_fields.h"

namespace kdswap {
namespace {

const int kImageSizes[] = {128, 256, 384, 512, 768, 1024};

// A narrow panel (little room beside the widgets for their labels) puts each label above its
// widget, and the widgets take the whole width.
bool gNarrow = false;

//! The ImGui label for a widget: `label` itself, or, when narrow, "##label" after the label has
//! been written on a line of its own.
std::string field(const char* label) {
  if (!gNarrow) return label;
  ImGui::TextUnformatted(label);
  return std::string("##") + label;
}

void section(const char* title) {
  ImGui::Spacing();
  ImGui::TextColored(ImVec4(0.55f, 0.75f, 1.0f, 1.0f), "%s", title);
  ImGui::Separator();
}

// What the data combo shows for a choice: a built-in spec as it is, a file by its name (with
// its folder when another choice has the same name), so the end of a long path is never cut off.
std::string choiceLabel(const std::string& choice, const std::vector<std::string>& all) {
  namespace fs = std::filesystem;
  if (choice.find('/') == std::string::npos && choice.find('\\') == std::string::npos) return choice;
  const fs::path path(choice);
  const std::string name = path.filename().string();
  for (const std::string& other : all) {
    std::error_code ec;
    if (other != choice && fs::path(other).filename().string() == name && !fs::equivalent(other, choice, ec))
      return (path.parent_path().filename() / path.filename()).string();
  }
  return name.empty() ? choice : name;
}

//! Records where the last widget was drawn, under `name`, for scripts (`move item NAME`).
void markItem(GuiState& state, const std::string& name) {
  const ImVec2 a = ImGui::GetItemRectMin(), b = ImGui::GetItemRectMax();
  state.layout.items[name] = ImVec4(a.x, a.y, b.x - a.x, b.y - a.y);
}

//! Makes `data` the scene's data, opened with the raw layout given for it if there is one.
void chooseData(GuiState& state, const std::string& data) {
  SceneSpec& scene = state.scene;
  scene.data = data;
  if (const auto it = state.rawLayouts.find(data); it != state.rawLayouts.end()) scene.rawPath = data, scene.raw = it->second;
  state.tfEdited = false;  // a new data set brings its own preset
  state.requestFrame(false);
}

//! `count` numbers side by side across the item width. Unlike ImGui's InputInt3 each is a widget
//! of its own, marked NAME-0, NAME-1, ... so that a script can click one.
void inputRow(GuiState& state, const char* label, const char* name, ImGuiDataType type, void* values, std::size_t size,
              int count, const char* format) {
  const std::string id = field(label);
  const float spacing = ImGui::GetStyle().ItemInnerSpacing.x;
  const float width = std::max(20.0f, (ImGui::CalcItemWidth() - spacing * float(count - 1)) / float(count));
  ImGui::PushID(id.c_str());
  for (int i = 0; i < count; ++i) {
    if (i > 0) ImGui::SameLine(0, spacing);
    ImGui::PushID(i);
    ImGui::SetNextItemWidth(width);
    ImGui::InputScalar("##value", type, static_cast<char*>(values) + std::size_t(i) * size, nullptr, nullptr, format);
    markItem(state, std::string(name) + "-" + std::to_string(i));
    ImGui::PopID();
  }
  ImGui::PopID();
  if (!gNarrow) {
    ImGui::SameLine(0, spacing);
    ImGui::TextUnformatted(label);
  }
}

//! A combo over `entries`, marked NAME while closed and each entry NAME:ENTRY while open (the last
//! item then is the popup). True when an entry was chosen.
bool markedCombo(GuiState& state, const char* label, const char* name, int& current, const std::vector<std::string>& entries) {
  bool chosen = false;
  if (!ImGui::BeginCombo(field(label).c_str(), entries[std::size_t(current)].c_str())) {
    markItem(state, name);
    return false;
  }
  for (int i = 0; i < int(entries.size()); ++i) {
    if (ImGui::Selectable(entries[std::size_t(i)].c_str(), i == current)) current = i, chosen = true;
    markItem(state, std::string(name) + ":" + entries[std::size_t(i)]);
  }
  ImGui::EndCombo();
  return chosen;
}

// The layout of the headerless .raw file whose path is typed: a file has none of its own. The
// fields are not checked here; opening the file refuses a wrong layout with the reader's message.
void drawRawLayoutFields(GuiState& state) {
  RawLayoutFields& f = state.settings.raw;
  ImGui::TextDisabled("raw file layout");
  inputRow(state, "dims", "raw-dims", ImGuiDataType_S32, f.dims, sizeof f.dims[0], 3, "%d");
  std::vector<std::string> types;
  for (int t = 0; t < kScalarTypeCount; ++t) types.emplace_back(scalarTypeName(ScalarType(t)));
  int type = int(f.type);
  if (markedCombo(state, "voxel type", "raw-type", type, types)) f.type = ScalarType(type);
  int order = f.bigEndian ? 1 : 0;
  if (markedCombo(state, "byte order", "raw-endian", order, {"little", "big"})) f.bigEndian = order == 1;
  inputRow(state, "spacing", "raw-spacing", ImGuiDataType_Float, f.spacing, sizeof f.spacing[0], 3, "%g");
  ImGui::InputScalar(field("header bytes").c_str(), ImGuiDataType_U64, &f.headerBytes);
  markItem(state, "raw-skip");
  if (ImGui::IsItemHovered()) ImGui::SetTooltip("bytes to skip at the start of the file");
}

void drawDataSection(GuiState& state) {
  SceneSpec& scene = state.scene;
  const std::string current = choiceLabel(scene.data, state.dataChoices);
  if (ImGui::BeginCombo(field("data").c_str(), fitText(current, ImGui::CalcItemWidth() - ImGui::GetFrameHeight() - 8).c_str())) {
    for (const std::string& choice : state.dataChoices) {
      const std::string shown = choiceLabel(choice, state.dataChoices), label = shown + "##" + choice;
      if (ImGui::Selectable(label.c_str(), choice == scene.data)) chooseData(state, choice);
      if (ImGui::IsItemHovered() && shown != choice) ImGui::SetTooltip("%s", choice.c_str());
    }
    ImGui::EndCombo();
  } else if (ImGui::IsItemHovered()) {
    std::error_code ec;
    const std::filesystem::path full = std::filesystem::absolute(scene.data, ec).lexically_normal();
    ImGui::SetTooltip("%s", current == scene.data || ec ? scene.data.c_str() : full.string().c_str());
  }
  std::string& typed = state.settings.typedData;
  const float open = buttonWidth("Open") + ImGui::GetStyle().ItemSpacing.x;
  ImGui::SetNextItemWidth(std::max(40.0f, ImGui::GetContentRegionAvail().x - open));
  const bool entered = ImGui::InputTextWithHint("##path", "path or name:size", &typed, ImGuiInputTextFlags_EnterReturnsTrue);
  markItem(state, "data-path");
  ImGui::SameLine();
  const bool clicked = ImGui::Button("Open");
  markItem(state, "open");
  // A newly typed path shows what is known of its layout; an unknown one keeps what is typed.
  if (state.settings.rawFilledFor != typed) {
    state.settings.rawFilledFor = typed;
    if (auto known = knownRawLayout(typed, state.rawLayouts)) state.settings.raw = *known;
  }
  const bool raw = isRawFile(typed);
  if (raw) drawRawLayoutFields(state);
  if ((clicked || entered) && !typed.empty()) {
    if (raw) state.rawLayouts[typed] = toRawLayout(state.settings.raw);
    chooseData(state, typed);
  }
  if (state.sceneShown) {
    const VolumeInfo& info = state.sceneShown->info;
    ImGui::PushTextWrapPos(0.0f);
    ImGui::TextDisabled("%d x %d x %d %s, values %.4g..%.4g", info.dims.x, info.dims.y, info.dims.z, info.type.c_str(),
                        double(info.minValue), double(info.maxValue));
    ImGui::TextDisabled("built in %.2f s (distribution %.2f s)", state.sceneShown->buildSeconds,
                        state.sceneShown->distributeSeconds);
    ImGui::PopTextWrapPos();
  }
}

void drawClusterSection(GuiState& state) {
  ClusterOptions& c = state.scene.cluster;
  int& nodes = state.settings.nodes;
  if (!ImGui::IsAnyItemActive()) nodes = c.nodes;
  // The same range as --nodes; logarithmic, so 1..16 keep a third of the slider, and halve /
  // double buttons step through the powers of two (Ctrl+click the slider to type a count).
  const float spacing = ImGui::GetStyle().ItemInnerSpacing.x;
  const float buttons = buttonWidth("/2") + buttonWidth("x2") + 2 * spacing;
  field("nodes");
  ImGui::PushID("nodes");
  ImGui::SetNextItemWidth(std::max(40.0f, ImGui::CalcItemWidth() - buttons));
  ImGui::SliderInt("##nodes", &nodes, 1, kMaxNodes, "%d", ImGuiSliderFlags_Logarithmic | ImGuiSliderFlags_AlwaysClamp);
  if (ImGui::IsItemHovered()) ImGui::SetTooltip("virtual nodes P, 1..%d (Ctrl+click to type)", kMaxNodes);
  bool settled = ImGui::IsItemDeactivatedAfterEdit();
  ImGui::SameLine(0, spacing);
  if (ImGui::Button("/2")) nodes = std::max(1, c.nodes / 2), settled = true;
  if (ImGui::IsItemHovered()) ImGui::SetTooltip("halve the nodes");
  ImGui::SameLine(0, spacing);
  if (ImGui::Button("x2")) nodes = std::min(kMaxNodes, c.nodes * 2), settled = true;
  if (ImGui::IsItemHovered()) ImGui::SetTooltip("double the nodes");
  if (!gNarrow) {
    ImGui::SameLine(0, spacing);
    ImGui::TextUnformatted("nodes");
  }
  ImGui::PopID();
  if (settled && nodes != c.nodes) {
    c.nodes = nodes;
    state.requestFrame(false);
  }
  int partition = c.partition == PartitionKind::KdTree ? 0 : 1;
  if (ImGui::Combo(field("partition").c_str(), &partition, "k-d tree\0slabs\0")) {
    c.partition = partition == 0 ? PartitionKind::KdTree : PartitionKind::Slab;
    state.requestFrame(false);
  }
  if (ImGui::BeginCombo(field("compositing").c_str(), c.strategy.c_str())) {
    for (const std::string& name : strategyNames())
      if (ImGui::Selectable(name.c_str(), name == c.strategy)) {
        c.strategy = name;
        state.requestFrame(false);
      }
    ImGui::EndCombo();
  }
  // Load balancing (the paper's conclusion): the timeline shows its effect on each node's work.
  int balance = c.balance == "cost" ? 1 : 0;
  if (ImGui::Combo(field("load balance").c_str(), &balance, "halve space\0by cost\0")) {
    if (balance == 1)
      useCostBalance(c, state.request.transfer);
    else
      c.balance = "space";
    state.requestFrame(false);
  }
  if (ImGui::IsItemHovered())
    ImGui::SetTooltip("place the k-d planes to halve space (the paper), or to balance the work the transfer "
                      "function makes (estimated when chosen; choose again after editing it)");
  int& bricks = state.settings.bricksPerNode;
  if (!ImGui::IsAnyItemActive()) bricks = c.bricksPerNode;
  ImGui::SliderInt(field("bricks per node").c_str(), &bricks, 1, 64, "%d", ImGuiSliderFlags_AlwaysClamp);
  if (ImGui::IsItemHovered())
    ImGui::SetTooltip("over-decomposition: each node's brick cut into this many, handed out on demand each frame");
  if (ImGui::IsItemDeactivatedAfterEdit() && bricks != c.bricksPerNode) {
    c.bricksPerNode = bricks;
    state.requestFrame(false);
  }
}

void drawRenderSection(GuiState& state) {
  FrameRequest& r = state.request;
  char current[32];
  std::snprintf(current, sizeof current, "%d x %d", r.width, r.height);
  if (ImGui::BeginCombo(field("image size").c_str(), current)) {
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
  if (ImGui::SliderFloat(field("step (voxels)").c_str(), &s.stepVoxels, 0.1f, 2.0f, "%.2f", ImGuiSliderFlags_AlwaysClamp)) state.requestFrame(true);
  if (ImGui::IsItemDeactivatedAfterEdit()) state.requestFrame(false);
  if (ImGui::SliderFloat(field("early termination").c_str(), &s.earlyTermination, 0.5f, 1.0f, "%.3f", ImGuiSliderFlags_AlwaysClamp))
    state.requestFrame(true);
  if (ImGui::IsItemDeactivatedAfterEdit()) state.requestFrame(false);
  if (ImGui::Checkbox("shading", &s.shading)) state.requestFrame(false);
  ImGui::SameLine();
  if (ImGui::Checkbox("jitter", &s.jitter)) state.requestFrame(false);
  ImGui::SameLine();
  if (ImGui::Checkbox("waves", &s.frontToBackWaves)) state.requestFrame(false);
  if (ImGui::IsItemHovered())
    ImGui::SetTooltip("front-to-back waves (beyond the paper): nodes render nearest first and stop where the light in "
                      "front is spent, so none samples behind the single-node ray's end (one brick per node)");
  ImGui::SliderInt(field("refine passes").c_str(), &state.refinePasses, 1, kMaxRefinePasses, "%d",
                   ImGuiSliderFlags_AlwaysClamp);
  if (ImGui::IsItemHovered())
    ImGui::SetTooltip("once the view rests, the frame is refined to the mean of this many passes on shifted sampling "
                      "lattices (kdswap render --passes): grain and rings average out; 1: off");
  if (ImGui::IsItemDeactivatedAfterEdit()) state.requestFrame(false);
  int projection = r.view.projection == Projection::Perspective ? 0 : 1;
  if (ImGui::Combo(field("projection").c_str(), &projection, "perspective\0orthographic\0")) {
    r.view.projection = projection == 0 ? Projection::Perspective : Projection::Orthographic;
    state.requestFrame(false);
  }
  int up = int(r.view.up);
  if (ImGui::Combo(field("up axis").c_str(), &up, "+x\0-x\0+y\0-y\0+z\0-z\0")) {
    r.view.up = UpAxis(up);
    state.requestFrame(false);
  }
  if (ImGui::SliderFloat(field("field of view").c_str(), &r.view.fovDeg, 10.0f, 90.0f, "%.0f deg")) state.requestFrame(true);
  if (ImGui::IsItemDeactivatedAfterEdit()) state.requestFrame(false);
}

}  // namespace

void drawSettingsPanel(GuiState& state) {
  state.layout.items.clear();  // only what is drawn this frame can be clicked
  if (!ImGui::Begin("Settings")) {
    ImGui::End();
    return;
  }
  // Widgets leave room for the widest label beside them; when that would leave them under 55%
  // of the panel, labels go above the widgets instead.
  float label = 0;
  for (const char* text : {"data", "nodes", "partition", "compositing", "load balance", "bricks per node", "image size", "step (voxels)",
                           "early termination", "projection", "up axis", "field of view", "dims", "voxel type", "byte order",
                           "spacing", "header bytes"})
    label = std::max(label, ImGui::CalcTextSize(text).x);
  const float avail = ImGui::GetContentRegionAvail().x;
  const float beside = avail - label - ImGui::GetStyle().ItemInnerSpacing.x - 2;
  gNarrow = beside < avail * 0.55f;
  ImGui::PushItemWidth(gNarrow ? avail : std::min(avail * 0.62f, beside));
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
