// kdswap-gui: the desktop app (GLFW + Dear ImGui). Parses the options and runs ui/gui_app.
#include <cstdio>
#include <exception>
#include <optional>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "app/raw_layout_options.h"
#include "app/scene_options.h"
#include "core/cluster/virtual_cluster.h"
#include "core/composite/registry.h"
#include "core/util/error.h"
#include "core/util/memory.h"
#include "core/volume/datasets/dataset.h"
#include "ui/gui_app.h"
#include "core/util/printable_text.h"
#include "core/util/text_items.h"
#include "ui/ui_scale.h"
#include "ui/window_size.h"

int main(int argc, char** argv) {
  kdswap::configureMalloc();  // before any thread allocates (core/util/memory.h)
  kdswap::GuiOptions o;
  std::string windowSize = std::to_string(kdswap::kDefaultWindowSize.width) + "x" +
                           std::to_string(kdswap::kDefaultWindowSize.height);
  CLI::App app{
      "kdswap-gui: explore data-distributed volume rendering with binary-swap compositing\n"
      "(Ma, Painter, Hansen & Krogh 1993) on P virtual nodes: the final image, every node's partial\n"
      "image after each compositing phase (the paper's Figure 6), the transfer function and timings.\n"};
  std::string volume;
  CLI::Option* datasetOption =
      app.add_option("--dataset,-d", o.dataset,
                     "Built-in data set NAME[:SIZE] (phantom, vessels, turbulence); a volume file works here too")
          ->capture_default_str();
  // --volume as in `kdswap render`, so a command line carries over from one program to the other.
  app.add_option("--volume", volume,
                 "Volume file: .nrrd/.nhdr, .mhd/.mha, .nii/.nii.gz, legacy .vtk, or .raw (layout from --raw-* or a "
                 "name like head_256x256x113_uint16.raw)")
      ->excludes(datasetOption);
  kdswap::RawLayoutOptions raw;
  kdswap::addRawLayoutOptions(&app, raw);
  // Numbers are checked as kdswap's are ("abc" is not a whole number), before the ranges below.
  app.add_option("--nodes,-n", o.nodes, "Number of virtual nodes P, 1.." + std::to_string(kdswap::kMaxNodes))
      ->check(kdswap::wholeNumber())
      ->capture_default_str();
  app.add_option("--partition", o.partition, "kd or slab")->capture_default_str();
  app.add_option("--composite", o.composite, "Compositing strategy: " + kdswap::strategyNameList())
      ->capture_default_str();
  app.add_option("--balance", o.balance,
                 "Plane placement: space (halve space) or cost (balance the work the transfer function makes)")
      ->capture_default_str();
  app.add_option("--bricks-per-node", o.bricksPerNode,
                 "Over-decomposition: each node's brick cut into this many (1..64), handed out on demand")
      ->check(kdswap::wholeNumber())
      ->capture_default_str();
  app.add_flag("--waves", o.waves,
               "Front-to-back waves (beyond the paper): nodes render nearest first and stop where the light in front "
               "is spent (one brick per node); also a checkbox under Rendering");
  app.add_option("--refine", o.refinePasses,
                 "Once the view rests, average this many frames on shifted sampling lattices (1..64, 1: off), "
                 "which takes the grain and rings out; also a slider under Rendering")
      ->check(kdswap::wholeNumber())
      ->capture_default_str();
  app.add_option("--tf", o.tf, "Transfer-function preset or JSON file (default: the data set's preset)");
  app.add_option("--image-size", o.imageSize, "Rendered frame is N x N pixels, 16..4096")
      ->check(kdswap::wholeNumber())
      ->capture_default_str();
  app.add_option("--up", o.up,
                 "Volume axis pointing up on screen: +x -x +y -y +z -z (as kdswap render; also a list under Rendering)")
      ->capture_default_str();
  app.add_option("--size", windowSize,
                 "Window size WxH (default: 1600x1000 times --ui-scale, or the screen if that is smaller)")
      ->capture_default_str();
  app.add_option("--ui-scale", o.uiScale,
                 "Draw text and panels this many times larger, 0.5..4 (default: the screen's own scale, 2 on a 4K "
                 "screen set to 200%; 1.5 or 2 for a projector)")
      ->check(kdswap::number());
  app.add_option("--screenshot", o.screenshot,
                 "Write the whole window to this PNG once the first frame has rendered and --frames UI frames passed "
                 "(default 30), or when --script ends; then exit");
  app.add_option("--frames", o.frames, "Exit after N UI frames once the first full frame is shown")
      ->check(kdswap::wholeNumber());
  app.add_option("--layout", o.layout, "With --screenshot: also write where the viewport and stage cells were drawn (JSON)");
  app.add_option("--script", o.script,
                 "Play synthetic mouse and keyboard input from FILE, then exit. One command a line, # comments: "
                 "move TARGET; glide DX DY FRAMES; down|up|click left|right|middle; wheel STEPS; key LETTER; "
                 "type TEXT; frames N; wait full|preview; checkpoint NAME; verify-redraw. TARGET: viewport FX FY "
                 "(fractions of the image), cell NODE PHASE, tf-point K, item NAME (a named widget, e.g. data-path, "
                 "open, raw-dims-0), at X Y (window pixels)");
  app.add_option("--dump-state", o.dumpState,
                 "At exit write the view, transfer function, layout, frames shown and the script's checkpoints as JSON "
                 "(checkpoint pictures go beside it)");
  app.add_option("--report-fps", o.reportFps,
                 "At exit write the UI frame timing as JSON (fps, median and p95 frame time and its parts, idle and "
                 "while rendering) and print a summary");
  app.add_flag("--full-redraw", o.fullRedraw,
               "Draw the whole window every UI frame, changed or not (by default only what changed is drawn)");
  app.footer(
      "Mouse: drag to orbit, right-drag to pan, wheel to zoom, R to reset the view.\n"
      "Example: kdswap-gui --dataset phantom:128 --nodes 8\n"
      "Volume file: kdswap-gui --volume ../shared/data/cthead.nhdr --up -z --nodes 16\n"
      "Raw file: kdswap-gui --volume scan.raw --raw-dims 256x256x113 --raw-type uint16\n"
      "Headless: xvfb-run -a -s \"-screen 0 1600x1000x24\" kdswap-gui --screenshot shot.png --frames 30\n"
      "Measure: kdswap-gui --frames 300 --report-fps fps.json");
  try {
    app.parse(argc, argv);
    const std::vector<std::string> sides = kdswap::splitItems(windowSize, 'x');
    const auto side = [&](std::size_t i) { return sides.size() == 2 ? kdswap::parseWholeNumber(sides[i]) : std::nullopt; };
    const std::optional<std::int64_t> width = side(0), height = side(1);
    if (!width || !height || *width < 320 || *height < 240 || *width > 16384 || *height > 16384)
      throw kdswap::Error("--size \"" + windowSize + "\": expected WxH, from 320x240 to 16384x16384");
    o.windowWidth = int(*width), o.windowHeight = int(*height);
    o.windowSizeGiven = app.count("--size") > 0;
    if (app.count("--ui-scale") && !(o.uiScale >= kdswap::kMinUiScale && o.uiScale <= kdswap::kMaxUiScale))
      throw kdswap::Error("--ui-scale " + app.get_option("--ui-scale")->as<std::string>() + ": expected 0.5..4");
    if (app.count("--frames") && o.frames < 1) throw kdswap::Error("--frames " + std::to_string(o.frames) + ": expected at least 1");
    if (!o.screenshot.empty() && o.frames == 0 && o.script.empty()) o.frames = 30;
    if (!o.layout.empty() && o.screenshot.empty()) throw kdswap::Error("--layout needs --screenshot");
    if (app.count("--volume")) {
      if (volume.empty()) throw kdswap::Error("--volume: expected a file name");
      o.dataset = volume;
    }
    if (kdswap::isDatasetSpec(o.dataset)) kdswap::checkNoRawLayout(raw, "--dataset " + o.dataset);
    o.raw = kdswap::parseRawLayout(raw);  // also without --raw-*: a raw file missing its layout then names them
    return kdswap::runGui(o);
  } catch (const CLI::CallForHelp& e) {
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    std::fprintf(stderr, "kdswap-gui: %s\n", kdswap::printableText(e.what()).c_str());
    return 2;
  } catch (const kdswap::Error& e) {
    std::fprintf(stderr, "kdswap-gui: %s\n", kdswap::printableText(e.what()).c_str());
    return 2;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "kdswap-gui: unexpected error: %s\n", kdswap::printableText(e.what()).c_str());
    return 2;
  }
}
