// The desktop app: window and ImGui set-up, the per-frame loop (poll worker, draw panels, submit
// the newest request, redraw what changed), first-run layout, and what tests and measurements use:
// the screenshot, scripted input, state dumps and the frame-time report.
#include "ui/gui_app.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <optional>
#include <thread>

#include <GL/gl.h>
#include <GLFW/glfw3.h>
#include <imgui.h>
#include <imgui_impl_glfw.h>
#include <imgui_impl_opengl3.h>
#include <nlohmann/json.hpp>

#include "core/cluster/front_to_back_waves.h"
#include "core/composite/registry.h"
#include "core/image/image_io.h"
#include "core/transfer/presets.h"
#include "core/util/error.h"
#include "core/volume/datasets/dataset.h"
#include "core/volume/readers/raw_reader.h"
#include "ui/damage_renderer.h"
#include "ui/frame_clock.h"
#include "ui/input_script.h"
#include "ui/panels.h"
#include "core/util/printable_text.h"
#include "ui/state_dump.h"
#include "ui/ui_scale.h"
#include "ui/window_size.h"

namespace kdswap {
namespace {

constexpr double kRefineAfterSeconds = 0.25;  // still mouse this long: render at full quality
constexpr double kFirstFrameTimeoutSeconds = 300;
constexpr double kFrameSeconds = 1.0 / 60.0;  // UI frames are paced to 60 Hz
const ImVec4 kClearColour(0.06f, 0.06f, 0.07f, 1.0f);
std::string glfwLastError;
bool windowExposed = false;  // set by GLFW's refresh callback: the window needs a full redraw

// Built-in data sets at three sizes, then volume files in assets/ and the shared data folder.
std::vector<std::string> findDataChoices() {
  std::vector<std::string> choices;
  for (const std::string& name : datasetNames())
    for (const char* size : {":64", ":128", ":256"}) choices.push_back(name + size);
  namespace fs = std::filesystem;
  const fs::path source(KDSWAP_SOURCE_DIR);
  for (const fs::path& dir : {fs::path(assetsDirectory()), source / "assets", source / ".." / "shared" / "data"}) {
    std::error_code ec;
    if (!fs::is_directory(dir, ec)) continue;
    std::vector<std::string> found;
    for (const auto& entry : fs::recursive_directory_iterator(dir, ec)) {
      const std::string name = entry.path().filename().string();
      for (const char* ext : {".nhdr", ".nrrd", ".mhd", ".vtk", ".nii.gz", ".nii"})
        if (name.size() > std::strlen(ext) && name.ends_with(ext)) found.push_back(fs::weakly_canonical(entry.path()).string());
    }
    std::sort(found.begin(), found.end());
    for (const std::string& f : found)
      if (std::find(choices.begin(), choices.end(), f) == choices.end()) choices.push_back(f);
  }
  return choices;
}

std::string presetFor(const std::string& data) {
  const std::string name = data.substr(0, data.find(':'));
  const std::vector<std::string> presets = presetNames();
  return std::find(presets.begin(), presets.end(), name) != presets.end() ? name : "";
}

void initState(GuiState& state, const GuiOptions& o) {
  state.scene.data = o.dataset;
  state.scene.rawPath = o.dataset, state.scene.raw = o.raw;
  if (isRawFile(o.dataset)) {
    state.rawLayouts[o.dataset] = o.raw;
    state.settings.typedData = o.dataset;  // its layout fields show what it was opened with
  }
  state.scene.cluster.nodes = o.nodes;
  state.scene.cluster.partition = parsePartition(o.partition);
  checkStrategyName(o.composite);
  state.scene.cluster.strategy = o.composite;
  if (o.balance != "space" && o.balance != "cost") throw Error("--balance " + o.balance + ": expected space or cost");
  if (o.bricksPerNode < 1 || o.bricksPerNode > 64)
    throw Error("--bricks-per-node " + std::to_string(o.bricksPerNode) + ": expected 1..64");
  state.scene.cluster.bricksPerNode = o.bricksPerNode;
  checkWavesWithBricksPerNode(o.waves, o.bricksPerNode);
  state.request.settings.frontToBackWaves = o.waves;
  if (o.refinePasses < 1 || o.refinePasses > kMaxRefinePasses)
    throw Error("--refine " + std::to_string(o.refinePasses) + ": expected 1.." + std::to_string(kMaxRefinePasses));
  state.refinePasses = o.refinePasses;
  // Leave a core for the UI thread (and Mesa's rasteriser) so the window stays responsive.
  state.scene.cluster.threads = std::max(1, int(std::thread::hardware_concurrency()) - 1);
  if (o.nodes < 1 || o.nodes > kMaxNodes) throw Error("--nodes " + std::to_string(o.nodes) + ": expected 1.." + std::to_string(kMaxNodes));
  if (o.imageSize < 16 || o.imageSize > 4096) throw Error("--image-size " + std::to_string(o.imageSize) + ": expected 16..4096");
  state.request.width = state.request.height = o.imageSize;
  state.request.view.up = parseUpAxis(o.up, "--up");
  const std::string preset = o.tf.empty() ? presetFor(o.dataset) : o.tf;
  state.request.transfer = loadTransferFunction(preset.empty() ? "grayscale" : preset);
  state.tfEdited = !o.tf.empty();
  if (o.balance == "cost") useCostBalance(state.scene.cluster, state.request.transfer);
  state.dataChoices = findDataChoices();
}

// First-run window placement, as fractions of the window: settings and timing on the left, the
// viewport and transfer function in the middle, the stages grid on the right.
void drawPanels(GuiState& state, float w, float h) {
  const float left = std::round(w * 0.21f), middle = std::round(w * 0.40f), right = w - left - middle;
  const float top = std::round(h * 0.53f), view = std::round(h * 0.64f);
  auto place = [](float x, float y, float ww, float hh) {
    ImGui::SetNextWindowPos(ImVec2(x, y), ImGuiCond_FirstUseEver);
    ImGui::SetNextWindowSize(ImVec2(ww, hh), ImGuiCond_FirstUseEver);
  };
  place(0, 0, left, top);
  drawSettingsPanel(state);
  place(0, top, left, h - top);
  drawTimingPanel(state);
  place(left, 0, middle, view);
  drawViewportPanel(state);
  place(left, view, middle, h - view);
  drawTransferPanel(state);
  place(left + middle, 0, right, h);
  drawStagesPanel(state);
}

// Takes what the worker finished: new scene (maybe its preset), frames (uploaded), errors.
void pollWorker(GuiState& state, RenderWorker& worker, DamageRenderer& renderer) {
  if (auto scene = worker.takeScene()) {
    const bool newData = !state.sceneShown || state.sceneShown->spec.data != scene->spec.data;
    // Errors shown so far were about the data before (one that would not open, say): the new data
    // on screen answers them. This poll's own errors are added below.
    if (newData) state.errors.clear();
    if (newData && !state.tfEdited && !scene->info.preset.empty() && scene->info.preset != state.request.transfer.name()) {
      try {
        state.request.transfer = loadTransferFunction(scene->info.preset);
        state.requestFrame(false);
      } catch (const Error& e) {
        state.errors.push_back(e.what());
      }
    }
    if (newData) state.request.view = resetView(state.request.view);
    state.sceneShown = scene;
  }
  if (auto frame = worker.takeFrame()) {
    state.frame = frame;
    state.sceneShown = frame->scene;
    state.frameTexture.upload(frame->image);
    renderer.textureChanged(state.frameTexture.imguiId());
    if (!frame->preview) {
      // A refinement pass brings a new image but the first pass's stages: upload those once.
      const bool newStages = !state.fullFrame || state.fullFrame->id != frame->id || frame->passes == 1;
      state.fullFrame = frame;
      state.fullTexture.upload(frame->image);
      renderer.textureChanged(state.fullTexture.imguiId());
      if (newStages) {
        state.stagesTexture.upload(frame->stages.pixels);
        renderer.textureChanged(state.stagesTexture.imguiId());
      }
    }
    if (state.logShown)
      state.shownLog.push_back({state.uiFrame, frame->id, frame->preview, frame->request.width, frame->request.height,
                                frame->request.view, ImGui::IsAnyMouseDown()});
  }
  const std::uint64_t failed = worker.lastFailed();  // before takeErrors: its error comes with it
  std::vector<std::string> errors = worker.takeErrors();
  if (!errors.empty()) {
    // The worker kept the previous scene: show its settings again.
    if (state.sceneShown && !worker.building()) state.scene = state.sceneShown->spec;
    state.errors.insert(state.errors.end(), errors.begin(), errors.end());
    if (state.errors.size() > 4) state.errors.erase(state.errors.begin(), state.errors.end() - 4);
  }
  state.lastFailed = failed;
  state.rendering = worker.busy();
  state.building = worker.building();
}

FrameRequest previewOf(const FrameRequest& full) {
  FrameRequest r = full;
  r.width = std::max(16, full.width / 2);
  r.height = std::max(16, full.height / 2);
  r.settings.stepVoxels = std::min(full.settings.stepVoxels * 2.0f, 4.0f);
  return r;
}

// Sends what the panels asked for: a preview while something moves, the full frame once nothing
// has moved for kRefineAfterSeconds (the button may still be held), or at once for a settled change.
void submitRequests(GuiState& state, RenderWorker& worker, double now, double& lastMove) {
  if (state.wantPreview) {
    state.lastSubmitted = worker.submit(state.scene, previewOf(state.request), true);
    lastMove = now, state.refinePending = true;
  } else if (state.wantFull || (state.refinePending && now - lastMove > kRefineAfterSeconds)) {
    state.lastSubmitted = worker.submit(state.scene, state.request, false, state.refinePasses);
    state.refinePending = false;
  }
  state.wantPreview = state.wantFull = false;
  state.rendering = worker.busy();
}

// Waits for input until this frame's deadline, so input is handled at most one frame late and
// the loop does not spin. A frame that overran starts the next one at once.
void waitForFrame(double& deadline) {
  const double now = glfwGetTime();
  deadline = std::max(deadline + kFrameSeconds, now);
  for (double left = deadline - now; left > 1e-4; left = deadline - glfwGetTime()) glfwWaitEventsTimeout(left);
  glfwPollEvents();
}

void writeLayout(const std::string& path, const GuiState& state, int width, int height) {
  auto rect = [](const ImVec4& r) { return nlohmann::json::array({r.x, r.y, r.z, r.w}); };
  nlohmann::json j;
  j["window"] = {{"width", width}, {"height", height}, {"ui_scale", uiScale()}, {"font_px", ImGui::GetFontSize()}};
  j["viewport"] = rect(state.layout.viewport);
  nlohmann::json cells = nlohmann::json::array();
  for (const DrawnLayout::Cell& c : state.layout.cells) cells.push_back({{"node", c.node}, {"phase", c.phase}, {"rect", rect(c.rect)}});
  j["stages"] = {{"columns", state.layout.columns}, {"rows", state.layout.rows}, {"cells", cells}};
  std::ofstream out(path);
  out << j.dump(2) << "\n";
  if (!out) throw Error(path + ": cannot write the layout file");
}

void writeJson(const std::string& path, const nlohmann::json& j, const char* what) {
  std::ofstream out(path);
  out << j.dump(2) << "\n";
  if (!out) throw Error(path + ": cannot write the " + std::string(what));
}

// A script checkpoint: the state now, plus the window and the shown frame as PNGs beside the
// --dump-state file (`<stem>-<name>-window.png`, `<stem>-<name>-frame.png`).
nlohmann::json checkpoint(const std::string& name, const GuiState& state, const Pixels& window, const std::string& dumpPath) {
  nlohmann::json j = describeState(state);
  if (dumpPath.empty()) return j;
  const std::filesystem::path dump(dumpPath);
  const std::string stem = (dump.parent_path() / dump.stem()).string() + "-" + name;
  writePixels(stem + "-window.png", window);
  j["window_png"] = stem + "-window.png";
  if (state.frame) {
    writePixels(stem + "-frame.png", state.frame->image);
    j["frame_png"] = stem + "-frame.png";
  }
  return j;
}

void setUpImGui(GLFWwindow* window) {
  IMGUI_CHECKVERSION();
  ImGui::CreateContext();
  ImGuiIO& io = ImGui::GetIO();
  io.IniFilename = nullptr;  // a fixed first-run layout every time (no docking in Debian's 1.86)
  const char* font = "/usr/share/fonts/truetype/dejavu/DejaVuSans.ttf";
  if (std::filesystem::exists(font)) {
    io.Fonts->AddFontFromFileTTF(font, scaled(kBaseFontSize));
  } else if (uiScale() != 1.0f) {
    ImFontConfig config;
    config.SizePixels = scaled(13.0f);  // ImGui's own font is 13 pixels
    io.Fonts->AddFontDefault(&config);
  }
  ImGui::StyleColorsDark();
  ImGuiStyle& style = ImGui::GetStyle();
  style.WindowRounding = 0.0f;
  style.FrameRounding = 3.0f;
  style.WindowBorderSize = 1.0f;
  style.ScaleAllSizes(uiScale());
  ImGui_ImplGlfw_InitForOpenGL(window, true);
  ImGui_ImplOpenGL3_Init("#version 330 core");
}

// The per-frame loop and what ends it: the window closing, --frames, the end of --script.
class GuiLoop {
 public:
  GuiLoop(const GuiOptions& options, GuiState& state, GLFWwindow* window, DamageRenderer& renderer)
      : options_(options), state_(state), window_(window), renderer_(renderer) {
    if (!options.script.empty()) script_ = InputScript::load(options.script);
    state.logShown = script_.has_value() || !options.dumpState.empty();
  }

  int run() {
    RenderWorker worker;
    SweepWorker sweep;
    state_.sweep = &sweep;
    state_.lastSubmitted = worker.submit(state_.scene, state_.request, false, state_.refinePasses);
    start_ = glfwGetTime();
    double deadline = start_, lastMove = 0;
    int exitCode = -1;
    while (exitCode < 0 && !glfwWindowShouldClose(window_)) {
      clock_.begin(glfwGetTime());
      waitForFrame(deadline);
      clock_.mark(FrameClock::Wait, glfwGetTime());
      pollWorker(state_, worker, renderer_);
      clock_.setRendering(state_.rendering || state_.building);
      clock_.mark(FrameClock::Take, glfwGetTime());
      ImGui_ImplOpenGL3_NewFrame();
      ImGui_ImplGlfw_NewFrame();
      if (script_) script_->apply(ImGui::GetIO());
      ImGui::NewFrame();
      drawPanels(state_, ImGui::GetIO().DisplaySize.x, ImGui::GetIO().DisplaySize.y);
      submitRequests(state_, worker, glfwGetTime(), lastMove);
      ImGui::Render();
      clock_.mark(FrameClock::Build, glfwGetTime());
      int width, height;
      glfwGetFramebufferSize(window_, &width, &height);
      const bool capture = !pendingCheckpoint_.empty() || exitCode_ >= 0;
      if (capture) clock_.exclude();
      if (std::exchange(windowExposed, false) || (capture && !renderer_.partial())) renderer_.invalidate();
      const bool changed = renderer_.render(ImGui::GetDrawData(), width, height, kClearColour);
      clock_.setPresented(changed, renderer_.lastDamagedFraction());
      if (capture) captured_ = {width, height, renderer_.readPixels(width, height)};
      clock_.mark(FrameClock::Draw, glfwGetTime());
      renderer_.present();
      clock_.mark(FrameClock::Swap, glfwGetTime());
      ++state_.uiFrame;
      exitCode = afterFrame(width, height);
    }
    state_.sweep = nullptr;
    finish();
    return std::max(exitCode, 0);
  }  // the workers join here, before the GL context goes away

 private:
  // Records what this frame captured (a checkpoint asked for by the last frame, the final
  // screenshot), then advances the script or the frame count. Returns an exit code to stop, or -1.
  int afterFrame(int width, int height) {
    if (!pendingCheckpoint_.empty())
      checkpoints_[pendingCheckpoint_] = checkpoint(pendingCheckpoint_, state_, captured_, options_.dumpState);
    pendingCheckpoint_.clear();
    if (exitCode_ >= 0) {
      if (!options_.screenshot.empty()) {
        writePixels(options_.screenshot, captured_);
        if (!options_.layout.empty()) writeLayout(options_.layout, state_, width, height);
        std::printf("wrote %s (%dx%d)\n", options_.screenshot.c_str(), width, height);
      }
      return exitCode_;
    }
    const double now = glfwGetTime();
    if (firstShown_ < 0 && state_.fullFrame && !state_.rendering) {
      firstShown_ = state_.uiFrame;
      std::printf("first frame shown after %.1f s (%ld UI frames)\n", now - start_, state_.uiFrame);
    }
    // Checkpoints and the exit take their pictures on the next frame, drawn completely.
    if (script_) {
      const InputScript::Step step = script_->advance(state_, now);
      pendingCheckpoint_ = step.checkpoint;
      if (step.verifyRedraw) renderer_.requestVerification();
      if (step.finished) exitCode_ = 0;
    } else if (options_.frames > 0) {
      if (firstShown_ >= 0 && state_.uiFrame - firstShown_ >= options_.frames) exitCode_ = 0;
      if (!state_.sceneShown && !state_.errors.empty() && !state_.rendering) return 2;  // nothing to show
      if (firstShown_ < 0 && now - start_ > kFirstFrameTimeoutSeconds) {
        std::fprintf(stderr, "kdswap-gui: no frame finished within %.0f s\n", kFirstFrameTimeoutSeconds);
        return 1;
      }
    }
    return -1;
  }

  void finish() {
    if (!options_.reportFps.empty() || options_.frames > 0 || script_) std::fputs(clock_.reportText().c_str(), stdout);
    if (!options_.reportFps.empty()) writeJson(options_.reportFps, nlohmann::json::parse(clock_.reportJson()), "frame-time report");
    if (!options_.dumpState.empty()) {
      nlohmann::json j;
      j["final"] = describeState(state_);
      j["redraw"] = {{"partial", renderer_.partial()}, {"verified_mismatched_pixels", renderer_.verificationMismatches()}};
      j["checkpoints"] = checkpoints_;
      j["shown"] = describeShownFrames(state_);
      writeJson(options_.dumpState, j, "state dump");
    }
    if (options_.frames > 0 || script_)
      for (const std::string& e : state_.errors) std::fprintf(stderr, "kdswap-gui: %s\n", printableText(e).c_str());
  }

  const GuiOptions& options_;
  GuiState& state_;
  GLFWwindow* window_;
  DamageRenderer& renderer_;
  std::optional<InputScript> script_;
  FrameClock clock_;
  nlohmann::json checkpoints_ = nlohmann::json::object();
  double start_ = 0;
  long firstShown_ = -1;           //!< UI frame at which the first full frame was shown
  std::string pendingCheckpoint_;  //!< recorded after the next frame is drawn
  int exitCode_ = -1;              //!< >= 0: exit with it after the next frame is drawn
  Pixels captured_;                //!< the window as drawn by a capturing frame
};

}  // namespace

int runGui(const GuiOptions& options) {
  GuiState state;
  initState(state, options);
  if (!options.screenshot.empty() && !isSupportedImagePath(options.screenshot))
    throw Error("--screenshot " + options.screenshot + ": expected a .png, .tif or .exr path");
  glfwSetErrorCallback([](int, const char* text) {
    glfwLastError = text;
    while (!glfwLastError.empty() && glfwLastError.back() == ' ') glfwLastError.pop_back();
  });
  if (!glfwInit()) throw Error("cannot open a display (" + glfwLastError + "); set DISPLAY or run under xvfb-run");
  glfwWindowHint(GLFW_CONTEXT_VERSION_MAJOR, 3);
  glfwWindowHint(GLFW_CONTEXT_VERSION_MINOR, 3);
  glfwWindowHint(GLFW_OPENGL_PROFILE, GLFW_OPENGL_CORE_PROFILE);
  glfwWindowHint(GLFW_OPENGL_FORWARD_COMPAT, GLFW_TRUE);
  // The monitor's content scale (2 on a 4K screen set to 200%), unless --ui-scale gives one.
  GLFWmonitor* monitor = glfwGetPrimaryMonitor();  // null when none is reported: scale 1, size as asked
  float scale = options.uiScale;
  if (!(scale > 0.0f)) {
    float xScale = 1.0f, yScale = 1.0f;
    if (monitor) glfwGetMonitorContentScale(monitor, &xScale, &yScale);
    scale = std::clamp(std::isfinite(xScale) ? xScale : 1.0f, 1.0f, kMaxUiScale);
  }
  setUiScale(scale);
  WindowSize size{options.windowWidth, options.windowHeight};
  if (!options.windowSizeGiven) {
    size = WindowSize{int(std::lround(float(size.width) * scale)), int(std::lround(float(size.height) * scale))};
    int areaX = 0, areaY = 0, areaWidth = 0, areaHeight = 0;
    if (monitor) glfwGetMonitorWorkarea(monitor, &areaX, &areaY, &areaWidth, &areaHeight);
    size = fitWindowToWorkArea(size, areaWidth, areaHeight);
  }
  GLFWwindow* window = glfwCreateWindow(size.width, size.height,
                                        "kdswap: parallel volume rendering with binary-swap compositing", nullptr, nullptr);
  if (!window) {
    glfwTerminate();
    throw Error("cannot create an OpenGL 3.3 core window (" + glfwLastError + ")");
  }
  glfwMakeContextCurrent(window);
  glfwSwapInterval(1);
  glfwSetWindowRefreshCallback(window, [](GLFWwindow*) { windowExposed = true; });
  setUpImGui(window);

  int exitCode = 0;
  std::string error;
  try {
    DamageRenderer renderer(window, options.fullRedraw);
    GuiLoop loop(options, state, window, renderer);
    exitCode = loop.run();
  } catch (const Error& e) {
    error = e.what();  // rethrown below, once the window is closed
  }
  state.frameTexture.reset();
  state.fullTexture.reset();
  state.stagesTexture.reset();
  ImGui_ImplOpenGL3_Shutdown();
  ImGui_ImplGlfw_Shutdown();
  ImGui::DestroyContext();
  glfwDestroyWindow(window);
  glfwTerminate();
  if (!error.empty()) throw Error(error);
  return exitCode;
}

}  // namespace kdswap
