// The GUI's logic that needs no window: the histogram under the transfer-function editor, the
// speedup sweep's warm-up and medians, error text safe to print, and the data-set error messages.
#define DOCTEST_CONFIG_IMPLEMENT_WITH_MAIN
#include <doctest/doctest.h>

#include <chrono>
#include <string>
#include <thread>
#include <vector>

#include "core/transfer/presets.h"
#include "core/util/error.h"
#include "core/volume/datasets/dataset.h"
#include "core/volume/memory_volume.h"
#include "ui/histogram.h"
#include "ui/printable_text.h"
#include "ui/render_worker.h"
#include "ui/sweep_worker.h"

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

}  // namespace kdswap
