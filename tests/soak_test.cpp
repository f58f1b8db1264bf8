// Soak and stress: many frames with the view changing every frame keep memory flat and never
// fail; the largest node count runs at a small image.
#include <doctest/doctest.h>

#include <cstddef>

#include "core/util/memory.h"
#include "test_support.h"

using namespace kdswap;

#if defined(KDSWAP_SANITIZED)
// The sanitizer runtimes' allocator statistics (sanitizer/allocator_interface.h, which GCC does
// not install): bytes the program holds now, without ASan's quarantine of freed blocks.
extern "C" std::size_t __sanitizer_get_current_allocated_bytes();
#endif

namespace {

#if defined(__SANITIZE_THREAD__)
// ThreadSanitizer (scripts/tsan.sh) starts 64 instrumented threads per frame with oneTBB on one
// thread per caller; 300 frames (200 after the warm-up) keep that stage within CI's time while
// still renewing every node's buffers hundreds of times.
constexpr int kSoakFrames = 300;
#else
constexpr int kSoakFrames = 1000;
#endif

#if defined(KDSWAP_SANITIZED)
// Resident memory in sanitizer builds also counts ASan's quarantine of freed blocks (up to
// 256 MiB) and shadow memory, so "flat" is measured on the heap bytes the program holds (under
// ASan, LeakSanitizer also reports anything unreachable at exit).
std::uint64_t memoryInUse() { return __sanitizer_get_current_allocated_bytes(); }
#else
std::uint64_t memoryInUse() { return currentResidentBytes(); }
#endif

}  // namespace

TEST_CASE("1000 frames at P = 64 with a new view every frame: no failure and flat memory") {
  auto volume = test::makeBlobs({32, 32, 32});
  ClusterOptions options;
  options.nodes = 64;
  options.checksums = true;
  VirtualCluster cluster(*volume, options);
  FrameRequest request;
  request.width = 48;
  request.height = 40;
  request.transfer = test::testTransfer();
  std::uint64_t inUseAfterWarmUp = 0;
  int frames = 0;
  for (int f = 0; f < kSoakFrames; ++f) {
    request.view.azimuthDeg = float(f) * 7.3f;
    request.view.elevationDeg = float((f * 13) % 140) - 70.0f;
    request.view.projection = f % 3 == 0 ? Projection::Orthographic : Projection::Perspective;
    const FrameResult frame = cluster.renderFrame(request);
    REQUIRE(frame.stats.perNode.size() == 64);
    ++frames;
    if (f == 99) inUseAfterWarmUp = memoryInUse();
  }
  CHECK(frames == kSoakFrames);
  const std::uint64_t inUseAtEnd = memoryInUse();
  INFO("memory in use after 100 frames " << inUseAfterWarmUp << ", after " << kSoakFrames << " " << inUseAtEnd);
  CHECK(inUseAtEnd <= inUseAfterWarmUp + 16ull * 1024 * 1024);
}

TEST_CASE("4096 nodes, the largest cluster, render a small image correctly") {
  auto volume = test::makeBlobs({40, 36, 32});
  ClusterOptions options;
  options.nodes = 4096;
  options.threads = 2;
  VirtualCluster cluster(*volume, options);
  FrameRequest request;
  request.width = 24;
  request.height = 20;
  request.transfer = test::testTransfer();
  request.settings.earlyTermination = 1.0f;
  const FrameResult frame = cluster.renderFrame(request);
  const Brick whole = wholeVolumeBrick(*volume);
  const ReferenceResult ref = renderReference(whole, request.view, 24, 20, request.transfer, request.settings,
                                              glm::vec2(volume->info().minValue, volume->info().maxValue));
  CHECK(maxAbsDifference(frame.image, ref.image, ref.image.rect()) <= 1e-5f);
}
