// Occlusion culling across bricks: the bound it uses is sound (whenever it says the samples before
// lattice index K end the ray, the single-node ray's own samples before K really reach the
// termination opacity), it is not vacuous, the per-frame map holds exactly that bound per pixel,
// and distributed images with it stay equal to the single-node image.
#include <doctest/doctest.h>

#include <random>

#include "core/cluster/virtual_cluster.h"
#include "core/partition/kd_tree.h"
#include "core/render/occlusion_grid.h"
#include "core/render/occlusion_map.h"
#include "core/render/ray_caster.h"
#include "core/render/reference_render.h"
#include "core/render/trilinear.h"
#include "core/render/voxel_ray.h"
#include "core/transfer/presets.h"
#include "core/volume/datasets/dataset.h"
#include "test_support.h"

using namespace kdswap;

namespace {

//! The opacity the single-node ray gathers from its samples with lattice index k < kEnd, accumulated
//! exactly as the ray caster does (float "over" of the corrected opacities), without early termination.
float opacityBefore(const Brick& whole, const TransferTable& table, float scale, float bias, const glm::vec3& o,
                    const glm::vec3& d, long kEnd, float step, float phase) {
  const glm::vec3 hi(whole.owned().hi);
  float alpha = 0.0f;
  for (long k = 0; k < kEnd; ++k) {
    const float t = (float(k) + phase) * step;
    const glm::vec3 p = o + d * t;
    if (!(p.x >= 0.0f && p.x < hi.x && p.y >= 0.0f && p.y < hi.y && p.z >= 0.0f && p.z < hi.z)) continue;
    const float a = table.lookup(TrilinearCell(whole, p).value() * scale + bias).a;
    alpha += (1.0f - alpha) * a;
  }
  return alpha;
}

//! Dense opaque matter (a rippled block) inside a faint haze: rays through the block end early.
std::unique_ptr<VolumeSource> makeBlock(int n) {
  return test::makeVolume(glm::ivec3(n, n + 4, n - 4), [n](int x, int y, int z) {
    const bool inside = x > n / 5 && x < n - n / 4 && y > n / 6 && y < n - n / 5 && z > n / 5 && z < n - n / 3;
    const float ripple = 0.5f + 0.5f * std::sin(0.7f * float(x) + 0.3f * float(y)) * std::cos(0.5f * float(z));
    return inside ? 0.7f + 0.3f * ripple : 0.12f * ripple;
  });
}

std::unique_ptr<VolumeSource> openData(const std::string& name) {
  return name == "block" ? makeBlock(48) : openDataset(name);
}

}  // namespace

TEST_CASE("occlusion bound: every ray it culls is one the single-node ray ends before that point") {
  for (const std::string data : {"block", "phantom:96"}) {
    auto volume = openData(data);
    const Brick whole = wholeVolumeBrick(*volume);
    const glm::ivec3 dims = volume->info().dims;
    const float step = 0.7f;
    const TransferTable table(loadTransferFunction("grayscale"), step);
    const glm::vec2 range = resolveValueRange(RenderSettings{}, volume->info());
    const float scale = normalisingScaleBias(range).x, bias = normalisingScaleBias(range).y;
    const float stopAt = 0.95f;
    // The summary gathered from a k-d split must serve as well as the whole volume's.
    std::vector<Brick> parts;
    const int cut = dims.x / 2 + 3;
    for (const VoxelBox& owned : {VoxelBox{glm::ivec3(0), glm::ivec3(cut, dims.y - 1, dims.z - 1)},
                                  VoxelBox{glm::ivec3(cut, 0, 0), dims - 1}}) {
      parts.push_back(test::brickOf(*volume, owned));
    }
    const CellRangeGrid fromParts = CellRangeGrid::fromBricks(dims, {&parts[0], &parts[1]});
    const CellRangeGrid fromWhole = CellRangeGrid::fromBricks(dims, {&whole});
    REQUIRE(fromParts.ranges.size() == fromWhole.ranges.size());
    for (std::size_t i = 0; i < fromWhole.ranges.size(); ++i) {
      CHECK(fromParts.ranges[i].x <= fromWhole.ranges[i].x);
      CHECK(fromParts.ranges[i].y >= fromWhole.ranges[i].y);
    }
    const OcclusionGrid grid(fromParts, table, scale, bias, stopAt);
    REQUIRE(grid.active());
    CHECK(fromParts.fineBlock == fromWhole.fineBlock);
    if (data == "phantom:96") CHECK(grid.fineBlocks() > 0);  // its skull is walked voxel by voxel

    std::mt19937 rng(5);
    std::uniform_real_distribution<float> u(0.0f, 1.0f);
    int culled = 0, rays = 0;
    const glm::vec3 centre = glm::vec3(dims - 1) * 0.5f;
    for (int i = 0; i < 1500; ++i) {
      // Rays from outside through random points of the volume, in every direction.
      const glm::vec3 target = glm::vec3(u(rng), u(rng), u(rng)) * glm::vec3(dims - 1);
      glm::vec3 dir = glm::normalize(glm::vec3(u(rng) - 0.5f, u(rng) - 0.5f, u(rng) - 0.5f) + 1e-3f);
      const glm::vec3 o = centre - dir * float(dims.x + dims.y + dims.z) + (target - centre) * 0.3f;
      const float phase = u(rng);
      ++rays;
      const long from = grid.occludedFrom(o, dir, step, phase);
      if (from == OcclusionGrid::kNever) continue;
      ++culled;
      CAPTURE(data);
      CAPTURE(i);
      CHECK(opacityBefore(whole, table, scale, bias, o, dir, from, step, phase) >= stopAt);
    }
    MESSAGE(data << ": " << culled << " of " << rays << " rays culled");
    CHECK(culled > rays / 20);  // the bound does cull: not vacuous
  }
}

TEST_CASE("occlusion bound: rays walked in batches (eight at once with AVX2, sixteen with AVX-512) get the single ray's index") {
  for (const std::string data : {"block", "phantom:96", "turbulence:96"}) {
    auto volume = openData(data);
    const Brick whole = wholeVolumeBrick(*volume);
    const glm::ivec3 dims = volume->info().dims;
    const glm::vec2 map = normalisingScaleBias(resolveValueRange(RenderSettings{}, volume->info()));
    for (const float step : {0.5f, 1.0f}) {
      const TransferTable table(loadTransferFunction("grayscale"), step);
      const OcclusionGrid grid(CellRangeGrid::fromBricks(dims, {&whole}), table, map.x, map.y, 0.95f);
      REQUIRE(grid.active());
      if (data != "turbulence:96") CHECK(grid.fineBlocks() > 0);  // walks through one-voxel cells too
      // Bundles of nearly parallel rays (as a row of pixels), axis-parallel ones, rays that miss and
      // rays from inside.
      std::mt19937 rng(11);
      std::uniform_real_distribution<float> u(0.0f, 1.0f);
      constexpr int kRays = 203;  // not a multiple of eight: the last eight wrap around
      std::vector<glm::vec3> origins, directions;
      std::vector<float> phases;
      const glm::vec3 centre = glm::vec3(dims - 1) * 0.5f;
      int ending = 0;
      for (int bundle = 0; bundle < 24; ++bundle) {
        glm::vec3 axis = glm::normalize(glm::vec3(u(rng) - 0.5f, u(rng) - 0.5f, u(rng) - 0.5f));
        if (bundle % 6 == 0) axis = glm::vec3(bundle % 12 == 0 ? 1.0f : 0.0f, 0.0f, bundle % 12 == 0 ? 0.0f : -1.0f);
        // Every sixth bundle looks out from inside the volume (the walk starts where the ray does).
        const glm::vec3 eye = centre - axis * (bundle % 6 == 3 ? 3.0f : float(dims.x + dims.y + dims.z));
        origins.clear(), directions.clear(), phases.clear();
        for (int i = 0; i < kRays; ++i) {
          const glm::vec3 target = centre + (glm::vec3(u(rng), u(rng), u(rng)) - 0.5f) * glm::vec3(dims) * 1.3f;
          origins.push_back(eye);
          directions.push_back(bundle % 6 == 0 ? axis : glm::normalize(target - eye));
          phases.push_back(u(rng));
        }
        // Eight rays at a time and sixteen at a time, as the map asks (the sixteen walk at once on any
        // CPU with AVX-512, whichever the map prefers there); the last batch wraps around to the first rays.
        const auto raysFrom = [&](int first) {
          VoxelRays8 rays;
          for (int j = 0; j < 8; ++j) {
            const std::size_t i = std::size_t((first + j) % kRays);
            rays.ox[j] = origins[i].x, rays.oy[j] = origins[i].y, rays.oz[j] = origins[i].z;
            rays.dx[j] = directions[i].x, rays.dy[j] = directions[i].y, rays.dz[j] = directions[i].z;
            rays.phase[j] = phases[i];
          }
          return rays;
        };
        std::vector<long> batched(kRays), batched16(kRays);
        for (int first = 0; first < kRays; first += 8) {
          long eight[8];
          grid.occludedFrom(raysFrom(first), step, eight);
          for (int j = 0; j < 8 && first + j < kRays; ++j) batched[std::size_t(first + j)] = eight[j];
        }
        for (int first = 0; first < kRays; first += 16) {
          long sixteen[16];
          grid.occludedFrom(raysFrom(first), raysFrom(first + 8), step, sixteen);
          for (int j = 0; j < 16 && first + j < kRays; ++j) batched16[std::size_t(first + j)] = sixteen[j];
        }
        for (int i = 0; i < kRays; ++i) {
          const long single = grid.occludedFrom(origins[std::size_t(i)], directions[std::size_t(i)], step, phases[std::size_t(i)]);
          CAPTURE(data);
          CAPTURE(bundle);
          CAPTURE(i);
          CHECK(batched[std::size_t(i)] == single);
          CHECK(batched16[std::size_t(i)] == single);
          ending += single != OcclusionGrid::kNever;
        }
      }
      CAPTURE(data);
      CHECK(ending > 200);  // not only rays that never end
    }
  }
}

TEST_CASE("occlusion bound: an opaque wall eight voxels thick is credited, wherever it sits in the cells") {
  // An 8^3 cell's samples touch 9 voxels per axis, so an 8-voxel wall shares every such cell with
  // the empty space around it; it fills some 4^3 cell (5 voxels) at any offset, and the summary
  // must see it as opaque.
  for (const int wallLo : {16, 17, 18, 19}) {
    auto volume = test::makeVolume(glm::ivec3(48, 40, 40), [wallLo](int x, int, int) {
      return x >= wallLo && x < wallLo + 8 ? 1.0f : 0.0f;
    });
    const Brick whole = wholeVolumeBrick(*volume);
    const float step = 0.5f;
    const TransferTable table(loadTransferFunction("grayscale"), step);
    const glm::vec2 map = normalisingScaleBias(resolveValueRange(RenderSettings{}, volume->info()));
    const OcclusionGrid grid(CellRangeGrid::fromBricks(volume->info().dims, {&whole}), table, map.x, map.y, 0.95f);
    REQUIRE(grid.active());
    // Along +x through the middle: the ray must be proven to end inside or just past the wall.
    const glm::vec3 o(0.0f, 20.3f, 19.6f), d(1.0f, 0.0f, 0.0f);
    const long k = grid.occludedFrom(o, d, step, 0.25f);
    REQUIRE(k != OcclusionGrid::kNever);
    CHECK((float(k) + 0.25f) * step <= float(wallLo + 8));
    // And the bound is sound: the single-node ray's samples before k do reach the opacity.
    CHECK(opacityBefore(whole, table, map.x, map.y, o, d, k, step, 0.25f) >= 0.95f);
  }
}

TEST_CASE("occlusion bound: a wall four voxels thick, filling no cell, is credited voxel by voxel") {
  // A 4^3 cell's samples touch five voxels per axis, so a four-voxel wall (the phantom's skull is
  // 3.5) fills no cell at any offset; the one-voxel cells of the cells it crosses must prove it.
  for (const int wallLo : {16, 17, 18, 19}) {
    auto volume = test::makeVolume(glm::ivec3(48, 40, 40), [wallLo](int x, int, int) {
      return x >= wallLo && x < wallLo + 4 ? 1.0f : 0.0f;
    });
    const Brick whole = wholeVolumeBrick(*volume);
    const glm::ivec3 dims = volume->info().dims;
    const float step = 0.5f;
    const TransferTable table(loadTransferFunction("grayscale"), step);
    const glm::vec2 map = normalisingScaleBias(resolveValueRange(RenderSettings{}, volume->info()));
    const CellRangeGrid cells = CellRangeGrid::fromBricks(dims, {&whole});
    // Cut by bricks (at x = 18, inside some of the walls' cells), the summary is the same.
    const Brick left = test::brickOf(*volume, VoxelBox{glm::ivec3(0), glm::ivec3(18, dims.y - 1, dims.z - 1)});
    const Brick right = test::brickOf(*volume, VoxelBox{glm::ivec3(18, 0, 0), dims - 1});
    const CellRangeGrid cut = CellRangeGrid::fromBricks(dims, {&left, &right});
    CHECK(cut.fineBlock == cells.fineBlock);
    REQUIRE(cut.fine.size() == cells.fine.size());
    for (std::size_t i = 0; i < cells.fine.size(); ++i) {
      CHECK(cut.fine[i].lo == cells.fine[i].lo);
      CHECK(cut.fine[i].hi == cells.fine[i].hi);
    }
    const OcclusionGrid grid(cut, table, map.x, map.y, 0.95f);
    REQUIRE(grid.active());
    CHECK(grid.fineBlocks() > 0);
    // Along +x, and obliquely: each ray is proven to end inside the wall or just past it, soundly.
    for (const glm::vec3 d : {glm::vec3(1.0f, 0.0f, 0.0f), glm::normalize(glm::vec3(1.0f, 0.37f, -0.21f))}) {
      const glm::vec3 o = glm::vec3(0.0f, 13.3f, 26.6f) - d * 0.5f;
      const long k = grid.occludedFrom(o, d, step, 0.25f);
      CAPTURE(wallLo);
      REQUIRE(k != OcclusionGrid::kNever);
      CHECK(o.x + d.x * (float(k) + 0.25f) * step <= float(wallLo + 4));
      CHECK(opacityBefore(whole, table, map.x, map.y, o, d, k, step, 0.25f) >= 0.95f);
    }
  }
}

TEST_CASE("cell summary: processes holding different bricks merge theirs into the whole volume's") {
  // As MPI ranks do (mpi_cluster.cpp): each takes rangesOf its own bricks, the ranges are merged
  // (min, max), each encodes its bricks' fine codes on the merged ranges, and the codes are merged
  // (min of lo, max of hi). The result must be the summary fromBricks gives with every brick at hand.
  for (const char* spec : {"phantom:40", "vessels:40"}) {
    CAPTURE(spec);
    auto volume = openDataset(spec);
    const glm::ivec3 dims = volume->info().dims;
    const KdTree tree = KdTree::build(dims, 6, PartitionKind::KdTree, 2, {});
    std::vector<Brick> bricks;
    for (int b = 0; b < 6; ++b) bricks.push_back(test::brickOf(*volume, tree.brick(b)));
    const std::vector<std::vector<const Brick*>> processes = {{&bricks[0], &bricks[3]}, {&bricks[1]},
                                                              {&bricks[2], &bricks[4], &bricks[5]}};
    std::vector<const Brick*> all;
    for (const Brick& b : bricks) all.push_back(&b);
    const CellRangeGrid expected = CellRangeGrid::fromBricks(dims, all);

    std::vector<glm::vec2> merged = CellRangeGrid::rangesOf(dims, processes[0]);
    for (std::size_t p = 1; p < processes.size(); ++p) {
      const std::vector<glm::vec2> own = CellRangeGrid::rangesOf(dims, processes[p]);
      for (std::size_t i = 0; i < merged.size(); ++i)
        merged[i] = glm::vec2(std::min(merged[i].x, own[i].x), std::max(merged[i].y, own[i].y));
    }
    CellRangeGrid grid = CellRangeGrid::withRanges(dims, merged, processes[0]);
    for (std::size_t p = 1; p < processes.size(); ++p) {
      const CellRangeGrid own = CellRangeGrid::withRanges(dims, merged, processes[p]);
      REQUIRE(own.fine.size() == grid.fine.size());
      for (std::size_t i = 0; i < grid.fine.size(); ++i)
        grid.fine[i] = {std::min(grid.fine[i].lo, own.fine[i].lo), std::max(grid.fine[i].hi, own.fine[i].hi)};
    }
    CHECK(grid.count == expected.count);
    CHECK(grid.ranges == expected.ranges);
    CHECK(grid.fineBlock == expected.fineBlock);
    REQUIRE(grid.fine.size() == expected.fine.size());
    CHECK(!grid.fine.empty());  // the phantom's skull and the vessels' walls keep fine codes
    std::size_t differing = 0;
    for (std::size_t i = 0; i < grid.fine.size(); ++i)
      differing += grid.fine[i].lo != expected.fine[i].lo || grid.fine[i].hi != expected.fine[i].hi;
    CHECK(differing == 0);
    // One process alone does not hold the whole summary: the merge is what makes it whole.
    CHECK(CellRangeGrid::rangesOf(dims, processes[1]) != expected.ranges);
  }
}

TEST_CASE("occlusion map: stopping each single-node ray at its map index changes no pixel") {
  // Both voxel formats: with compact storage the summary holds the ranges of the stored values.
  for (const std::string data : {"block", "phantom:96"})
  for (const VoxelChoice voxels : {VoxelChoice::Float, VoxelChoice::Compact}) {
    auto volume = openData(data);
    const Brick whole = wholeVolumeBrick(*volume, Brick::kCellShiftByVolume, voxels);
    const VolumeInfo& info = volume->info();
    RenderSettings settings;
    settings.stepVoxels = 0.6f;
    const TransferTable table(loadTransferFunction("grayscale"), settings.stepVoxels);
    const glm::vec2 range = resolveValueRange(settings, info);
    const glm::vec2 map = normalisingScaleBias(range);
    const OcclusionGrid grid(CellRangeGrid::fromBricks(info.dims, {&whole}), table, map.x, map.y,
                             settings.earlyTermination);
    std::size_t endInside = 0;
    for (const float azimuth : {20.0f, 160.0f, 250.0f}) {
      View view;
      view.azimuthDeg = azimuth;
      view.elevationDeg = azimuth > 200.0f ? -35.0f : 15.0f;
      const glm::vec3 worldHi = glm::vec3(info.dims - 1) * info.spacing;
      const Camera camera(view, glm::vec3(0.0f), worldHi, 72, 60);
      const OcclusionMap occlusion(grid, camera, worldHi, info.spacing, settings);
      const RayCaster caster(whole, table, settings, range);
      RenderCounters plain, stopped;
      int mismatches = 0, indexMismatches = 0;
      for (int y = 0; y < camera.height(); ++y)
        for (int x = 0; x < camera.width(); ++x) {
          const Ray ray = camera.ray(x, y);
          const Rgba a = caster.castRay(ray, plain);
          const Rgba b = caster.castRay(ray, stopped, occlusion.occludedFrom(x, y));
          mismatches += !(a.r == b.r && a.g == b.g && a.b == b.b && a.a == b.a);
          // The map sets its rays up eight at a time where it can: the index of each is the one
          // the pixel's own voxel ray gets.
          const VoxelRay voxelRay(ray, info.spacing, settings);
          const long single = grid.occludedFrom(voxelRay.origin, voxelRay.direction, voxelRay.step, voxelRay.phase);
          indexMismatches += occlusion.occludedFrom(x, y) != single;
        }
      CAPTURE(data);
      CAPTURE(azimuth);
      CAPTURE(whole.storage().compactFormat());
      CHECK(mismatches == 0);
      CHECK(indexMismatches == 0);
      CHECK(stopped.samples == plain.samples);  // the single-node ray never reaches its map index
      endInside += occlusion.occludedPixels();
    }
    MESSAGE(data << ": " << endInside << " pixels of 3 views end inside the volume by the map");
    CHECK(endInside > 50);  // not vacuous
  }
}

TEST_CASE("distributed images with occlusion culling equal the single-node image and take fewer samples") {
  // The block, and the phantom, whose skull the culling walks voxel by voxel.
  for (const std::string data : {"block", "phantom:96"}) {
    auto volume = openData(data);
    std::uint64_t culledSamples = 0, allSamples = 0;
    for (const int nodes : {2, 8, 27, 64})
      for (const float azimuth : {15.0f, 130.0f}) {
        FrameRequest request;
        request.width = 96;
        request.height = 80;
        request.view.azimuthDeg = azimuth;
        request.transfer = loadTransferFunction("grayscale");
        request.settings.stepVoxels = 0.8f;
        ClusterOptions options;
        options.nodes = nodes;
        VirtualCluster cluster(*volume, options);
        const FrameResult culled = cluster.renderFrame(request);
        FrameRequest plain = request;
        plain.settings.cullOccluded = false;
        const FrameResult all = cluster.renderFrame(plain);
        CAPTURE(data);
        CAPTURE(nodes);
        CAPTURE(azimuth);
        const float tolerance = 1e-5f + (1.0f - request.settings.earlyTermination);
        CHECK(test::diffAgainstReference(*volume, request, culled.image) <= tolerance);
        CHECK(test::diffAgainstReference(*volume, plain, all.image) <= tolerance);
        CHECK(culled.stats.samples() <= all.stats.samples());
        if (data == "block") CHECK(culled.stats.samples() < all.stats.samples());
        culledSamples += culled.stats.samples(), allSamples += all.stats.samples();
      }
    MESSAGE(data << ": " << culledSamples << " samples with culling, " << allSamples << " without");
    CHECK(culledSamples < allSamples);
  }
}

TEST_CASE("occlusion culling rests for a while after a frame where it culled little, then resumes") {
  auto volume = makeBlock(40);
  FrameRequest opaque;
  opaque.width = 96;
  opaque.height = 80;
  opaque.view.azimuthDeg = 15.0f;
  opaque.transfer = loadTransferFunction("grayscale");
  opaque.settings.stepVoxels = 0.8f;
  // Faint: every cell can add some opacity (so the map is built) but no ray gathers 0.99 of it.
  FrameRequest faint = opaque;
  faint.transfer = TransferFunction::ramp(0.0f, 0.02f);
  ClusterOptions options;
  options.nodes = 8;
  VirtualCluster cluster(*volume, options);
  const auto culledPairs = [](const FrameResult& r) { return r.stats.raysOccluded(); };
  const auto rayPairs = [](const FrameResult& r) { return r.stats.rays(); };

  const FrameResult first = cluster.renderFrame(opaque);
  const std::uint64_t opaqueCulled = culledPairs(first);
  CHECK(double(opaqueCulled) > 0.06 * double(rayPairs(first)));  // culling pays here (over 5% of pairs): it stays on
  CHECK(culledPairs(cluster.renderFrame(opaque)) == opaqueCulled);

  const FrameResult faintFrame = cluster.renderFrame(faint);
  CHECK(rayPairs(faintFrame) > 1000);
  CHECK(culledPairs(faintFrame) == 0);
  // The next frames skip the map, even where it would cull: their images are the same regardless.
  for (int frame = 0; frame < 15; ++frame) {
    const FrameResult rested = cluster.renderFrame(opaque);
    CAPTURE(frame);
    CHECK(culledPairs(rested) == 0);
    CHECK(test::diffAgainstReference(*volume, opaque, rested.image) <= 1e-5f + (1.0f - opaque.settings.earlyTermination));
  }
  CHECK(culledPairs(cluster.renderFrame(opaque)) == opaqueCulled);  // tried again, and kept
}
