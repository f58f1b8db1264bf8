// `kdswap animate`: a camera path (orbit or key views) rendered on the virtual cluster as a
// numbered image sequence, with per-frame stats, resume after Ctrl-C, and an MP4 when ffmpeg exists.
#include <unistd.h>

#include <cmath>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>

#include "app/commands.h"
#include "app/scene_options.h"
#include "core/animation/camera_path.h"
#include "core/animation/progress_meter.h"
#include "core/animation/sequence_writer.h"
#include "core/cluster/lattice_passes.h"
#include "core/cluster/phase_grid.h"
#include "core/image/image_io.h"
#include "core/transfer/presets.h"
#include "core/util/error.h"
#include "core/volume/datasets/dataset.h"

namespace kdswap {
namespace {

struct AnimateOptions {
  SceneOptions scene;
  float orbit = 360.0f;
  int frames = 36;
  std::string elevationSweep, keys;
  std::string outDir = "animation", format = "png", stats;
  bool phases = false, resume = false, noVideo = false;
  float fps = 24.0f;
  int passes = 1;     //!< each frame the mean of this many passes on shifted lattices
  int stopAfter = 0;  //!< test hook: behave as if Ctrl-C came after this many rendered frames
};

volatile std::sig_atomic_t gInterrupted = 0;

//! Ctrl-C finishes the current frame; a second Ctrl-C kills at once (the default action).
void onInterrupt(int) {
  gInterrupted = 1;
  std::signal(SIGINT, SIG_DFL);
}

//! Installs onInterrupt for the duration of the run and restores the previous handler.
class InterruptGuard {
 public:
  InterruptGuard() {
    gInterrupted = 0;
    previous_ = std::signal(SIGINT, onInterrupt);
  }
  ~InterruptGuard() { std::signal(SIGINT, previous_); }

 private:
  void (*previous_)(int) = SIG_DFL;
};

std::string shellQuote(const std::string& s) {
  std::string q = "'";
  for (char c : s) q += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return q + "'";
}

//! This process's own command line plus --resume, from /proc; empty where /proc is missing.
std::string resumeCommand() {
  std::ifstream in("/proc/self/cmdline", std::ios::binary);
  std::string arg, line;
  bool hasResume = false;
  while (std::getline(in, arg, '\0')) {
    hasResume = hasResume || arg == "--resume";
    const bool plain = !arg.empty() && arg.find_first_not_of(
        "abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ0123456789-_.,/:=+") == std::string::npos;
    line += (line.empty() ? "" : " ") + (plain ? arg : shellQuote(arg));
  }
  return line.empty() || hasResume ? line : line + " --resume";
}

bool onPath(const std::string& program) {
  const char* path = std::getenv("PATH");
  std::stringstream dirs(path ? path : "");
  for (std::string dir; std::getline(dirs, dir, ':');)
    if (!dir.empty() && ::access((std::filesystem::path(dir) / program).c_str(), X_OK) == 0) return true;
  return false;
}

//! Encodes the PNG sequence as DIR/animation.mp4. Every path is single-quoted for the shell.
void encodeVideo(const SequenceWriter& writer, const AnimateOptions& o) {
  if (o.noVideo) return;
  if (!onPath("ffmpeg")) {
    std::fprintf(stderr, "ffmpeg not found on PATH: no MP4 written (the frames are in %s)\n", o.outDir.c_str());
    return;
  }
  if (o.format != "png") {
    std::fprintf(stderr, "no MP4 written: it is made from PNG frames (--format png)\n");
    return;
  }
  const std::string mp4 = (std::filesystem::path(o.outDir) / "animation.mp4").string();
  char rate[32];
  std::snprintf(rate, sizeof rate, "%g", o.fps);
  // Even width and height, 4:2:0 chroma: what common players accept from H.264/MPEG-4.
  const std::string command = "ffmpeg -nostdin -y -loglevel error -framerate " + std::string(rate) + " -i " +
                              shellQuote(writer.framePattern()) +
                              " -vf 'pad=ceil(iw/2)*2:ceil(ih/2)*2' -pix_fmt yuv420p " + shellQuote(mp4);
  const int status = std::system(command.c_str());
  if (status != 0) {
    std::fprintf(stderr, "kdswap: ffmpeg failed (status %d) making %s; the frames are complete\n", status, mp4.c_str());
    throw CommandExit{1};
  }
  std::printf("wrote %s\n", mp4.c_str());
}

CameraPath buildPath(const AnimateOptions& o, const std::vector<CameraKey>& keys, const View& base) {
  if (!o.keys.empty()) return CameraPath::fromKeys(base, keys, o.frames);
  std::optional<glm::vec2> sweep;
  if (!o.elevationSweep.empty()) {
    float from, to;
    char extra;
    if (std::sscanf(o.elevationSweep.c_str(), "%f,%f%c", &from, &to, &extra) != 2)
      throw Error("--elevation-sweep \"" + o.elevationSweep + "\": expected FROM,TO in degrees, e.g. -20,40");
    sweep = glm::vec2(from, to);
  }
  return CameraPath::orbit(base, o.orbit, o.frames, sweep);
}

//! What decides a frame's pixels; a resumed run keeps a frame only if all of this is unchanged.
nlohmann::json frameIdentity(const AnimateOptions& o, const PathFrame& f) {
  const SceneOptions& s = o.scene;
  nlohmann::json identity = {{"view", {{"azimuth", f.view.azimuthDeg}, {"elevation", f.view.elevationDeg}, {"distance", f.view.distance}}},
          {"tf", !f.tf.empty() ? f.tf : (!s.tf.empty() ? s.tf : "default")},
          {"render",
           {{"volume", !s.volume.empty() ? s.volume : (!s.dataset.empty() ? s.dataset : std::string(kDefaultDataset))},
            {"size", s.size}, {"fov", s.fov}, {"projection", s.projection}, {"up", s.up}, {"step", s.step},
            {"shading", s.shading}, {"jitter", s.jitter}, {"ert", s.ert}, {"range", s.range},
            {"nodes", s.nodes}, {"partition", s.partition}, {"composite", s.composite}, {"sparse", s.sparse}}}};
  // Only when used, so frames recorded before the option existed keep their identity.
  if (o.passes > 1) identity["render"]["passes"] = o.passes;
  return identity;
}

void printSummary(const SequenceWriter& writer, const VirtualCluster& cluster, const AnimateOptions& o) {
  const SequenceSummary s = summarizeSequence(writer.records());
  std::printf("animation: %d frames in %s (%s), P = %d, %s\n", s.frames, o.outDir.c_str(), o.format.c_str(),
              cluster.options().nodes, cluster.options().strategy.c_str());
  std::printf("  median frame wall time          %.4f s\n", s.medianWallSeconds);
  std::printf("  median modelled parallel time   %.4f s\n", s.medianModelledSeconds);
  std::printf("  data distribution (once)        %.4f s   (host cost, paper Table 5)\n", cluster.distributeSeconds());
  std::printf("  median image gather per frame   %.6f s   (host cost, paper Table 5)\n", s.medianGatherSeconds);
  std::printf("  stats: %s\n", writer.statsPath().c_str());
}

void run(const AnimateOptions& o) {
  if (o.frames < 1 || o.frames > kMaxAnimationFrames)
    throw Error("--frames " + std::to_string(o.frames) + ": must be from 1 to " + std::to_string(kMaxAnimationFrames));
  if (o.format != "png" && o.format != "exr") throw Error("--format \"" + o.format + "\": expected png or exr");
  if (!(o.fps > 0.0f && o.fps <= 240.0f)) throw Error("--fps must be in (0, 240]");
  if (!(std::fabs(o.orbit) <= kMaxOrbitDegrees)) throw Error("--orbit: degrees must be from -36000 to 36000 (100 turns)");
  checkOutputFolder(o.outDir, "--out-dir");  // before any frame, not after the first render
  const std::vector<CameraKey> keys = o.keys.empty() ? std::vector<CameraKey>{} : loadCameraKeys(o.keys);
  Scene scene = buildScene(o.scene);
  const CameraPath path = buildPath(o, keys, scene.request.view);
  std::map<std::string, TransferFunction> transfers;  // loaded up front: a bad name fails before any frame
  for (const std::string& name : path.transferFunctions())
    transfers.emplace(name, loadTransferOption(name, "--keys " + o.keys + ": \"tf\""));

  SequenceOptions so{o.outDir, o.format, o.stats, o.frames, o.resume, {}};
  so.identity = [&](int i) { return frameIdentity(o, path.frame(i)); };
  SequenceWriter writer(so);
  std::vector<int> todo;
  for (int i = 0; i < o.frames; ++i)
    if (!writer.isDone(i) || (o.phases && !std::filesystem::exists(writer.phasesPath(i)))) todo.push_back(i);
  if (o.resume) std::fprintf(stderr, "resume: %d of %d frames already done\n", o.frames - int(todo.size()), o.frames);
  if (writer.staleRemoved() > 0)
    std::fprintf(stderr, "removed %d pictures of an earlier run from %s (frames this run does not make)\n",
                 writer.staleRemoved(), o.outDir.c_str());

  // The one distribution of the data (paper Table 5); from here on only the view and TF change.
  VirtualCluster cluster(*scene.source, scene.cluster);
  scene.request.recordPhases = o.phases;
  const TransferFunction baseTransfer = scene.request.transfer;
  ProgressMeter progress(stderr, ::isatty(fileno(stderr)), o.frames, o.frames - int(todo.size()));
  InterruptGuard guard;
  int rendered = 0;
  for (int i : todo) {
    const PathFrame& f = path.frame(i);
    scene.request.view = f.view;
    scene.request.transfer = f.tf.empty() ? baseTransfer : transfers.at(f.tf);
    const FrameResult frame = renderPasses(cluster, scene.request, o.passes).frame;
    writeImage(writer.framePath(i), frame.image);
    if (frame.phases) writeImage(writer.phasesPath(i), drawPhaseGrid(*frame.phases, frame.image));
    nlohmann::json line = frame.stats.toJson();
    line.update(frameIdentity(o, f));
    line["frame"] = i;
    line["file"] = std::filesystem::path(writer.framePath(i)).filename().string();
    writer.record(line);  // last: a recorded frame has all its files
    progress.frameDone();
    if (gInterrupted || (o.stopAfter > 0 && ++rendered >= o.stopAfter)) {
      progress.finish();
      const int done = int(writer.records().size());
      std::fprintf(stderr, "interrupted: %d of %d frames done in %s; to continue run:\n  %s\n", done, o.frames,
                   o.outDir.c_str(), resumeCommand().empty() ? "the same command with --resume" : resumeCommand().c_str());
      throw CommandExit{130};
    }
  }
  progress.finish();
  printSummary(writer, cluster, o);
  encodeVideo(writer, o);
}

}  // namespace

void addAnimateCommand(CLI::App& app) {
  auto options = std::make_shared<AnimateOptions>();
  CLI::App* cmd = app.add_subcommand("animate", "Render a camera path on P virtual nodes as an image sequence");
  cmd->footer(
      "The data are distributed once; each frame changes only the view (and the transfer function).\n"
      "Output: DIR/frame_0000.png ... (or .exr), DIR/stats.jsonl (one FrameStats JSON per line plus\n"
      "\"frame\", \"view\", \"tf\"), DIR/phases_0000.png with --phases, DIR/animation.mp4 if ffmpeg is on PATH.\n"
      "Ctrl-C stops after the current frame (exit 130); add --resume to the same command to continue.\n"
      "\n"
      "Orbit: frame i looks from azimuth AZ + DEGREES * i / FRAMES (--view gives AZ,EL), so 360 loops.\n"
      "--elevation-sweep FROM,TO moves the elevation from FROM (first frame) to TO (last frame).\n"
      "\n"
      "Key file (--keys): a JSON list of keys, or {\"keys\": [...]}, spread evenly over --frames (first key at\n"
      "the first frame, last key at the last) and interpolated linearly. Each key may give\n"
      "  \"azimuth\" (degrees, -36000..36000, not wrapped: 0 then 360 is a full turn), \"elevation\" (degrees, in (-90, 90)),\n"
      "  \"distance\" (bounding-sphere radii), \"tf\" (preset or JSON file, relative to the key file;\n"
      "  switches from that key's frame on).  Missing values repeat the previous key's (first: --view).\n"
      "  [{\"azimuth\": 0, \"elevation\": 10, \"distance\": 3},\n"
      "   {\"azimuth\": 180, \"elevation\": 40, \"tf\": \"ct-bone\"},\n"
      "   {\"azimuth\": 360, \"elevation\": 10, \"distance\": 2}]\n"
      "\n"
      "Examples:\n"
      "  kdswap animate --nodes 8 --orbit 360 --frames 72 --out-dir orbit\n"
      "  kdswap animate --dataset vessels:128 --keys tour.json --frames 120 --phases --out-dir tour\n"
      "  kdswap animate --nodes 8 --orbit 360 --frames 72 --out-dir orbit --resume\n");
  addSceneOptions(cmd, options->scene);
  addClusterOptions(cmd, options->scene);
  CLI::Option* orbit =
      cmd->add_option("--orbit", options->orbit, "Orbit this many degrees around the up axis (-36000..36000: up to 100 turns)")->capture_default_str();
  CLI::Option* sweep = cmd->add_option("--elevation-sweep", options->elevationSweep,
                                       "Orbit: elevation from FROM to TO degrees over the sequence, each in (-90, 90), e.g. -20,40")
                          ->check(nonEmpty());
  cmd->add_option("--keys", options->keys, "Key views from a JSON file (format below)")
      ->check(nonEmpty())
      ->excludes(orbit)
      ->excludes(sweep);
  cmd->add_option("--frames", options->frames, "Number of frames (1..100000)")->capture_default_str();
  cmd->add_option("--out-dir", options->outDir, "Folder for the frames, stats and video")
      ->check(nonEmpty())
      ->capture_default_str();
  cmd->add_option("--format", options->format, "Frame format: png (8-bit over black) or exr (float RGBA)")
      ->capture_default_str();
  cmd->add_option("--stats", options->stats, "Per-frame stats as JSON lines (default DIR/stats.jsonl)")->check(nonEmpty());
  cmd->add_option("--passes", options->passes,
                  "Each frame the mean of N passes on shifted sampling lattices (1..256; grain and rings average "
                  "out, N times the time; stats and stages: the first pass)")
      ->check(CLI::Range(1, kMaxLatticePasses))
      ->capture_default_str();
  cmd->add_flag("--phases", options->phases, "Also write each frame's compositing stages (Figure 6) as DIR/phases_NNNN.png");
  cmd->add_flag("--resume", options->resume, "Continue a stopped sequence: keep frames already written and recorded");
  cmd->add_option("--fps", options->fps, "Frame rate of the MP4, in (0, 240]")->capture_default_str();
  cmd->add_flag("--no-video", options->noVideo, "Do not make the MP4 even if ffmpeg is on PATH");
  cmd->add_option("--stop-after", options->stopAfter, "Testing: stop as if interrupted after K rendered frames")
      ->group("");
  cmd->callback([options] { run(*options); });
}

}  // namespace kdswap
