// JSON snapshots of the GUI state for --dump-state and script checkpoints.
#include "ui/state_dump.h"

#include "core/image/image_io.h"

namespace kdswap {
namespace {

nlohmann::json rect(const ImVec4& r) { return nlohmann::json::array({r.x, r.y, r.z, r.w}); }

nlohmann::json describeFrame(const FrameSnapshot& f, const GuiState& state) {
  return {{"id", f.id},
          {"preview", f.preview},
          {"width", f.request.width},
          {"height", f.request.height},
          {"view", describeView(f.request.view)},
          {"view_is_current", describeView(f.request.view) == describeView(state.request.view)},
          {"transfer_is_current", f.request.transfer.toJson() == state.request.transfer.toJson()}};
}

}  // namespace

nlohmann::json describeView(const View& v) {
  return {{"azimuth", v.azimuthDeg},       {"elevation", v.elevationDeg},       {"distance", v.distance},
          {"fov", v.fovDeg},               {"pan", {v.pan.x, v.pan.y}},         {"projection", toString(v.projection)},
          {"up", toString(v.up)}};
}

nlohmann::json describeState(const GuiState& state) {
  nlohmann::json j;
  j["ui_frame"] = state.uiFrame;
  j["view"] = describeView(state.request.view);
  j["image"] = {state.request.width, state.request.height};
  j["transfer"] = state.request.transfer.toJson();
  j["tf_edited"] = state.tfEdited;
  j["rendering"] = state.rendering;
  j["selected"] = {{"node", state.stages.selectedNode}, {"phase", state.stages.selectedPhase}};
  j["frame"] = state.frame ? describeFrame(*state.frame, state) : nlohmann::json();
  j["full_frame"] = state.fullFrame ? describeFrame(*state.fullFrame, state) : nlohmann::json();
  j["frames_shown"] = state.shownLog.size();
  if (state.sceneShown) {
    const VolumeInfo& info = state.sceneShown->info;
    j["data"] = {{"spec", state.sceneShown->spec.data},
                 {"dims", {info.dims.x, info.dims.y, info.dims.z}},
                 {"type", info.type},
                 {"spacing", {info.spacing.x, info.spacing.y, info.spacing.z}},
                 {"range", {info.minValue, info.maxValue}}};
  }
  nlohmann::json points = nlohmann::json::array();
  for (const ImVec2& p : state.layout.tfPoints) points.push_back({p.x, p.y});
  const DrawnLayout::Shown &tip = state.layout.tooltip, &big = state.layout.enlarged;
  j["layout"] = {{"viewport", rect(state.layout.viewport)},
                 {"stages", {{"columns", state.layout.columns}, {"rows", state.layout.rows}}},
                 {"tf_points", points},
                 {"tooltip", {{"node", tip.node}, {"phase", tip.phase}, {"rect", rect(tip.rect)}}},
                 {"enlarged", {{"node", big.node}, {"phase", big.phase}, {"rect", rect(big.rect)}}}};
  nlohmann::json cells = nlohmann::json::array();
  for (const DrawnLayout::Cell& c : state.layout.cells) cells.push_back({{"node", c.node}, {"phase", c.phase}, {"rect", rect(c.rect)}});
  j["layout"]["cells"] = cells;
  j["errors"] = state.errors;
  return j;
}

nlohmann::json describeShownFrames(const GuiState& state) {
  nlohmann::json list = nlohmann::json::array();
  for (const ShownFrame& f : state.shownLog)
    list.push_back({{"ui_frame", f.uiFrame},
                    {"id", f.id},
                    {"preview", f.preview},
                    {"width", f.width},
                    {"height", f.height},
                    {"view", describeView(f.view)},
                    {"mouse_down", f.mouseDown}});
  return list;
}

void writePixels(const std::string& path, const Pixels& pixels) {
  Image image(Rect{0, 0, pixels.width, pixels.height});
  for (int y = 0; y < pixels.height; ++y)
    for (int x = 0; x < pixels.width; ++x) {
      const std::uint8_t* p = &pixels.rgba[(std::size_t(y) * pixels.width + x) * 4];
      image.at(x, y) = Rgba{p[0] / 255.0f, p[1] / 255.0f, p[2] / 255.0f, 1.0f};
    }
  writeImage(path, image);
}

}  // namespace kdswap
