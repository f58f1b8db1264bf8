// kdswap-mpi: `mpirun -np R kdswap-mpi render ...` runs the node program on R MPI ranks, K virtual
// nodes each (P = R x K). Every rank parses the same command line into the same FrameRequest (no
// broadcast needed); rank 0 is also the host: it writes the image and the stats.
#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <memory>
#include <optional>
#include <vector>

#include <CLI/CLI.hpp>
// The C API only: Open MPI's deprecated C++ bindings would need libmpi_cxx.
#define OMPI_SKIP_MPICXX 1
#define MPICH_SKIP_MPICXX 1
#include <mpi.h>
#include <nlohmann/json.hpp>

#include "app/output_files.h"
#include "app/scene_options.h"
#include "core/bench/statistics.h"
#include "core/cluster/lattice_passes.h"
#include "core/cluster/mpi_cluster.h"
#include "core/comm/mpi_agreement.h"
#include "core/image/image_average.h"
#include "core/image/image_io.h"
#include "core/render/reference_render.h"
#include "core/render/voxel_ray.h"
#include "core/util/error.h"
#include "core/util/file_writer.h"
#include "core/util/memory.h"
#include "core/util/printable_text.h"

namespace kdswap {
namespace {

struct MpiRenderOptions {
  SceneOptions scene;
  int nodesPerRank = 1;
  double stallSeconds = 60.0;
  std::string out = "render.png";
  std::string stats;
  bool verify = false;
  bool quiet = false;
  int frames = 1;          //!< measured frames; above 1, after one warm-up frame
  float orbitDeg = 1.0f;   //!< the view's turn per frame (azimuth), with frames > 1
  bool orbitGiven = false;
  int passes = 1;          //!< each frame the mean of this many passes on shifted lattices
};

//! Rank 0: the measured frames' figures, one per frame, and their medians ("frames" in the stats).
nlohmann::json framesJson(const std::vector<FrameStats>& measured, float orbitDeg) {
  std::vector<double> wall, render, composite, modelled;
  for (const FrameStats& f : measured) {
    wall.push_back(f.wallSeconds), render.push_back(f.renderMax()), composite.push_back(f.compositeMax());
    modelled.push_back(f.modelledParallelSeconds());
  }
  return {{"count", measured.size()}, {"warm_up", 1}, {"orbit_deg", orbitDeg},
          {"wall_s", wall}, {"render_s_max", render}, {"composite_s_max", composite},
          {"modelled_parallel_s", modelled},
          {"median", {{"wall_s", median(wall)}, {"render_s_max", median(render)},
                      {"composite_s_max", median(composite)}, {"modelled_parallel_s", median(modelled)}}}};
}

constexpr float kVerifyTolerance = 1e-5f;

//! Collective: ranks that disagree on K would number the nodes differently and wait for messages
//! that never come. Returns the problem on every rank alike (empty when they agree).
std::string nodesPerRankDisagreement(int nodesPerRank, int ranks) {
  std::vector<int> all(std::size_t(ranks), 0);
  MPI_Allgather(&nodesPerRank, 1, MPI_INT, all.data(), 1, MPI_INT, MPI_COMM_WORLD);
  for (int r = 1; r < ranks; ++r)
    if (all[std::size_t(r)] != all[0])
      return "--nodes-per-rank: " + std::to_string(all[std::size_t(r)]) + " on rank " + std::to_string(r) + ", " +
             std::to_string(all[0]) + " on rank 0: every rank must be started with the same value";
  return "";
}

//! This rank's options, before the network starts (throws kdswap::Error).
void checkRankOptions(MpiRenderOptions& o, int ranks, bool nodesGiven) {
  if (o.nodesPerRank < 1 || std::int64_t(o.nodesPerRank) * ranks > kMaxNodes)
    throw Error("--nodes-per-rank " + std::to_string(o.nodesPerRank) + ": ranks (" + std::to_string(ranks) +
                ") x nodes per rank must be from 1 to " + std::to_string(kMaxNodes));
  if (nodesGiven && o.scene.nodes != ranks * o.nodesPerRank)
    throw Error("--nodes " + std::to_string(o.scene.nodes) + ": must equal MPI ranks (" + std::to_string(ranks) +
                ") x --nodes-per-rank (" + std::to_string(o.nodesPerRank) + "); or leave it out");
  if (!(o.stallSeconds > 0)) throw Error("--stall-seconds must be > 0");
  if (o.frames < 1 || o.frames > 100000) throw Error("--frames " + std::to_string(o.frames) + ": expected 1 to 100000");
  if (!(o.orbitDeg >= -360.0f && o.orbitDeg <= 360.0f)) {
    char value[32];
    std::snprintf(value, sizeof value, "%g", double(o.orbitDeg));
    throw Error(std::string("--orbit ") + value + ": expected degrees from -360 to 360");
  }
  if (o.orbitGiven && o.frames < 2) throw Error("--orbit turns the view between frames: give --frames 2 or more");
  if (o.passes < 1 || o.passes > kMaxLatticePasses)
    throw Error("--passes " + std::to_string(o.passes) + ": expected 1 to " + std::to_string(kMaxLatticePasses));
  o.scene.nodes = ranks * o.nodesPerRank;
}

//! Rank 0, after a successful frame: image, table, optional verification and stats. Returns the
//! exit code (1: verification failed).
int writeResults(const MpiRenderOptions& o, const Scene& scene, const MpiFrameOutcome& outcome,
                 const std::vector<FrameStats>& measured, double passesWall) {
  const FrameResult& frame = outcome.result;
  writeImage(o.out, frame.image);
  nlohmann::json stats = outcome.statsJson();
  if (measured.size() > 1) stats["frames"] = framesJson(measured, o.orbitDeg);
  if (o.passes > 1) stats["passes"] = {{"count", o.passes}, {"wall_s", passesWall}};
  if (!o.quiet) {
    std::printf("%s  over %d MPI rank(s) x %d node(s) per rank\n", formatFrameTable(frame.stats).c_str(),
                outcome.ranks, outcome.nodesPerRank);
    if (o.passes > 1)
      std::printf("  %d passes averaged, lattice shifted by the R1 sequence; wall %.2f s in all (the table: pass 1)\n",
                  o.passes, passesWall);
    if (measured.size() > 1) {
      const nlohmann::json& m = stats["frames"]["median"];
      std::printf("medians of %zu frames after a warm-up (view turning %g deg a frame; the table is the last "
                  "frame's):\n  wall %.2f ms, render max %.2f ms, composite max %.2f ms, modelled parallel %.2f ms\n",
                  measured.size(), double(o.orbitDeg), m["wall_s"].get<double>() * 1e3,
                  m["render_s_max"].get<double>() * 1e3, m["composite_s_max"].get<double>() * 1e3,
                  m["modelled_parallel_s"].get<double>() * 1e3);
    }
    std::printf("wrote %s\n", o.out.c_str());
  }
  bool verified = true;
  if (o.verify) {
    // The reference reads the whole volume, on rank 0 only; with passes, the mean of the same passes.
    const FrameRequest& r = scene.request;
    const Brick whole = wholeVolumeBrick(*scene.source, Brick::kCellShiftByVolume, scene.cluster.voxels);
    const Image reference =
        referencePasses(whole, r, resolveValueRange(r.settings, scene.source->info()), o.passes);
    const float diff = maxAbsDifference(frame.image, reference, frame.image.rect());
    const float ert = r.settings.earlyTermination;
    const float tolerance = ert < 1.0f ? kVerifyTolerance + (1.0f - ert) : kVerifyTolerance;
    verified = diff <= tolerance;
    stats["verify"] = {{"max_abs_diff", diff}, {"tolerance", tolerance}, {"passed", verified}};
    std::printf("verify: max |distributed - single node| = %.4g (tolerance %.4g): %s\n", diff, tolerance,
                verified ? "OK" : "FAILED");
  }
  if (!o.stats.empty()) {
    writeFileAtomically(o.stats, stats.dump(2) + "\n");
  }
  return verified ? 0 : 1;
}

//! Every rank. Returns the exit code rank 0 decided (all ranks return the same). Problems before
//! the frame are agreed among the ranks (they throw the same kdswap::Error on every rank).
int run(MpiRenderOptions& o, const MpiSession& session, bool nodesGiven) {
  const int ranks = session.size(), rank = session.rank();
  std::string problem = nodesPerRankDisagreement(o.nodesPerRank, ranks);
  Scene scene;
  if (problem.empty()) try {
      checkRankOptions(o, ranks, nodesGiven);
      if (rank == 0) {  // rank 0 writes them
        if (!isSupportedImagePath(o.out))
          throw Error("--out " + o.out + ": unsupported image extension (expected .png, .exr, .tif, .tiff or .jpg)");
        checkOutputFiles({{"--out", o.out}, {"--stats", o.stats}}, {o.scene.volume, existingFileOrEmpty(o.scene.tf)});
      }
      scene = buildScene(o.scene);  // opens the volume on this rank: headers only for plain files
    } catch (const std::exception& e) {
      problem = e.what();
    }
  const std::string first = firstProblemOfAnyRank(problem);
  if (!first.empty()) throw Error(first);
  const std::unique_ptr<MpiRankFrame> frame = prepareRankFrame(*scene.source, scene.request, scene.cluster, o.nodesPerRank);

  // With --frames N > 1: a warm-up frame (caches, first-touch pages, pooled buffers), then N
  // measured ones, the first at the requested view, each turned --orbit degrees further. With
  // --passes N each frame is the mean of N passes, pass i on the lattice shifted by
  // latticePassShift(i), as kdswap render's; a frame's figures are its first pass's. The bricks
  // stay loaded; each pass runs over its own network.
  const int total = o.frames > 1 ? o.frames + 1 : 1;
  const View firstView = scene.request.view;
  std::vector<FrameStats> measured;
  MpiFrameOutcome outcome;  // rank 0: the last frame's first pass, its image the passes' mean
  double passesWall = 0;    // the last frame's passes
  int code = 0;
  for (int f = 0; f < total && code == 0; ++f) {
    View view = firstView;
    view.azimuthDeg += o.orbitDeg * float(std::max(f - 1, 0));
    ImageAverage mean(o.passes > 1 && rank == 0 ? Rect{0, 0, scene.request.width, scene.request.height} : Rect{});
    passesWall = 0;
    for (int pass = 0; pass < o.passes && code == 0; ++pass) {
      if (f > 0 || pass > 0) {
        std::string viewProblem;  // agreed, as every problem between frames, so no rank waits alone
        try {
          frame->setView(view, latticePassShift(pass));
        } catch (const std::exception& e) {
          viewProblem = e.what();
        }
        const std::string agreed = firstProblemOfAnyRank(viewProblem);
        if (!agreed.empty()) throw Error(agreed);
      }
      MpiNetwork network(o.nodesPerRank, o.stallSeconds);
      MpiFrameOutcome passOutcome = renderFrameOverMpi(network, *frame);
      // Rank 0 decides: a failure anywhere reaches the host, which names it.
      int ok = passOutcome.ok ? 1 : 0;
      MPI_Bcast(&ok, 1, MPI_INT, 0, MPI_COMM_WORLD);
      if (!ok) {
        if (rank == 0) std::fprintf(stderr, "kdswap-mpi: %s\n", oneLine(passOutcome.error).c_str());
        code = 2;
      } else if (rank == 0) {
        passesWall += passOutcome.result.stats.wallSeconds;
        if (o.passes > 1) mean.add(passOutcome.result.image);
        if (pass == 0) outcome = std::move(passOutcome);
      }
    }
    if (code != 0 || rank != 0) continue;
    if (o.passes > 1) outcome.result.image = mean.mean();
    if (total == 1 || f > 0) {
      measured.push_back(outcome.result.stats);
      if (total > 1 && !o.quiet)
        std::printf("frame %d/%d: wall %.2f ms\n", f, total - 1, outcome.result.stats.wallSeconds * 1e3);
    }
  }
  scene.request.view = frame->request.view;  // --verify checks the last frame
  if (code == 0 && rank == 0) {
    try {
      code = writeResults(o, scene, outcome, measured, passesWall);
    } catch (const std::exception& e) {
      std::fprintf(stderr, "kdswap-mpi: %s\n", oneLine(e.what()).c_str());
      code = 2;
    }
  }
  MPI_Bcast(&code, 1, MPI_INT, 0, MPI_COMM_WORLD);
  return code;
}

}  // namespace
}  // namespace kdswap

using kdswap::oneLine;

int main(int argc, char** argv) {
  kdswap::configureMalloc();  // before any thread allocates (core/util/memory.h)
  std::unique_ptr<kdswap::MpiSession> session;
  try {
    session = std::make_unique<kdswap::MpiSession>(argc, argv);
  } catch (const kdswap::Error& e) {
    std::fprintf(stderr, "kdswap-mpi: %s\n", oneLine(e.what()).c_str());
    return 2;
  }
  const bool root = session->rank() == 0;
  CLI::App app{"kdswap-mpi: the kdswap node program on MPI ranks (mpirun -np R kdswap-mpi render ...)"};
  app.require_subcommand(1);
  // Only `render` runs over MPI; name it rather than CLI11's "A subcommand is required".
  if (argc == 1 || (argv[1][0] != '-' && std::string(argv[1]) != "render")) {
    const std::string problem =
        argc == 1
            ? std::string("give the subcommand render (mpirun -np R kdswap-mpi render ...; kdswap-mpi render --help)")
            : std::string("unknown subcommand \"") + argv[1] +
                  "\": kdswap-mpi has only render (bench, animate, export and info are kdswap's)";
    const std::string first = kdswap::firstProblemOfAnyRank(problem);
    if (root) std::fprintf(stderr, "kdswap-mpi: %s\n", oneLine(first).c_str());
    return 2;
  }
  kdswap::MpiRenderOptions o;
  CLI::App* cmd = app.add_subcommand("render", "Render one frame on R ranks x K nodes and write the image on rank 0");
  kdswap::addSceneOptions(cmd, o.scene);
  kdswap::addClusterOptions(cmd, o.scene);
  // The virtual cluster's options that the MPI node program does not carry out: hidden from the
  // help and refused below, never silently ignored.
  const char* const virtualOnly[] = {"--stall-timeout", "--checksums", "--node-execution", "--inject-fault", "--waves"};
  for (const char* name : virtualOnly) cmd->get_option(name)->group("");
  cmd->add_option("--nodes-per-rank,-k", o.nodesPerRank, "Virtual nodes K on each rank: P = ranks x K")
      ->capture_default_str();
  cmd->add_option("--stall-seconds", o.stallSeconds, "Abort when nodes wait with no traffic this long")
      ->capture_default_str();
  cmd->add_option("--frames", o.frames,
                  "Render this many measured frames (1..100000) after a warm-up frame, the view turning --orbit "
                  "degrees a frame; prints and writes (--stats \"frames\") their medians; the image is the last")
      ->capture_default_str();
  cmd->add_option("--orbit", o.orbitDeg, "With --frames: degrees the view turns per frame (azimuth), -360..360")
      ->capture_default_str();
  cmd->add_option("--passes", o.passes,
                  "Each frame the mean of N passes on shifted sampling lattices (1..256), as kdswap render "
                  "--passes: N frames' time for a picture without the sampling's grain")
      ->capture_default_str();
  cmd->add_option("--out,-o", o.out, "Output image, by extension: .png, .exr, .tif, .tiff or .jpg, written by rank 0")
      ->capture_default_str();
  cmd->add_option("--stats", o.stats, "Write the frame's figures as JSON (kdswap render keys + per_rank)");
  cmd->add_flag("--verify", o.verify, "Also render the single-node reference on rank 0; exit 1 if they differ");
  cmd->add_flag("--quiet,-q", o.quiet, "Print nothing but errors and the verify line");
  // Every rank parses its own command line (an MPMD launch gives each its own); they agree on
  // stopping before any traffic.
  std::optional<CLI::CallForHelp> help;
  std::optional<CLI::CallForAllHelp> allHelp;
  std::string problem;
  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp& e) {
    help = e;
  } catch (const CLI::CallForAllHelp& e) {
    allHelp = e;
  } catch (const CLI::ParseError& e) {
    problem = e.what();
  }
  if (problem.empty() && !help && !allHelp)
    for (const char* name : virtualOnly)
      if (cmd->get_option(name)->count() > 0) {
        problem = std::string(name) + " is not supported over MPI ranks (kdswap render has it)" +
                  (std::string(name) == "--stall-timeout" ? "; use --stall-seconds" : "");
        break;
      }
  // Collective from here: a rank that stopped alone would leave the others waiting in MPI.
  const std::string first = kdswap::firstProblemOfAnyRank(problem);
  if (!first.empty()) {
    if (root) std::fprintf(stderr, "kdswap-mpi: %s\n", oneLine(first).c_str());
    return 2;
  }
  const int asking = kdswap::firstRankWith(help || allHelp);
  if (asking >= 0) {
    if (session->rank() == asking) help ? app.exit(*help) : app.exit(*allHelp);
    return 0;
  }
  try {
    o.orbitGiven = cmd->get_option("--orbit")->count() > 0;
    return kdswap::run(o, *session, cmd->get_option("--nodes")->count() > 0);
  } catch (const std::exception& e) {
    // Problems before the frame are agreed among the ranks (the same message on every rank), and
    // the frame's own are in its outcome: rank 0 reports them.
    if (root) std::fprintf(stderr, "kdswap-mpi: %s\n", oneLine(e.what()).c_str());
    return 2;
  }
}
