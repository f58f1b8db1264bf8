// Kernel micro benchmarks: ray casting per core, over vs memcpy, binary-swap alone.
//   [1] ray casting   [2] over and copy   [3] binary-swap harness   [4] report
#include "core/bench/micro_bench.h"

#include <cstdio>
#include <cstddef>
#include <cstring>
#include <optional>
#include <vector>

#include <oneapi/tbb/task_arena.h>
#include <oneapi/tbb/task_group.h>

#include "core/bench/quantised_source.h"
#include "core/bench/statistics.h"
#include "core/cluster/node_arena.h"
#include "core/comm/inproc_network.h"
#include "core/composite/registry.h"
#include "core/render/ray_march.h"
#include "core/render/reference_render.h"
#include "core/transfer/presets.h"
#include "core/util/clock.h"
#include "core/util/error.h"
#include "core/volume/datasets/dataset.h"

namespace kdswap {
namespace {

// [1] One whole-volume brick rendered on one thread.
RayCastFigure castOnOneCore(const VolumeSource& source, const std::string& type, bool shaded, MarchFunction march,
                            VoxelChoice voxels, const MicroOptions& o) {
  const Brick brick = wholeVolumeBrick(source, Brick::kCellShiftByVolume, voxels);
  RenderSettings settings;
  settings.shading = shaded;
  settings.stepVoxels = 0.5f;
  const TransferFunction tf = loadTransferFunction(source.info().preset.empty() ? "grayscale" : source.info().preset);
  const TransferTable table(tf, settings.stepVoxels);
  RayCaster caster(brick, table, settings, resolveValueRange(settings, source.info()));
  caster.useMarch(march);
  const Camera camera(View{}, glm::vec3(0.0f), source.info().worldMax(), o.imageSize, o.imageSize);
  std::vector<double> rates;
  double samples = 0;
  tbb::task_arena single(1);
  single.execute([&] {
    for (int i = 0; i <= o.repeats; ++i) {
      RenderCounters counters;
      const double t0 = nowSeconds();
      Image image = caster.render(camera, counters);
      const double t = nowSeconds() - t0;
      if (i == 0) continue;  // warm-up
      samples = double(counters.samples);
      rates.push_back(t > 0 ? double(counters.samples) / t : 0.0);
    }
  });
  return RayCastFigure{type, shaded, brick.storage().compactFormat() ? "compact" : "float", marchName(march),
                       median(rates), samples};
}

void fillSynthetic(Image& image, int seed) {
  // Deterministic translucent pattern (premultiplied): alpha varies across the frame so `over`
  // cannot be short-cut by an all-opaque or all-empty test.
  Rgba* p = image.data();
  const int w = image.width(), h = image.height();
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const float a = float((x * 7 + y * 13 + seed * 29) % 97) / 128.0f;
      p[std::size_t(y) * w + x] = Rgba{0.5f * a, 0.3f * a, 0.8f * a, a};
    }
}

class IgnorePhases : public PhaseObserver {
 public:
  void beginPhase(std::string_view, int) override {}
  void endPhase(const Rect&, const Image&, std::int64_t) override {}
};

//! A plain copy of one buffer of `bytes`, timed one copy at a time: the yardstick compositing is
//! quoted against. The exchange harness sizes it to the bytes an exchange sends and times it right
//! after each exchange, so both see the same machine: this host's memory bandwidth drifts from
//! second to second (one 16 MiB image copied back to back measured 0.45 to 0.95 ms within an
//! hour), and a yardstick timed in other seconds than the runs it divides carries that drift into
//! the ratio. One buffer of the whole size, not one image copied again, so the copy is of memory,
//! as the exchange's is, not of what the last copy left in cache.
class TimedCopy {
 public:
  explicit TimedCopy(std::uint64_t bytes)
      : src_(std::size_t(bytes), std::byte{1}), dst_(std::size_t(bytes), std::byte{0}) {
    once();  // faults both buffers in
  }
  double once() {
    const double t0 = nowSeconds();
    std::memcpy(dst_.data(), src_.data(), src_.size());
    return nowSeconds() - t0;
  }

 private:
  std::vector<std::byte> src_, dst_;
};

//! memcpy of one full image's bytes (16 B a pixel), back to back, median of `repeats`.
double copySeconds(int width, int height, int repeats) {
  TimedCopy copy(std::uint64_t(width) * std::uint64_t(height) * sizeof(Rgba));
  std::vector<double> times;
  for (int i = 0; i < repeats; ++i) times.push_back(copy.once());
  return median(times);
}

}  // namespace

std::vector<RayCastFigure> measureRayCasting(const MicroOptions& o) {
  const std::string spec = "phantom:" + std::to_string(o.volumeSize);
  auto asFloat = openDataset(spec);
  QuantisedSource as8(openDataset(spec), 8), as16(openDataset(spec), 16);
  // The march renders use, the plain AVX2 build of it where that is not the one, and the scalar
  // reference beside them.
  std::vector<MarchFunction> marches{selectedMarchFunction()};
  if (avx2MarchFunction() && marches[0] != avx2MarchFunction() && marches[0] != &marchScalar)
    marches.push_back(avx2MarchFunction());
  if (marches[0] != &marchScalar) marches.push_back(&marchScalar);
  std::vector<RayCastFigure> out;
  auto rows = [&](MarchFunction march, VoxelChoice voxels) {  // shaded and unshaded, each data type
    for (bool shaded : {true, false}) {
      out.push_back(castOnOneCore(as8, "uint8", shaded, march, voxels, o));
      out.push_back(castOnOneCore(as16, "uint16", shaded, march, voxels, o));
      out.push_back(castOnOneCore(*asFloat, "float32", shaded, march, voxels, o));
    }
  };
  for (MarchFunction march : marches) rows(march, VoxelChoice::Float);
  rows(marches[0], VoxelChoice::Compact);  // large volumes' default, with the march renders use
  return out;
}

// [2] Two full frames composited with `over`, and the same bytes copied.
CompositeFigure measureOver(int width, int height, int repeats) {
  CompositeFigure f;
  f.width = width;
  f.height = height;
  Image back(Rect{0, 0, width, height}), front(Rect{0, 0, width, height});
  fillSynthetic(back, 2);
  fillSynthetic(front, 3);
  std::vector<double> times;
  for (int i = 0; i <= repeats; ++i) {
    Image dst = back;  // fresh each time so the values do not drift towards opaque
    const double t0 = nowSeconds();
    compositeInto(dst, front, true);
    const double t = nowSeconds() - t0;
    if (i > 0) times.push_back(t);
  }
  f.overSeconds = median(times);
  f.copySeconds = copySeconds(width, height, repeats);
  return f;
}

// [3] Binary-swap alone: every node starts with a full-frame synthetic partial image.
BinarySwapFigure measureBinarySwap(int nodes, int width, int height, int repeats) {
  return measureCompositing("binary-swap", nodes, width, height, repeats);
}

const std::vector<CompositingReference>& compositingReferences() {
  // Issue 8's measurements (P = 8: binary swap, radix-k, direct-send; P = 6: 2-3 swap and IceT's
  // telescoping), in seconds.
  static const std::vector<CompositingReference> refs{{"binary-swap", 8, 0.032}, {"radix-k", 8, 0.021},
                                                      {"direct-send", 8, 0.242}, {"2-3-swap", 6, 0.017},
                                                      {"telescoping", 6, 0.033}};
  return refs;
}

std::string formatCompositingTable(const std::vector<BinarySwapFigure>& figures) {
  std::string out =
      "Compositing strategies alone, full-frame synthetic partial images, wall time of all nodes on this\n"
      "machine's cores (as miniGraphics' ranks shared them), median; target: half of miniGraphics:\n"
      "  strategy       P   image       kdswap wall   max node   miniGraphics   target   result\n";
  char buf[256];
  for (const BinarySwapFigure& f : figures) {
    double reference = 0;
    for (const CompositingReference& r : compositingReferences())
      if (r.strategy == f.strategy && r.nodes == f.nodes) reference = r.miniGraphicsSeconds;
    std::snprintf(buf, sizeof buf, "  %-12s %3d   %4dx%-4d  %9.2f ms %8.2f ms", f.strategy.c_str(), f.nodes, f.width,
                  f.height, f.wallSeconds * 1e3, f.compositeMaxSeconds * 1e3);
    out += buf;
    if (reference > 0) {
      std::snprintf(buf, sizeof buf, "   %9.1f ms %6.1f ms   %s\n", reference * 1e3, reference * 0.5e3,
                    f.wallSeconds <= reference * 0.5 ? "MET" : "MISSED");
      out += buf;
    } else {
      out += "   (no reference)\n";
    }
  }
  return out;
}

BinarySwapFigure measureCompositing(const std::string& name, int nodes, int width, int height, int repeats,
                                    const CompositeOptions& options) {
  BinarySwapFigure f;
  f.strategy = name;
  f.nodes = nodes;
  f.width = width;
  f.height = height;
  const Rect frame{0, 0, width, height};
  // Ranks in order are front to back: valid for every strategy's tree, whose subtrees hold
  // consecutive ranks.
  const auto strategy = createStrategy(name, options);
  InprocNetwork network(nodes);
  VisibilityOrder order;
  for (int r = 0; r < nodes; ++r) order.frontToBack.push_back(r), order.position.push_back(r);
  std::vector<Image> source(static_cast<std::size_t>(nodes));
  for (int r = 0; r < nodes; ++r) {
    source[std::size_t(r)] = Image(frame);
    fillSynthetic(source[std::size_t(r)], r);
  }
  std::vector<double> maxima, walls, sentCopies;
  std::optional<TimedCopy> sentCopy;  // sized by the warm-up run's traffic
  NodeArena arena(0, nodes);  // as the clusters run their nodes
  for (int i = 0; i <= repeats; ++i) {
    network.reset();
    std::vector<Image> partial = source;  // copied outside the timed region
    std::vector<Tile> finished(static_cast<std::size_t>(nodes));  // and released outside it (with the buffers they share)
    std::vector<double> compute(std::size_t(nodes), 0.0);
    std::vector<std::uint64_t> sent(std::size_t(nodes), 0);
    const double t0 = nowSeconds();
    arena.execute([&] {
      tbb::task_group group;
      for (int r = 0; r < nodes; ++r)
        group.run([&, r] {
          InprocCommunicator comm(network, r);
          IgnorePhases phases;
          const double start = nowSeconds();
          try {
            finished[std::size_t(r)] = strategy->compose(std::move(partial[std::size_t(r)]), frame, order, comm, phases);
          } catch (const std::exception& e) {
            network.abort("node " + std::to_string(r) + ": " + e.what());
          }
          compute[std::size_t(r)] = nowSeconds() - start - comm.counters().waitSeconds;
          sent[std::size_t(r)] = comm.counters().bytesSent;
        });
      group.wait();
    });
    const double wall = nowSeconds() - t0;
    if (network.aborted()) throw Error(name + " harness: " + network.abortReason());
    f.bytesSent = 0;
    for (std::uint64_t b : sent) f.bytesSent += b;
    if (i == 0) {
      sentCopy.emplace(f.bytesSent);
      continue;
    }
    double m = 0;
    for (double c : compute) m = std::max(m, c);
    maxima.push_back(m);
    walls.push_back(wall);
    sentCopies.push_back(sentCopy->once());
  }
  f.compositeMaxSeconds = median(maxima);
  f.wallSeconds = median(walls);
  f.copySeconds = copySeconds(width, height, repeats);
  f.copySentSeconds = median(sentCopies);
  return f;
}

// [4]
std::string formatMicro(const std::vector<RayCastFigure>& rays, const CompositeFigure& over,
                        const BinarySwapFigure& swap, const MicroOptions& o) {
  std::string out;
  char buf[512];
  std::snprintf(buf, sizeof buf,
                "Ray casting, one core (tbb::task_arena(1)), phantom:%d, %dx%d, step 0.5, median of %d:\n",
                o.volumeSize, o.imageSize, o.imageSize, o.repeats);
  out += buf;
  for (const RayCastFigure& r : rays) {
    std::snprintf(buf, sizeof buf, "  %-8s %-9s %-8s %-13s %8.2f Msamples/s   (%.2f M samples per image)\n",
                  r.dataType.c_str(), r.shaded ? "shaded" : "unshaded", r.voxels.c_str(), r.march.c_str(),
                  r.samplesPerSecond * 1e-6, r.samples * 1e-6);
    out += buf;
  }
  out += "  note: uint8/uint16 is the source data quantised before distribution; the bricks hold float\n"
         "  (16 B: value + gradient as floats) or compact voxels (8 B: 16-bit integers, the default above\n"
         "  2^23 voxels), so rows of one storage differ only through the values (early ray termination,\n"
         "  empty-space skipping), and float against compact shows the cost of widening the integers on\n"
         "  a volume this size.\n\n";
  std::snprintf(buf, sizeof buf,
                "Compositing, one core, %dx%d premultiplied RGBA float (16 MiB per image), median of %d:\n"
                "  over (compositeInto)  %8.3f ms  %9.1f Mpixels/s\n"
                "  memcpy, same bytes    %8.3f ms  %9.1f Mpixels/s\n"
                "  over / copy           %8.2f x   (over reads two images and writes one; copy reads one)\n\n",
                over.width, over.height, o.compositingRepeats, over.overSeconds * 1e3, over.overPixelsPerSecond() * 1e-6,
                over.copySeconds * 1e3, over.copyPixelsPerSecond() * 1e-6,
                over.copySeconds > 0 ? over.overSeconds / over.copySeconds : 0.0);
  out += buf;
  std::snprintf(buf, sizeof buf,
                "Binary-swap alone, P=%d, %dx%d full-frame synthetic partial images, median of %d:\n"
                "  composite, max over nodes  %8.3f ms   (compose time minus time suspended waiting)\n"
                "  whole exchange, wall       %8.3f ms   (all %d nodes on this machine's cores)\n"
                "  memcpy of one image        %8.3f ms\n"
                "  composite max / copy       %8.2f x\n"
                "  bytes sent, all nodes      %8.1f MiB   (copying them: %.3f ms, one memcpy after each run)\n"
                "  wall / copy of bytes sent  %8.2f x\n",
                swap.nodes, swap.width, swap.height, o.compositingRepeats, swap.compositeMaxSeconds * 1e3, swap.wallSeconds * 1e3,
                swap.nodes, swap.copySeconds * 1e3,
                swap.copySeconds > 0 ? swap.compositeMaxSeconds / swap.copySeconds : 0.0,
                double(swap.bytesSent) / (1 << 20), swap.copySentSeconds * 1e3,
                swap.copySentSeconds > 0 ? swap.wallSeconds / swap.copySentSeconds : 0.0);
  out += buf;
  return out;
}

}  // namespace kdswap
