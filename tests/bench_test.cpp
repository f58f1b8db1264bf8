// The bench's non-timing behaviour: medians, the shape of its CSV and JSON on a tiny grid, the
// speedup chart's file. Speed itself is measured by `kdswap bench`, never asserted here.
#include <doctest/doctest.h>

#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <sstream>

#include <nlohmann/json.hpp>

#include "core/bench/bench_grid.h"
#include "core/bench/bench_report.h"
#include "core/bench/machine_info.h"
#include "core/bench/micro_bench.h"
#include "core/bench/paper_comparison.h"
#include "core/bench/paper_tables.h"
#include "core/bench/quantised_source.h"
#include "core/bench/speed_targets.h"
#include "core/volume/datasets/dataset.h"
#include "core/volume/respaced_source.h"
#include "core/bench/speedup_chart.h"
#include "core/bench/statistics.h"
#include "core/render/ray_march.h"
#include "core/image/image_io.h"
#include "core/transfer/presets.h"
#include "core/util/error.h"
#include "tests/test_support.h"

using namespace kdswap;

TEST_CASE("median of odd and even counts, unsorted, with an outlier") {
  CHECK(median({}) == 0.0);
  CHECK(median({3.0}) == 3.0);
  CHECK(median({5.0, 1.0, 3.0}) == 3.0);
  CHECK(median({4.0, 1.0, 3.0, 2.0}) == doctest::Approx(2.5));
  CHECK(median({1.0, 1.1, 0.9, 1000.0, 1.05}) == doctest::Approx(1.05));
}

TEST_CASE("a one-cell grid yields one cell with every frame counted, and CSV and JSON of that shape") {
  auto volume = test::makeBlobs(glm::ivec3(12, 10, 9));
  BenchGridOptions o;
  o.sizes = {16};
  o.nodes = {2};
  o.frames = 3;
  o.base.transfer = loadTransferFunction("grayscale");
  int calls = 0;
  const BenchResult r = runBenchGrid(*volume, o, [&](const BenchProgress&) { ++calls; }, nullptr);
  REQUIRE(r.cells.size() == 1);
  CHECK_FALSE(r.interrupted);
  CHECK(calls >= 4);  // warm-up + 3 frames, then the cell
  const BenchCell& c = r.cells.front();
  CHECK(c.nodes == 2);
  CHECK(c.width == 16);
  CHECK(c.frames == 3);
  CHECK(c.speedup == doctest::Approx(2.0));  // P0 = P: P0 * T / T

  BenchContext ctx;
  ctx.commandLine = "kdswap bench --sizes 16 --nodes 2 --frames 3";
  ctx.dataset = "blobs";
  const std::string csv = benchCsv(ctx, r.cells);
  std::istringstream lines(csv);
  std::string header, row, extra;
  std::getline(lines, header);
  std::getline(lines, row);
  CHECK_FALSE(std::getline(lines, extra));
  const auto columns = [](const std::string& s) { return std::count(s.begin(), s.end(), ',') + 1; };
  CHECK(columns(header) == columns(row));
  CHECK(header.rfind("dataset,strategy,nodes,width,height,frames,render_s,composite_s,wall_s", 0) == 0);

  const nlohmann::json j = benchJson(ctx, r);
  CHECK(j["command"] == ctx.commandLine);
  REQUIRE(j["cells"].size() == 1);
  for (const char* key : {"strategy", "nodes", "image", "frames", "render_s", "composite_s", "wall_s", "modelled_s",
                          "speedup", "samples_per_s", "bytes_sent"})
    CHECK_MESSAGE(j["cells"][0].contains(key), key);
}

TEST_CASE("the machine is described from /proc/cpuinfo's text, with family and model, and recorded in bench.json") {
  const std::string cpuinfo =
      "processor\t: 0\nvendor_id\t: AuthenticAMD\ncpu family\t: 26\nmodel\t\t: 2\n"
      "model name\t: AMD EPYC\nflags\t\t: fpu avx2\n\nprocessor\t: 1\nmodel name\t: Other\n";
  const MachineInfo m = describeMachine(3, cpuinfo);
  CHECK(m.cpu == "AMD EPYC (family 26 model 2)");  // the first processor's, family and model apart from "model name"
  CHECK(m.threads == 3);
  CHECK(m.logicalCpus >= 1);
  CHECK(m.march == marchName(selectedMarchFunction()));
  CHECK(m.startedUtc.size() == 20);  // 2026-12-03T20:30:00Z
  CHECK(m.startedUtc[10] == 'T');
  CHECK(m.startedUtc.back() == 'Z');
  CHECK(describeMachine(0, "").cpu == "unknown CPU");
  CHECK(describeMachine(0, "").threads >= 1);  // 0: every core, as the run uses
  CHECK(describeMachine(0, "model name : Arm Neoverse\n").cpu == "Arm Neoverse");  // no family or model lines
  CHECK(formatMachine(m).rfind("machine: AMD EPYC (family 26 model 2), ", 0) == 0);

  BenchContext ctx;
  ctx.machine = m;
  const nlohmann::json j = benchJson(ctx, BenchResult{});
  CHECK(j["machine"]["cpu"] == m.cpu);
  CHECK(j["machine"]["threads"] == 3);
  CHECK(j["machine"]["ray_march"] == m.march);
  CHECK(j["machine"]["started_utc"] == m.startedUtc);
}

TEST_CASE("a stop flag already set ends the grid with no cells and says it was interrupted") {
  auto volume = test::makeBlobs(glm::ivec3(8));
  BenchGridOptions o;
  o.sizes = {8};
  o.nodes = {1, 2};
  o.base.transfer = loadTransferFunction("grayscale");
  const std::atomic<bool> stop{true};
  const BenchResult r = runBenchGrid(*volume, o, {}, &stop);
  CHECK(r.interrupted);
  CHECK(r.cells.empty());
}

TEST_CASE("speedup is T(1) / T(P) per strategy and size") {
  std::vector<BenchCell> cells(3);
  cells[0] = {"binary-swap", 1, 64, 64, 1, 0, 0, 0, 8.0};
  cells[1] = {"binary-swap", 4, 64, 64, 1, 0, 0, 0, 2.0};
  cells[2] = {"binary-tree", 4, 64, 64, 1, 0, 0, 0, 2.0};
  computeSpeedups(cells);
  CHECK(cells[0].speedup == doctest::Approx(1.0));
  CHECK(cells[1].speedup == doctest::Approx(4.0));
  CHECK(cells[2].speedup == doctest::Approx(4.0));  // its own baseline: P0 = 4
}

TEST_CASE("the speedup chart is written as a PNG of the requested size") {
  std::vector<BenchCell> cells;
  for (int size : {64, 128})
    for (int p : {1, 2, 4, 8}) {
      BenchCell c;
      c.strategy = "binary-swap";
      c.nodes = p;
      c.width = c.height = size;
      c.modelledSeconds = 1.0 / (0.8 * p + 0.2);
      cells.push_back(c);
    }
  computeSpeedups(cells);
  const Image chart = drawSpeedupChart(cells, "binary-swap", 320, 240);
  CHECK(chart.width() == 320);
  CHECK(chart.height() == 240);
  const std::string path = (std::filesystem::temp_directory_path() / ("kdswap_bench_test_speedup_" + std::to_string(::getpid()) + ".png")).string();
  writeImage(path, chart);
  const Image back = readImage(path);
  CHECK(back.width() == 320);
  CHECK(back.height() == 240);
  std::filesystem::remove(path);
  CHECK_THROWS_AS(drawSpeedupChart(cells, "no-such-strategy"), Error);
}

TEST_CASE("the speedup chart is log2 on both axes: a measured segment between two counts follows the ideal diagonal") {
  // Two counts only, both with ideal speedup. On a log2 x axis with a linear y axis the straight
  // segment from (1, 1) to (64, 64) would pass (8, 32.5), far above the ideal (8, 8); on log2-log2
  // axes both are the same diagonal, so the curve's colour must be found at the ideal's (8, 8).
  auto cell = [](int p, double speedup) {
    BenchCell c;
    c.strategy = "binary-swap";
    c.nodes = p;
    c.width = c.height = 64;
    c.speedup = speedup;
    return c;
  };
  auto isCurve = [](const Rgba& c) { return c.b > c.r + 0.3f; };  // the first palette colour, blue
  const std::vector<BenchCell> ideal{cell(1, 1.0), cell(64, 64.0)};
  const SpeedupChartLayout l = speedupChartLayout(ideal, "binary-swap");
  CHECK(l.log2SpeedupLo == 0.0);
  CHECK(l.log2SpeedupHi >= 6.0);
  CHECK(l.y(1.0) == doctest::Approx(l.bottom));
  CHECK(l.x(1.0) == doctest::Approx(l.left));
  CHECK(l.x(8.0) == doctest::Approx(0.5 * (l.x(1.0) + l.x(64.0))));
  const Image chart = drawSpeedupChart(ideal, "binary-swap");
  bool onDiagonal = false;
  for (int dy = -1; dy <= 1; ++dy)
    for (int dx = -1; dx <= 1; ++dx)
      onDiagonal |= isCurve(chart.at(int(l.x(8.0)) + dx, int(std::lround(l.y(8.0))) + dy));
  CHECK(onDiagonal);
  bool above = false;  // where the log-linear chart drew it: nothing of the curve there now
  for (int y = l.top; y < int(l.y(8.0)) - 4; ++y) above |= isCurve(chart.at(int(l.x(8.0)), y));
  CHECK_FALSE(above);

  // A speedup below 1 (nodes that cost more than they save) widens the axis below the baseline,
  // and an interrupted cell's speedup of 0 is left out instead of breaking the log scale.
  const std::vector<BenchCell> slow{cell(1, 1.0), cell(2, 0.7), cell(4, 0.0)};
  const SpeedupChartLayout s = speedupChartLayout(slow, "binary-swap");
  CHECK(s.log2SpeedupLo == -1.0);
  const Image slowChart = drawSpeedupChart(slow, "binary-swap");
  CHECK(isCurve(slowChart.at(int(s.x(2.0)), int(std::lround(s.y(0.7))))));
  CHECK(s.y(0.7) > s.y(1.0));  // below the baseline on screen
  CHECK_THROWS_AS(speedupChartLayout(slow, "binary-swap", 100, 100), Error);
}

TEST_CASE("quantising to 8 bits leaves at most 256 distinct values") {
  auto inner = test::makeBlobs(glm::ivec3(16));
  std::vector<float> raw(16 * 16 * 16);
  QuantisedSource q(std::move(inner), 8);
  q.read(VoxelBox{glm::ivec3(0), glm::ivec3(16)}, raw.data());
  std::sort(raw.begin(), raw.end());
  CHECK(std::unique(raw.begin(), raw.end()) - raw.begin() <= 256);
  CHECK(q.info().type == "uint8");
}

TEST_CASE("a respaced source keeps the values and changes only the spacing; bad spacings are refused") {
  auto inner = test::makeBlobs(glm::ivec3(12, 10, 8), glm::vec3(3.2f, 3.2f, 1.5f));
  std::vector<float> before(12 * 10 * 8), after(before.size());
  inner->read(VoxelBox{glm::ivec3(0), glm::ivec3(12, 10, 8)}, before.data());
  const RespacedSource unit(std::move(inner), glm::vec3(1.0f));
  unit.read(VoxelBox{glm::ivec3(0), glm::ivec3(12, 10, 8)}, after.data());
  CHECK(before == after);
  CHECK(unit.info().spacing == glm::vec3(1.0f));
  CHECK(unit.info().worldMax() == glm::vec3(11.0f, 9.0f, 7.0f));
  CHECK(parseSpacing("1,2.5,0.5", "--spacing") == glm::vec3(1.0f, 2.5f, 0.5f));
  for (const char* bad : {"1,1", "1,1,0", "1,-1,1", "1,nan,1", "1,1,1x", "", "a,b,c"})
    CHECK_THROWS_WITH_AS(parseSpacing(bad, "--spacing"), doctest::Contains("--spacing"), Error);
  CHECK_THROWS_AS(RespacedSource(test::makeBlobs(glm::ivec3(4)), glm::vec3(1.0f, 0.0f, 1.0f)), Error);
}

TEST_CASE("every paper figure carries its source") {
  for (const PaperCell& c : paperCells()) {
    CHECK_FALSE(c.source.empty());
    CHECK(c.nodes > 0);
  }
}

TEST_CASE("a paper cell with waves takes the single node's samples, fewer than without waves") {
  // A dense stand-in at a small size: the rays stop a few bricks deep, so without waves the nodes
  // behind sample what the single-node ray never reaches.
  PaperCell cell{"test table", "dense field", "turbulence:128", 64, 64, std::nullopt, std::nullopt, "test"};
  const auto standIn = openDataset(cell.standIn);
  bool interrupted = true;
  const BenchCell plain = measurePaperCell(cell, *standIn, 1, nullptr, interrupted);
  CHECK_FALSE(interrupted);
  const BenchCell waves = measurePaperCell(cell, *standIn, 1, nullptr, interrupted, /*waves=*/true);
  CHECK_FALSE(interrupted);
  cell.nodes = 1;
  const BenchCell one = measurePaperCell(cell, *standIn, 1, nullptr, interrupted);
  CHECK(plain.strategy == "binary-swap");
  CHECK(waves.strategy == "binary-swap+waves");
  CHECK(waves.nodes == 64);
  // The same samples as one node up to the rounding of each node's stop (T_own <= stop / T_front).
  CHECK(waves.samples == doctest::Approx(one.samples).epsilon(0.005));
  CHECK(waves.samples < 0.99 * plain.samples);
}

TEST_CASE("the grid compares space and cost planes, with node speeds and a network model") {
  auto volume = test::makeBlobs(glm::ivec3(20, 18, 16));
  BenchGridOptions o;
  o.sizes = {24};
  o.nodes = {1, 4};
  o.frames = 1;
  o.balances = {"space", "cost"};
  o.bricksPerNode = {1, 2};
  o.speedPattern = {1.0, 0.5};
  o.cluster.network = networkModel("ethernet10");
  o.base.transfer = loadTransferFunction("grayscale");
  const BenchResult r = runBenchGrid(*volume, o, {}, nullptr);
  REQUIRE(r.cells.size() == 8);
  CHECK(r.cells[0].strategy == "binary-swap");
  CHECK(r.cells[2].strategy == "binary-swap+bricks2");
  CHECK(r.cells[2].bricksPerNode == 2);
  CHECK(r.cells[4].strategy == "binary-swap+cost");
  CHECK(r.cells[4].balance == "cost");
  CHECK(r.cells[6].strategy == "binary-swap+cost+bricks2");
  for (const BenchCell& c : r.cells) {
    CHECK(c.renderImbalance >= 1.0);
    // One node sends nothing; four nodes swap over the shared Ethernet, which the model charges.
    if (c.nodes == 1) CHECK(c.commSeconds == 0.0);
    if (c.nodes == 4) CHECK(c.commSeconds > 0.0);
  }
  BenchContext ctx;
  ctx.dataset = "blobs";
  const std::string csv = benchCsv(ctx, r.cells);
  CHECK(csv.find(",balance,comm_s,render_imbalance,bricks_per_node,rays,rays_occluded,occlusion_map_s\n") !=
        std::string::npos);
  CHECK(csv.find(",cost,") != std::string::npos);
  CHECK(formatCellDetails(r.cells).find("comm ms") != std::string::npos);
}

TEST_CASE("the grid counts the ray-brick pairs that matter in front culled, their share and the map's time") {
  // An opaque block in faint surroundings: its rays end inside it, so the map culls bricks behind.
  const int n = 40;
  const auto volume = test::makeVolume(glm::ivec3(n), [n](int x, int y, int z) {
    const bool inside = x > n / 5 && x < n - n / 5 && y > n / 5 && y < n - n / 5 && z > n / 5 && z < n - n / 5;
    return inside ? 0.8f + 0.2f * std::sin(0.7f * float(x + y)) : 0.05f;
  });
  BenchGridOptions o;
  o.sizes = {48};
  o.nodes = {1, 16};
  o.frames = 1;
  o.base.transfer = loadTransferFunction("grayscale");
  const BenchResult r = runBenchGrid(*volume, o, {}, nullptr);
  REQUIRE(r.cells.size() == 2);
  CHECK(r.cells[0].rays > 0);
  CHECK(r.cells[0].raysOccluded == 0);  // one brick: nothing lies in front of it
  CHECK(r.cells[1].rays > r.cells[0].rays);  // a ray counts once per brick it may meet
  CHECK(r.cells[1].raysOccluded > 0.05 * r.cells[1].rays);
  // The map is computed only where there are bricks behind others, and its time is part of the frame's.
  CHECK(r.cells[0].occlusionMapSeconds == 0.0);
  CHECK(r.cells[1].occlusionMapSeconds > 0.0);
  CHECK(r.cells[1].occlusionMapSeconds < r.cells[1].wallSeconds);
  BenchContext ctx;
  ctx.dataset = "block";
  const std::string csv = benchCsv(ctx, r.cells);
  char tail[96];
  std::snprintf(tail, sizeof tail, ",%.0f,%.0f,%.9g\n", r.cells[1].rays, r.cells[1].raysOccluded,
                r.cells[1].occlusionMapSeconds);
  CHECK(csv.find(tail) != std::string::npos);
  const nlohmann::json j = benchJson(ctx, r);
  CHECK(j["cells"][1]["rays_occluded"].get<double>() == r.cells[1].raysOccluded);
  CHECK(j["cells"][1]["occlusion_map_s"].get<double>() == r.cells[1].occlusionMapSeconds);
  CHECK(formatCellDetails(r.cells).find("of wall: map ms") != std::string::npos);
  char share[32];
  std::snprintf(share, sizeof share, "%10.1f", 100.0 * r.cells[1].raysOccluded / r.cells[1].rays);
  const std::string table = formatCellDetails(r.cells);
  const std::size_t row = table.find("culled %");
  REQUIRE(row != std::string::npos);
  CHECK(table.substr(row, table.find('\n', row) - row).find(share) != std::string::npos);
}

TEST_CASE("a target against VTK measured here keeps the measurement and halves VTK's time") {
  const SpeedTarget fixed{"CT head ...", "kdswap bench ...", 60.0, 42.0, "ms", false, true, ""};
  const SpeedTarget slower = halfOfVtkHere(fixed, "CT head, P=64", 110.0);
  CHECK(slower.measured == 60.0);
  CHECK(slower.limit == 55.0);
  CHECK_FALSE(slower.met());  // 60 ms is more than half of 110
  CHECK(slower.command == fixed.command);
  CHECK(slower.note.find("110 ms") != std::string::npos);
  CHECK(slower.note.find("vtk_baseline") != std::string::npos);
  CHECK(halfOfVtkHere(fixed, "CT head, P=64", 130.0).met());
  SpeedTarget notRun = fixed;
  notRun.ran = false;
  CHECK_FALSE(halfOfVtkHere(notRun, "CT head, P=64", 1000.0).met());  // nothing measured, nothing met
}

TEST_CASE("targets over several runs are judged by the median of the runs; peak RSS by the first run") {
  auto run = [](double phantomMs, double rssMb, bool turbulenceRan) {
    return std::vector<SpeedTarget>{
        {"phantom wall", "kdswap bench ...", phantomMs, 29.0, "ms", false, true, ""},
        {"peak RSS", "kdswap bench ...", rssMb, 335.5, "MB", false, true, "process peak", true},
        {"turbulence wall", "kdswap bench ...", 80.0, 88.0, "ms", false, turbulenceRan, "P=1 wall 50 ms"}};
  };
  // Three runs: the phantom met once (the first run alone would say MET), missed twice.
  const std::vector<SpeedTarget> merged = medianOfRuns({run(28.0, 330.0, true), run(35.0, 340.0, false),
                                                        run(31.0, 345.0, true)});
  REQUIRE(merged.size() == 3);
  CHECK(merged[0].measured == 31.0);
  CHECK_FALSE(merged[0].met());
  CHECK(merged[0].note.find("median of 3 runs: 28.00, 35.00, 31.00") != std::string::npos);
  CHECK(merged[1].measured == 330.0);  // later runs' peaks include what earlier targets held
  CHECK(merged[1].met());
  CHECK(merged[1].note.find("first of the runs") != std::string::npos);
  CHECK(merged[2].measured == 80.0);   // the run that did not measure it is left out
  CHECK(merged[2].note.find("median of 2 runs") != std::string::npos);
  CHECK(merged[2].note.find("P=1 wall 50 ms") != std::string::npos);
  // A run cut short (Ctrl-C) has fewer targets; one run is passed through as it is.
  const std::vector<SpeedTarget> cut = medianOfRuns({run(30.0, 330.0, true), {run(20.0, 330.0, true)[0]}});
  CHECK(cut[0].measured == 25.0);
  CHECK(cut[2].note.find("median of 1 run: 80.00") != std::string::npos);
  CHECK(medianOfRuns({run(30.0, 330.0, true)})[0].note.empty());
  CHECK(medianOfRuns({}).empty());
}

TEST_CASE("a P = 64 / P = 1 ratio's note gives both cells' samples and what the miss comes from") {
  // P = 64 took 1.67 x one node's samples: the excess lies behind matter (the paper's nodes).
  const std::string behind = wallRatioNote(0.0120, 0.0262, 0.82e6, 1.37e6);
  CHECK(behind.find("P=1 wall 12.00 ms, P=64 wall 26.20 ms") != std::string::npos);
  CHECK(behind.find("samples a frame 0.82 M and 1.37 M") != std::string::npos);
  CHECK(behind.find("1.67 x: the nodes sample behind") != std::string::npos);
  CHECK(behind.find("cost of 64 bricks") == std::string::npos);
  // The same samples (waves): what is left is the per-brick and per-phase cost.
  const std::string fixedCost = wallRatioNote(0.0120, 0.0146, 0.82e6, 0.83e6, " (one node)");
  CHECK(fixedCost.find("P=1 wall 12.00 ms (one node), P=64 wall 14.60 ms") != std::string::npos);
  CHECK(fixedCost.find("1.01 x: the rest is the cost of 64 bricks") != std::string::npos);
  CHECK(fixedCost.find("sample behind") == std::string::npos);
  // An interrupted cell has no samples: no ratio of them, no verdict on the cause.
  const std::string none = wallRatioNote(0.0120, 0.0, 0.0, 0.0);
  CHECK(none.find(" x: ") == std::string::npos);
}

TEST_CASE("a target not run says why, in one run or several, and shows no measurement") {
  const SpeedTarget missing{"CT head wall", "kdswap bench --volume h.nhdr ...", 0.0, 42.0, "ms", false, false,
                            "h.nhdr not found (pass --head FILE)"};
  const std::vector<SpeedTarget> merged = medianOfRuns({{missing}, {missing}, {missing}});
  REQUIRE(merged.size() == 1);
  CHECK_FALSE(merged[0].ran);
  CHECK(merged[0].note == "h.nhdr not found (pass --head FILE)");
  const std::string text = formatSpeedTargets(merged);
  CHECK(text.find("NOT RUN") != std::string::npos);
  CHECK(text.find("not measured: h.nhdr not found (pass --head FILE)") != std::string::npos);
  CHECK(text.find("measured 0.00") == std::string::npos);
  CHECK(text.find("0 of 1 targets met (0 run)") != std::string::npos);
}

TEST_CASE("a grid with front-to-back waves labels its cells STRATEGY+waves, and its modelled time follows the waits") {
  auto volume = test::makeBlobs(glm::ivec3(16, 14, 12));
  BenchGridOptions o;
  o.sizes = {24};
  o.nodes = {1, 8};
  o.frames = 1;
  o.base.transfer = loadTransferFunction("grayscale");
  o.base.settings.frontToBackWaves = true;
  const BenchResult r = runBenchGrid(*volume, o, {}, nullptr);
  REQUIRE(r.cells.size() == 2);
  for (const BenchCell& c : r.cells) {
    CHECK(c.strategy == "binary-swap+waves");
    // The render span is at least the max render, so the modelled time is never below it.
    CHECK(c.modelledSeconds >= c.renderSeconds);
  }
  BenchContext ctx;
  ctx.dataset = "blobs";
  CHECK(benchJson(ctx, r)["cells"][1]["strategy"] == "binary-swap+waves");
  CHECK(benchCsv(ctx, r.cells).find(",binary-swap+waves,8,") != std::string::npos);

  o.base.settings.frontToBackWaves = false;
  CHECK(runBenchGrid(*volume, o, {}, nullptr).cells.front().strategy == "binary-swap");
}

TEST_CASE("an interleaved grid measures every cell in rounds and reports what the cell-by-cell grid does") {
  auto volume = test::makeBlobs(glm::ivec3(16, 14, 12));
  BenchGridOptions o;
  o.sizes = {16, 24};
  o.nodes = {1, 2, 4};
  o.strategies = {"binary-swap", "direct-send"};
  o.frames = 2;
  o.base.transfer = loadTransferFunction("grayscale");
  const BenchResult sequential = runBenchGrid(*volume, o, {}, nullptr);
  o.interleave = true;
  std::vector<std::string> order;  // the cell each frame belonged to, in the order they ran
  const BenchResult interleaved =
      runBenchGrid(*volume, o, [&](const BenchProgress& p) { order.push_back(p.current); }, nullptr);
  CHECK_FALSE(interleaved.interrupted);
  REQUIRE(sequential.cells.size() == 12);
  REQUIRE(interleaved.cells.size() == sequential.cells.size());
  for (std::size_t i = 0; i < sequential.cells.size(); ++i) {
    const BenchCell &a = sequential.cells[i], &b = interleaved.cells[i];
    CAPTURE(i);
    CHECK(a.strategy == b.strategy);
    CHECK(a.nodes == b.nodes);
    CHECK(a.width == b.width);
    CHECK(b.frames == 2);
    CHECK(a.samples == b.samples);  // the same views: frame k of a cell turns k degrees either way
    CHECK(a.bytesSent == b.bytesSent);
  }
  // Rounds: each cell renders frame k - 1 again, then frame k measured; the first round takes
  // every cell in report order, the second repeats it.
  REQUIRE(order.size() == 2 * 2 * 12);
  for (std::size_t c = 0; c < 12; ++c) {
    CAPTURE(c);
    CHECK(order[2 * c] == order[2 * c + 1]);
    CHECK(order[2 * c] == order[24 + 2 * c]);
    for (std::size_t d = 0; d < c; ++d) CHECK(order[2 * c] != order[2 * d]);
  }
  CHECK(order[0] == "16x16, P=1, binary-swap");
  CHECK(order[22] == "24x24, P=4, direct-send");
}

TEST_CASE("an interleaved grid stopped midway keeps every cell with a frame measured, none more than one frame ahead") {
  auto volume = test::makeBlobs(glm::ivec3(12, 10, 9));
  BenchGridOptions o;
  o.sizes = {16};
  o.nodes = {1, 2, 4};
  o.frames = 4;
  o.interleave = true;
  o.base.transfer = loadTransferFunction("grayscale");
  std::atomic<bool> stop{false};
  int frames = 0;
  // A round (each cell: the previous frame again, then the measured one) and the first cell's
  // frames of the next: then stop.
  const BenchResult r = runBenchGrid(*volume, o, [&](const BenchProgress&) {
    if (++frames == 8) stop = true;
  }, &stop);
  CHECK(r.interrupted);
  REQUIRE(r.cells.size() == 3);
  CHECK(r.cells[0].frames == 2);
  CHECK(r.cells[1].frames == 1);
  CHECK(r.cells[2].frames == 1);
}

TEST_CASE("the compositing harness reports the bytes an exchange sends and times a copy of them") {
  // Binary swap, P = 4, full 64x64 frames of 16-byte pixels: phase 1 gives away half the frame,
  // phase 2 half of the rest, on every node, each message with its rectangle (four 8-byte
  // integers): 4 x (32768 + 16384 + 2 x 32) bytes. The yardstick is a copy of that many bytes,
  // timed after each run, so it is measured and positive.
  const BinarySwapFigure f = measureCompositing("binary-swap", 4, 64, 64, 3);
  CHECK(f.bytesSent == 4u * (64u * 64u * 16u / 2u + 64u * 64u * 16u / 4u + 2u * 32u));
  CHECK(f.copySentSeconds > 0.0);
  CHECK(f.copySeconds > 0.0);
  CHECK(f.wallSeconds > 0.0);
}
