// The GUI's logic that needs no window: the histogram under the transfer-function editor, the
// speedup sweep's warm-up and medians, error text safe to print, the data-set error messages, the
// data panel's raw-layout fields, the timeline's bars, rows and ticks, and the render worker's
// refinement of a still frame.
#define DOCTEST_CONFIG_IMPLEMENT_WITH_MAIN
#include <doctest/doctest.h>

#include <chrono>
#include <cmath>
#include <map>
#include <string>
#include <thread>
#include <vector>

#include "core/transfer/presets.h"
#include "core/util/error.h"
#include "core/volume/datasets/dataset.h"
#include "core/volume/memory_volume.h"
#include "ui/histogram.h"
#include "ui/raw_layout_fields.h"
#include "core/util/printable_text.h"
#include "ui/render_worker.h"
#include "ui/sweep_worker.h"
#include "ui/timeline_layout.h"
#include "ui/window_size.h"

namespace kdswap {
namespace {

// A 16 x 16 x 16 volume whose voxels run through `values` over and over.
MemoryVolume volumeOf(const std::vector<float>& values, const std::string& type) {
  VolumeInfo info;
  info.dims = glm::ivec3(16);
  info.type = type;
  std::vector<float> voxels(16 * 16 * 16);
  for (std::size_t i = 0; i < voxels.size(); ++i) voxels[i] = values[i % values.size()];
  return MemoryVolume(info, voxels);
}

std::string errorOf(const std::string& spec) {
  try {
    openVolumeSpec(spec);
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

}  // namespace

TEST_CASE("gui scene: load balance and bricks per node rebuild the cluster, other edits do not") {
  SceneSpec a;
  SceneSpec b = a;
  CHECK(a.sameScene(b));
  b.cluster.bricksPerNode = 4;
  CHECK_FALSE(a.sameScene(b));  // over-decomposition cuts the bricks anew
  b = a;
  useCostBalance(b.cluster, loadTransferFunction("phantom"));
  CHECK(b.cluster.balance == "cost");
  CHECK_FALSE(a.sameScene(b));  // the planes move
  SceneSpec c = b;
  CHECK(b.sameScene(c));
  useCostBalance(c.cluster, loadTransferFunction("grayscale"));
  CHECK_FALSE(b.sameScene(c));  // another transfer function, other planes
  // With halved space the transfer function kept for cost balance does not matter.
  c.cluster.balance = b.cluster.balance = "space";
  CHECK(b.sameScene(c));
}

TEST_CASE("gui scene: a new layout for the raw file shown rebuilds it, a layout for another file does not") {
  SceneSpec a;
  a.data = a.rawPath = "scan.raw";
  a.raw.dims = glm::ivec3(8, 8, 5);
  SceneSpec b = a;
  b.raw.dims = glm::ivec3(8, 8, 4);
  CHECK_FALSE(a.sameScene(b));  // also retries a layout that failed
  a.data = b.data = "phantom:32";
  CHECK(a.sameScene(b));
}

TEST_CASE("gui raw layout fields: filled from the layout given before, else from the file name, else left") {
  const std::map<std::string, RawLayout> none;
  const auto named = knownRawLayout("data/head_256x256x113_UINT16.RAW", none);
  REQUIRE(named);
  CHECK(named->dims[0] == 256);
  CHECK(named->dims[2] == 113);
  CHECK(named->type == ScalarType::Uint16);
  CHECK_FALSE(named->bigEndian);
  CHECK(named->spacing[2] == 1.0f);
  CHECK(named->headerBytes == 0);
  CHECK_FALSE(knownRawLayout("scan.raw", none));  // the user's fields stay
  const auto huge = knownRawLayout("head_99999999999x2x2_uint8.raw", none);  // opening names the overflow
  REQUIRE(huge);
  CHECK(huge->dims[0] == 0);
  CHECK(huge->type == ScalarType::Uint8);

  // The start-up --raw-* options win over the name; what they leave out comes from it.
  RawLayout given;
  given.type = "float32";
  given.bigEndian = true;
  given.spacing = glm::vec3(1, 1, 2.5f);
  given.headerBytes = 64;
  const auto both = knownRawLayout("head_256x256x113_uint16.raw", {{"head_256x256x113_uint16.raw", given}});
  REQUIRE(both);
  CHECK(both->dims[1] == 256);
  CHECK(both->type == ScalarType::Float32);
  CHECK(both->bigEndian);
  CHECK(both->spacing[2] == 2.5f);
  CHECK(both->headerBytes == 64);

  // Every field reaches the layout the file is opened with.
  const RawLayout layout = toRawLayout(*both);
  CHECK(layout.dims == glm::ivec3(256, 256, 113));
  CHECK(layout.type == "float32");
  CHECK(layout.bigEndian == true);
  CHECK(layout.spacing == glm::vec3(1, 1, 2.5f));
  CHECK(layout.headerBytes == 64);
}

TEST_CASE("gui histogram: integer values 0..254 get one bin each and no bin is empty") {
  std::vector<float> values;
  for (int v = 0; v <= 254; ++v) values.push_back(float(v));
  const Histogram h = computeHistogram(volumeOf(values, "uint8"), 256);
  REQUIRE(h.bins.size() == 255);
  CHECK(h.valuesPerBin == 1);
  for (float b : h.bins) CHECK(b > 0.95f);  // every value about equally often (16 or 17 voxels)
  // Bin edges at half-integers: value v's bin is centred on v / 254 on the editor's axis.
  CHECK(h.x0 == doctest::Approx(-0.5 / 254));
  CHECK(h.x1 == doctest::Approx(254.5 / 254));
}

TEST_CASE("gui histogram: a wide integer range groups the same number of values in every bin") {
  std::vector<float> values;
  for (int v = -1024; v <= 3071; ++v) values.push_back(float(v));  // CT-like, 4096 values
  const Histogram h = computeHistogram(volumeOf(values, "int16"), 256);
  REQUIRE(h.bins.size() == 256);
  CHECK(h.valuesPerBin == 16);
  for (float b : h.bins) CHECK(b == doctest::Approx(1.0f));
}

TEST_CASE("gui histogram: non-integer data keeps equal bins over the value range") {
  std::vector<float> values;
  for (int v = 0; v < 1000; ++v) values.push_back(float(v) * 0.001f + 0.0005f);
  const Histogram h = computeHistogram(volumeOf(values, "float32"), 256);
  CHECK(h.bins.size() == 256);
  CHECK(h.valuesPerBin == 0);
  CHECK(h.x0 == 0.0f);
  CHECK(h.x1 == 1.0f);
}

TEST_CASE("gui error text: binary bytes are escaped, UTF-8 and newlines kept") {
  CHECK(printableText("plain text\nline 2") == "plain text\nline 2");
  CHECK(printableText("caf\xC3\xA9.nhdr") == "caf\xC3\xA9.nhdr");
  CHECK(printableText(std::string("\xCF\x70\xE1\xF3\x8F\x1D\x00 x", 9)) == "\\xCFp\\xE1\\xF3\\x8F\\x1D\\x00 x");
  CHECK(printableText("\x1B[2J") == "\\x1B[2J");  // a terminal escape sequence stays inert
  CHECK(printableText("\xC2\x9B") == "\\xC2\\x9B");  // C1 control (CSI)
  CHECK(printableText("a\xE2\x80\xAE" "b") == "a\\xE2\\x80\\xAEb");  // right-to-left override
}

TEST_CASE("gui data spec errors name the built-in data sets") {
  const std::string unknown = errorOf("foo");
  CHECK(unknown.find("\"foo\": no such file, and not a built-in data set") == 0);
  for (const std::string& name : datasetNames()) CHECK(unknown.find(name) != std::string::npos);
  const std::string empty = errorOf("");
  CHECK(empty.find("no data set given") == 0);
  CHECK(empty.find("phantom") != std::string::npos);
  CHECK(errorOf("phantom:24").empty());
}

TEST_CASE("gui speedup sweep: a warm-up frame, then the median of several frames per node count") {
  std::shared_ptr<const VolumeSource> source = openDataset("phantom:24");
  ClusterOptions options;
  FrameRequest request;
  request.width = request.height = 48;
  request.transfer = loadTransferFunction("phantom");
  SweepWorker sweep;
  sweep.start(source, options, request, {1, 2, 4}, 3);
  for (int i = 0; i < 600 && sweep.running(); ++i) std::this_thread::sleep_for(std::chrono::milliseconds(100));
  REQUIRE_FALSE(sweep.running());
  CHECK(sweep.error().empty());
  CHECK(sweep.progress() == doctest::Approx(1.0f));
  CHECK(sweep.framesPerPoint() == 3);
  const std::vector<SweepPoint> points = sweep.points();
  REQUIRE(points.size() == 3);
  for (std::size_t i = 0; i < points.size(); ++i) {
    CHECK(points[i].nodes == (1 << i));
    CHECK(points[i].frames == 3);
    CHECK(points[i].modelledSeconds > 0);
    CHECK(points[i].modelledMin <= points[i].modelledSeconds);
    CHECK(points[i].modelledSeconds <= points[i].modelledMax);
  }
}

namespace {

//! Polls `worker` until it is idle (at most 60 s) and returns the last frame it published.
std::shared_ptr<const FrameSnapshot> lastFrameWhenIdle(RenderWorker& worker) {
  std::shared_ptr<const FrameSnapshot> last;
  for (int i = 0; i < 6000; ++i) {
    if (auto f = worker.takeFrame()) last = f;
    if (!worker.busy()) break;
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  if (auto f = worker.takeFrame()) last = f;
  return last;
}

}  // namespace

TEST_CASE("gui refinement: a still frame becomes the mean of its passes, and a newer request cuts it short") {
  SceneSpec scene;
  scene.data = "phantom:32";
  scene.cluster.nodes = 4;
  FrameRequest request;
  request.width = request.height = 64;
  request.transfer = loadTransferFunction("phantom");
  RenderWorker worker;
  const std::uint64_t single = worker.submit(scene, request, false, 1);
  const std::shared_ptr<const FrameSnapshot> one = lastFrameWhenIdle(worker);
  REQUIRE(one);
  CHECK(one->id == single);
  CHECK(one->passes == 1);

  const std::uint64_t refined = worker.submit(scene, request, false, 6);
  const std::shared_ptr<const FrameSnapshot> six = lastFrameWhenIdle(worker);
  REQUIRE(six);
  CHECK(six->id == refined);
  CHECK(six->passes == 6);
  CHECK(six->passesRequested == 6);
  CHECK(six->stats.nodes == 4);  // the first pass's stats and stages come along
  CHECK_FALSE(six->stages.pixels.empty());
  // The same view, so nearly the same picture, but the mean of six lattices is not the first's.
  REQUIRE(six->image.rgba.size() == one->image.rgba.size());
  long differing = 0;
  for (std::size_t i = 0; i < one->image.rgba.size(); ++i) differing += one->image.rgba[i] != six->image.rgba[i];
  CHECK(differing > 0);

  // A preview submitted while a long refinement runs ends it after the pass in flight.
  worker.submit(scene, request, false, 64);
  for (int i = 0; i < 6000 && !worker.takeFrame(); ++i) std::this_thread::sleep_for(std::chrono::milliseconds(10));
  const std::uint64_t preview = worker.submit(scene, request, true, 64);
  const std::shared_ptr<const FrameSnapshot> last = lastFrameWhenIdle(worker);
  REQUIRE(last);
  CHECK(last->id == preview);
  CHECK(last->preview);
  CHECK(last->passes == 1);  // previews are never refined
}

namespace {

double lengthOf(const std::vector<TimelineBar>& bars, TimelineBar::Kind kind) {
  double s = 0;
  for (const TimelineBar& b : bars)
    if (b.kind == kind) s += b.end - b.start;
  return s;
}

}  // namespace

TEST_CASE("gui timeline: a frame's bars follow each node from 0 to its last phase, each phase filled by wait then composite") {
  std::shared_ptr<const VolumeSource> source = openDataset("phantom:24");
  FrameRequest request;
  request.width = request.height = 48;
  request.transfer = loadTransferFunction("phantom");
  for (const char* strategy : {"binary-swap", "direct-send"}) {
    ClusterOptions options;
    options.nodes = 8;
    options.strategy = strategy;
    VirtualCluster cluster(*source, options);
    const FrameStats stats = cluster.renderFrame(request).stats;
    REQUIRE(hasTimeline(stats));
    const double span = timelineSpan(stats, false);
    CHECK(span >= stats.wallSeconds);
    for (const NodeReport& n : stats.perNode) {
      CAPTURE(strategy);
      CAPTURE(n.rank);
      const std::vector<TimelineBar> bars = timelineBars(n, false);
      REQUIRE(!bars.empty());
      CHECK(bars.front().start == 0.0);
      double t = 0;
      for (std::size_t i = 0; i < bars.size(); ++i) {
        const TimelineBar& b = bars[i];
        CHECK(b.start >= t - 1e-12);  // in order, never overlapping
        CHECK(b.end >= b.start);
        CHECK(b.end <= span);
        switch (b.kind) {
          case TimelineBar::Kind::NotStarted: CHECK(b.end == n.renderStart); break;
          case TimelineBar::Kind::Render: CHECK((b.start == n.renderStart && b.end == n.renderEnd)); break;
          case TimelineBar::Kind::Wait:
            CHECK(b.start == n.phases[std::size_t(b.phase)].start);
            REQUIRE(i + 1 < bars.size());
            CHECK(bars[i + 1].phase == b.phase);  // the phase's compositing follows its wait at once
            CHECK(bars[i + 1].start == b.end);
            break;
          case TimelineBar::Kind::Composite: CHECK(b.end == n.phases[std::size_t(b.phase)].end); break;
          case TimelineBar::Kind::Brick: FAIL("no over-decomposition in this frame"); break;
        }
        t = b.end;
      }
      CHECK(t == n.phases.back().end);
      // The wait and composite bars add up to the node's totals.
      CHECK(lengthOf(bars, TimelineBar::Kind::Wait) == doctest::Approx(n.waitSeconds()).epsilon(1e-9));
      CHECK(lengthOf(bars, TimelineBar::Kind::Composite) == doctest::Approx(n.compositeSeconds()).epsilon(1e-9));
      CHECK(lengthOf(bars, TimelineBar::Kind::Render) == doctest::Approx(n.renderEnd - n.renderStart));
    }
  }
}

TEST_CASE("gui timeline: a report without times, or durations only, lays the durations end to end") {
  NodeReport n;
  n.renderSeconds = 0.004;
  PhaseStats a, b;
  a.waitSeconds = 0.002, a.computeSeconds = 0.001;
  b.waitSeconds = 0.0, b.computeSeconds = 0.0005;
  n.phases = {a, b};
  FrameStats stats;
  stats.wallSeconds = 0.1;
  stats.perNode = {n};
  CHECK_FALSE(hasTimeline(stats));
  const std::vector<TimelineBar> bars = timelineBars(n, false);  // no times: durations anyway
  REQUIRE(bars.size() == 4);  // render, wait + composite, composite (no empty wait bar)
  CHECK(bars[0].kind == TimelineBar::Kind::Render);
  CHECK(bars[1].kind == TimelineBar::Kind::Wait);
  CHECK(bars[1].start == doctest::Approx(0.004));
  CHECK(bars[2].phase == 0);
  CHECK(bars[3].phase == 1);
  CHECK(bars[3].end == doctest::Approx(0.0075));
  CHECK(timelineSpan(stats, true) == doctest::Approx(0.0075));  // the longest sum, not the wall time
  // With times, the same report as a timeline: not started, then where it really ran.
  n.timed = true;
  n.renderStart = 0.010, n.renderEnd = 0.014;
  n.phases[0].start = 0.014, n.phases[0].end = 0.017;
  n.phases[1].start = 0.017, n.phases[1].end = 0.0175;
  const std::vector<TimelineBar> timeline = timelineBars(n, false);
  REQUIRE(timeline.size() == 5);
  CHECK(timeline[0].kind == TimelineBar::Kind::NotStarted);
  CHECK(timeline[0].end == 0.010);
  CHECK(timeline[2].end == doctest::Approx(0.016));  // wait first, then compositing
  CHECK(timeline[3].start == doctest::Approx(0.016));
  CHECK(timelineBars(n, true).size() == 4);  // "durations only" overrides the times
}

TEST_CASE("gui timeline: hovering finds the bar under the mouse, a brick before its render step") {
  std::vector<TimelineBar> bars(3);
  bars[0] = {TimelineBar::Kind::Render, -1, -1, 1.0, 5.0};
  bars[1] = {TimelineBar::Kind::Brick, -1, 0, 2.0, 3.0};
  bars[2] = {TimelineBar::Kind::Wait, 0, -1, 5.0, 5.01};
  CHECK(barAt(bars, 1.5, 0.0) == 0);
  CHECK(barAt(bars, 2.5, 0.0) == 1);
  CHECK(barAt(bars, 5.005, 0.0) == 2);
  CHECK(barAt(bars, 5.05, 0.1) == 2);   // a thin bar within a pixel's slack
  CHECK(barAt(bars, 0.5, 0.1) == -1);
  CHECK(barAt(bars, 6.0, 0.1) == -1);
}

TEST_CASE("gui timeline: ticks are 1, 2 or 5 x 10^k s, the closest that keep their labels apart") {
  CHECK(tickStep(0.0924, 290, 56) == doctest::Approx(0.02));
  CHECK(tickStep(0.0095, 290, 56) == doctest::Approx(0.002));
  CHECK(tickStep(1.0, 100, 100) == doctest::Approx(1.0));
  for (double span = 1e-5; span < 100; span *= 1.37)
    for (float width : {80.0f, 290.0f, 1200.0f}) {
      const double step = tickStep(span, width, 56);
      CAPTURE(span);
      CAPTURE(width);
      CHECK(step * width / span >= 56 * (1 - 1e-9));  // far enough apart
      const double mantissa = step / std::pow(10.0, std::floor(std::log10(step) + 1e-9));
      CHECK((std::abs(mantissa - 1) < 1e-9 || std::abs(mantissa - 2) < 1e-9 || std::abs(mantissa - 5) < 1e-9));
      // The next smaller nice step (5 -> 2, 2 -> 1, 1 -> 0.5) would crowd them.
      const double smaller = step * (std::abs(mantissa - 2) < 1e-9 ? 0.5 : std::abs(mantissa - 5) < 1e-9 ? 0.4 : 0.5);
      CHECK(smaller * width / span < 56);
    }
}

TEST_CASE("gui timeline: rows fill the panel at 8 and 64 nodes, and scroll at 512 and 4096") {
  const TimelineRows eight = timelineRows(8, 370, 2, 28, 16);
  CHECK(eight.height == 28);  // capped: 8 rows are not each a panel high
  CHECK(eight.labelEvery == 1);
  CHECK(eight.gap > 0);
  const TimelineRows many = timelineRows(64, 370, 2, 28, 16);
  CHECK(many.height == 5);
  CHECK(many.total <= 370);
  CHECK(many.labelEvery == 4);  // labels 20 px apart, not 5
  for (int nodes : {512, 4096}) {
    const TimelineRows rows = timelineRows(nodes, 370, 2, 28, 16);
    CHECK(rows.height == 2);
    CHECK(rows.gap == 0);
    CHECK(rows.total == 2.0f * float(nodes));  // more than 370: the list scrolls
    CHECK(float(rows.labelEvery) * rows.height >= 16);
  }
  const TimelineRows rows = timelineRows(4096, 370, 2, 28, 16);
  CHECK(visibleRows(rows, 4096, 100, 370) == std::pair<int, int>(50, 235));
  CHECK(visibleRows(rows, 4096, 8192 - 370, 370) == std::pair<int, int>(4096 - 185, 4096));
  CHECK(visibleRows(eight, 8, 0, 370) == std::pair<int, int>(0, 8));
}

TEST_CASE("gui_window_opens_at_its_default_size_or_the_screen_if_smaller") {
  const WindowSize wanted = kDefaultWindowSize;  // 1600 x 1000
  const auto fitted = [&](int w, int h) {
    const WindowSize s = fitWindowToWorkArea(wanted, w, h);
    return std::to_string(s.width) + "x" + std::to_string(s.height);
  };
  CHECK(fitted(1920, 1050) == "1600x1000");  // a large screen: as wanted
  CHECK(fitted(1600, 1000) == "1600x1000");  // exactly fits (Xvfb in the tests)
  CHECK(fitted(1366, 740) == "1366x700");    // a laptop: its width, its height less a title bar
  CHECK(fitted(1920, 900) == "1600x860");    // only the height is short
  CHECK(fitted(600, 400) == "640x480");      // never below the smallest the panels lay out in
  CHECK(fitted(0, 0) == "1600x1000");        // no monitor reported: as wanted
  CHECK(fitWindowToWorkArea(WindowSize{800, 600}, 1366, 740).width == 800);  // never grown
}

}  // namespace kdswap
