// The desktop app: window and ImGui set-up, the per-frame loop (poll worker, draw panels, submit
// the newest request), first-run layout and the screenshot used by the GUI test.
#include "ui/gui_app.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <thread>
#include <cstdio>
#include <filesystem>
#include <fstream>

#include <GL/gl.h>
#include <GLFW/glfw3.h>
#include <imgui.h>
#include <imgui_impl_glfw.h>
#include <imgui_impl_opengl3.h>
#include <nlohmann/json.hpp>

#include "core/composite/registry.h"
#include "core/image/image_io.h"
#include "core/transfer/presets.h"
#include "core/util/error.h"
#include "core/volume/datasets/dataset.h"
#include "ui/panels.h"

namespace kdswap {
namespace {

constexpr double kRefineAfterSeconds = 0.25;  // still mouse this long: render at full quality
constexpr double kScreenshotTimeoutSeconds = 300;
std::string glfwLastError;

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
  state.scene.cluster.nodes = o.nodes;
  state.scene.cluster.partition = parsePartition(o.partition);
  const std::vector<std::string> strategies = strategyNames();
  if (std::find(strategies.begin(), strategies.end(), o.composite) == strategies.end())
    createStrategy(o.composite);  // throws, listing the valid names
  state.scene.cluster.strategy = o.composite;
  // Leave a core for the UI thread (and Mesa's rasteriser) so the window stays responsive.
  state.scene.cluster.threads = std::max(1, int(std::thread::hardware_concurrency()) - 1);
  if (o.nodes < 1 || o.nodes > kMaxNodes) throw Error("--nodes " + std::to_string(o.nodes) + ": expected 1.." + std::to_string(kMaxNodes));
  if (o.imageSize < 16 || o.imageSize > 4096) throw Error("--image-size " + std::to_string(o.imageSize) + ": expected 16..4096");
  state.request.width = state.request.height = o.imageSize;
  const std::string preset = o.tf.empty() ? presetFor(o.dataset) : o.tf;
  state.request.transfer = loadTransferFunction(preset.empty() ? "grayscale" : preset);
  state.tfEdited = !o.tf.empty();
  state.dataChoices = findDataChoices();
}

// First-run window placement, as fractions of the window: settings and timing on the left, the
// viewport and transfer function in the middle, the stages grid on the right.
void drawPanels(GuiState& state, float w, float h) {
  const float left = std::round(w * 0.21f), middle = std::round(w * 0.40f), right = w - left - middle;
  const float top = std::round(h * 0.48f), view = std::round(h * 0.64f);
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
void pollWorker(GuiState& state, RenderWorker& worker) {
  if (auto scene = worker.takeScene()) {
    const bool newData = !state.sceneShown || state.sceneShown->spec.data != scene->spec.data;
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
    if (!frame->preview) {
      state.fullFrame = frame;
      state.stagesTexture.upload(frame->stages.pixels);
    }
  }
  std::vector<std::string> errors = worker.takeErrors();
  if (!errors.empty()) {
    // The worker kept the previous scene: show its settings again.
    if (state.sceneShown && !worker.building()) state.scene = state.sceneShown->spec;
    state.errors.insert(state.errors.end(), errors.begin(), errors.end());
    if (state.errors.size() > 4) state.errors.erase(state.errors.begin(), state.errors.end() - 4);
  }
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

// The window's pixels (default framebuffer, bottom row first in GL) as a top-down PNG.
void writeScreenshot(const std::string& path, int width, int height) {
  std::vector<std::uint8_t> rgba(std::size_t(width) * height * 4);
  glPixelStorei(GL_PACK_ALIGNMENT, 1);
  glReadPixels(0, 0, width, height, GL_RGBA, GL_UNSIGNED_BYTE, rgba.data());
  Image image(Rect{0, 0, width, height});
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) {
      const std::uint8_t* p = &rgba[(std::size_t(height - 1 - y) * width + x) * 4];
      image.at(x, y) = Rgba{p[0] / 255.0f, p[1] / 255.0f, p[2] / 255.0f, 1.0f};
    }
  writeImage(path, image);
}

void writeLayout(const std::string& path, const GuiState& state, int width, int height) {
  auto rect = [](const ImVec4& r) { return nlohmann::json::array({r.x, r.y, r.z, r.w}); };
  nlohmann::json j;
  j["window"] = {{"width", width}, {"height", height}};
  j["viewport"] = rect(state.layout.viewport);
  nlohmann::json cells = nlohmann::json::array();
  for (const DrawnLayout::Cell& c : state.layout.cells) cells.push_back({{"node", c.node}, {"phase", c.phase}, {"rect", rect(c.rect)}});
  j["stages"] = {{"columns", state.layout.columns}, {"rows", state.layout.rows}, {"cells", cells}};
  std::ofstream out(path);
  out << j.dump(2) << "\n";
  if (!out) throw Error(path + ": cannot write the layout file");
}

void setUpImGui(GLFWwindow* window) {
  IMGUI_CHECKVERSION();
  ImGui::CreateContext();
  ImGuiIO& io = ImGui::GetIO();
  io.IniFilename = nullptr;  // a fixed first-run layout every time (no docking in Debian's 1.86)
  const char* font = "/usr/share/fonts/truetype/dejavu/DejaVuSans.ttf";
  if (std::filesystem::exists(font)) io.Fonts->AddFontFromFileTTF(font, 15.0f);
  ImGui::StyleColorsDark();
  ImGuiStyle& style = ImGui::GetStyle();
  style.WindowRounding = 0.0f;
  style.FrameRounding = 3.0f;
  style.WindowBorderSize = 1.0f;
  ImGui_ImplGlfw_InitForOpenGL(window, true);
  ImGui_ImplOpenGL3_Init("#version 330 core");
}

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
  GLFWwindow* window = glfwCreateWindow(options.windowWidth, options.windowHeight,
                                        "kdswap: parallel volume rendering with binary-swap compositing", nullptr, nullptr);
  if (!window) {
    glfwTerminate();
    throw Error("cannot create an OpenGL 3.3 core window (" + glfwLastError + ")");
  }
  glfwMakeContextCurrent(window);
  glfwSwapInterval(1);
  setUpImGui(window);

  int exitCode = 0;
  {
    RenderWorker worker;
    SweepWorker sweep;
    state.sweep = &sweep;
    worker.submit(state.scene, state.request, false);
    const bool capturing = !options.screenshot.empty();
    const double start = glfwGetTime();
    double lastMove = 0;
    bool refinePending = false;
    int framesAfterContent = -1;  // counting starts once the first full frame is shown
    int framesWhileRendering = 0;
    while (!glfwWindowShouldClose(window)) {
      if (capturing) glfwPollEvents();
      else glfwWaitEventsTimeout(1.0 / 60.0);  // redraws at <= 60 Hz while frames are in flight
      pollWorker(state, worker);
      ImGui_ImplOpenGL3_NewFrame();
      ImGui_ImplGlfw_NewFrame();
      ImGui::NewFrame();
      int width, height;
      glfwGetFramebufferSize(window, &width, &height);
      drawPanels(state, ImGui::GetIO().DisplaySize.x, ImGui::GetIO().DisplaySize.y);
      const double now = glfwGetTime();
      if (state.wantPreview) {
        worker.submit(state.scene, previewOf(state.request), true);
        lastMove = now, refinePending = true;
      } else if (state.wantFull || (refinePending && now - lastMove > kRefineAfterSeconds && !ImGui::IsAnyMouseDown())) {
        worker.submit(state.scene, state.request, false);
        refinePending = false;
      }
      state.wantPreview = state.wantFull = false;
      ImGui::Render();
      glViewport(0, 0, width, height);
      glClearColor(0.06f, 0.06f, 0.07f, 1.0f);
      glClear(GL_COLOR_BUFFER_BIT);
      ImGui_ImplOpenGL3_RenderDrawData(ImGui::GetDrawData());
      if (capturing) {
        if (framesAfterContent < 0 && state.fullFrame && !state.rendering) {
          framesAfterContent = 0;
          std::printf("UI drew %d frames in %.1f s while the first frame rendered (%.0f fps)\n", framesWhileRendering,
                      now - start, framesWhileRendering / std::max(now - start, 1e-9));
        }
        if (framesAfterContent < 0) ++framesWhileRendering;
        if (framesAfterContent >= 0 && ++framesAfterContent >= options.frames) {
          writeScreenshot(options.screenshot, width, height);
          if (!options.layout.empty()) writeLayout(options.layout, state, width, height);
          std::printf("wrote %s (%dx%d)\n", options.screenshot.c_str(), width, height);
          break;
        }
        if (!state.sceneShown && !state.errors.empty() && !state.rendering) {
          exitCode = 2;  // the scene never loaded: nothing to show (errors printed below)
          break;
        }
        if (now - start > kScreenshotTimeoutSeconds) {
          std::fprintf(stderr, "kdswap-gui: no frame finished within %.0f s; screenshot not written\n", kScreenshotTimeoutSeconds);
          exitCode = 1;
          break;
        }
      }
      glfwSwapBuffers(window);
    }
    if (!state.errors.empty() && capturing)
      for (const std::string& e : state.errors) std::fprintf(stderr, "kdswap-gui: %s\n", e.c_str());
    state.sweep = nullptr;
  }  // the workers join here, before the GL context goes away
  state.frameTexture.reset();
  state.stagesTexture.reset();
  ImGui_ImplOpenGL3_Shutdown();
  ImGui_ImplGlfw_Shutdown();
  ImGui::DestroyContext();
  glfwDestroyWindow(window);
  glfwTerminate();
  return exitCode;
}

}  // namespace kdswap
