// The k-d partition: bricks tile the volume exactly, replicated layers are as specified, no node
// holds the whole volume, and the traversal is a valid visibility order for any view.
#include <doctest/doctest.h>

#include <cstring>
#include <random>

#include "core/camera/camera.h"
#include "core/partition/kd_tree.h"
#include "core/volume/brick.h"
#include "test_support.h"

using namespace kdswap;

TEST_CASE("bricks' owned voxels add up to the volume exactly, without overlap") {
  for (glm::ivec3 dims : {glm::ivec3(33, 29, 31), glm::ivec3(64, 64, 64), glm::ivec3(5, 40, 2)})
    for (PartitionKind kind : {PartitionKind::KdTree, PartitionKind::Slab})
      for (int ranks : {1, 2, 3, 5, 7, 8, 12, 13, 16, 31, 64, 100}) {
        const KdTree tree = KdTree::build(dims, ranks, kind, 1);
        std::vector<int> owner(std::size_t(dims.x) * dims.y * dims.z, 0);
        std::int64_t total = 0;
        for (int r = 0; r < ranks; ++r) {
          const VoxelBox owned = Brick::ownedVoxelsFor(tree.brick(r), dims);
          total += owned.count();
          for (int z = owned.lo.z; z < owned.hi.z; ++z)
            for (int y = owned.lo.y; y < owned.hi.y; ++y)
              for (int x = owned.lo.x; x < owned.hi.x; ++x) ++owner[(std::size_t(z) * dims.y + y) * dims.x + x];
        }
        CHECK(total == std::int64_t(owner.size()));
        CHECK(std::all_of(owner.begin(), owner.end(), [](int c) { return c == 1; }));
      }
}

TEST_CASE("a brick stores its owned voxels plus one replicated layer and one gradient ghost layer") {
  const glm::ivec3 dims(64, 48, 40);
  const KdTree tree = KdTree::build(dims, 8, PartitionKind::KdTree);
  for (int r = 0; r < 8; ++r) {
    const VoxelBox owned = tree.brick(r);
    const VoxelBox stored = Brick::storedBoxFor(owned, dims);
    for (int a = 0; a < 3; ++a) {
      CHECK(stored.lo[a] == std::max(owned.lo[a] - 1, 0));
      // owned.hi is the shared (replicated) voxel plane; one more layer feeds its gradient.
      CHECK(stored.hi[a] == std::min(owned.hi[a] + 2, dims[a]));
    }
    CHECK(stored.count() < std::int64_t(dims.x) * dims.y * dims.z);  // no node holds the whole volume
  }
}

TEST_CASE("a brick keeps values and gradients only where its samples reach, and ships exactly what it received") {
  auto volume = test::makeBlobs({37, 30, 26}, glm::vec3(1.0f, 0.8f, 1.4f));
  const glm::ivec3 dims = volume->info().dims;
  const Brick whole = test::brickOf(*volume, VoxelBox{glm::ivec3(0), dims - 1});
  const KdTree tree = KdTree::build(dims, 8, PartitionKind::KdTree);
  for (int r = 0; r < 8; ++r) {
    const VoxelBox owned = tree.brick(r);
    const VoxelBox received = Brick::storedBoxFor(owned, dims);
    std::vector<float> raw(std::size_t(received.count()));
    volume->read(received, raw.data());
    const Brick brick(owned, dims, volume->info().spacing, raw, Brick::Shipping::Yes);
    CHECK(brick.stored() == VoxelBox{owned.lo, owned.hi + 1});  // samples in [lo, hi) touch voxels lo..hi
    CHECK(brick.storedValues() == raw);                          // shipping loses nothing
    const Brick rebuilt(owned, dims, volume->info().spacing, brick.storedValues());
    int differing = 0;
    for (int z = brick.stored().lo.z; z < brick.stored().hi.z; ++z)
      for (int y = brick.stored().lo.y; y < brick.stored().hi.y; ++y)
        for (int x = brick.stored().lo.x; x < brick.stored().hi.x; ++x) {
          const Voxel &a = brick.voxel(x, y, z), &b = rebuilt.voxel(x, y, z), &w = whole.voxel(x, y, z);
          differing += !(a.value == b.value && a.gradient == b.gradient);
          differing += !(a.value == w.value && a.gradient == w.gradient);  // gradients equal the whole volume's
        }
    CHECK(differing == 0);
    // The voxels kept (the cells' maps aside, a few bytes a cell) are fewer than those received.
    const std::uint64_t cells = brick.cellRanges().bytes() + brick.uniformCells().size();
    CHECK(brick.bytes() - cells < std::uint64_t(received.count()) * sizeof(Voxel));
    // A brick that stays home drops the outer ghost layer and renders from identical voxels.
    const Brick home(owned, dims, volume->info().spacing, raw);
    CHECK_FALSE(home.shippable());
    CHECK(home.bytes() + (received.count() - brick.stored().count()) * sizeof(float) == brick.bytes());
    CHECK(std::memcmp(home.voxelData(), brick.voxelData(), std::size_t(brick.stored().count()) * sizeof(Voxel)) == 0);
  }
}

TEST_CASE("node counts that are not powers of two get sizes in proportion, extras beside their siblings") {
  const glm::ivec3 dims(121, 121, 121);
  const KdTree tree = KdTree::build(dims, 12, PartitionKind::KdTree);
  std::int64_t smallest = 1LL << 60, largest = 0;
  for (int r = 0; r < 12; ++r) {
    const std::int64_t c = Brick::ownedVoxelsFor(tree.brick(r), dims).count();
    smallest = std::min(smallest, c);
    largest = std::max(largest, c);
  }
  CHECK(double(largest) / double(smallest) < 1.2);
  // Rank j + 8 (j < 4) is the k-d sibling of rank j, so folding it into j merges a subtree.
  int extrasSeen = 0;
  for (const KdNode& n : tree.nodes()) {
    if (n.low < 0) continue;
    const KdNode &lo = tree.nodes()[std::size_t(n.low)], &hi = tree.nodes()[std::size_t(n.high)];
    if (hi.rank >= 8) {
      CHECK(lo.rank == hi.rank - 8);
      ++extrasSeen;
    }
  }
  CHECK(extrasSeen == 4);
}

TEST_CASE("the k-d traversal is a valid visibility order for random views") {
  std::mt19937 rng(11);
  std::uniform_real_distribution<float> az(-180.0f, 180.0f), el(-85.0f, 85.0f), dist(1.2f, 5.0f);
  const glm::ivec3 dims(50, 40, 30);
  const glm::vec3 spacing(1.0f, 1.0f, 2.0f);
  const KdTree tree = KdTree::build(dims, 13, PartitionKind::KdTree);
  for (int trial = 0; trial < 200; ++trial) {
    View view;
    view.azimuthDeg = az(rng);
    view.elevationDeg = el(rng);
    view.distance = dist(rng);
    view.projection = trial % 2 ? Projection::Orthographic : Projection::Perspective;
    const Camera camera(view, glm::vec3(0.0f), glm::vec3(dims - 1) * spacing, 16, 16);
    const VisibilityOrder order = tree.order(camera, spacing);
    // Brick A occludes brick B along a ray if the ray meets A first. Sample rays through random
    // points of every pair of bricks and check that such a ray never meets B before A when A
    // comes after B in the order.
    for (int probe = 0; probe < 40; ++probe) {
      std::uniform_int_distribution<int> pick(0, 12);
      const int a = pick(rng), b = pick(rng);
      if (a == b) continue;
      const VoxelBox ba = tree.brick(a), bb = tree.brick(b);
      // Bricks are disjoint boxes, so planes of their faces separate them. If the eye is on A's
      // side of every separating plane, A can occlude B (a ray can meet A then B) and B can never
      // occlude A: A must come first. Mixed sides mean no ray meets both, and any order is fine.
      int votesA = 0, votesB = 0;
      bool unconstrained = false;
      for (int axis = 0; axis < 3; ++axis) {
        bool aLow;
        float gapLo, gapHi;  // world-space gap between the two boxes along this axis
        if (ba.hi[axis] <= bb.lo[axis]) aLow = true, gapLo = float(ba.hi[axis]), gapHi = float(bb.lo[axis]);
        else if (bb.hi[axis] <= ba.lo[axis]) aLow = false, gapLo = float(bb.hi[axis]), gapHi = float(ba.lo[axis]);
        else continue;
        gapLo *= spacing[axis], gapHi *= spacing[axis];
        bool eyeLow;
        if (camera.orthographic()) {
          if (camera.forward()[axis] == 0.0f) { unconstrained = true; continue; }
          eyeLow = camera.forward()[axis] > 0.0f;
        } else {
          const float e = camera.eye()[axis];
          if (e >= gapLo && e <= gapHi) { unconstrained = true; continue; }  // no ray meets both boxes
          eyeLow = e < gapLo;
        }
        (eyeLow == aLow ? votesA : votesB)++;
      }
      if (unconstrained) continue;
      if (votesA > 0 && votesB == 0) CHECK_MESSAGE(order.inFront(a, b), "view " << view.azimuthDeg << "," << view.elevationDeg);
      if (votesB > 0 && votesA == 0) CHECK_MESSAGE(order.inFront(b, a), "view " << view.azimuthDeg << "," << view.elevationDeg);
    }
  }
}
