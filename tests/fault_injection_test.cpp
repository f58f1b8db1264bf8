// Fault injection: a node that throws, a lost, late or corrupted message. The frame fails within a
// bounded time with an error naming the node; nothing hangs; the next frame renders correctly.
#include <doctest/doctest.h>

#include "core/util/clock.h"
#include "core/util/error.h"
#include "test_support.h"

using namespace kdswap;

namespace {

struct Setup {
  std::unique_ptr<MemoryVolume> volume = test::makeBlobs({24, 24, 24});
  Brick whole = wholeVolumeBrick(*volume);
  FrameRequest request;
  Setup() {
    request.width = 40;
    request.height = 32;
    request.transfer = test::testTransfer();
    request.settings.earlyTermination = 1.0f;
  }
  float diffAgainstReference(const Image& image) const {
    const ReferenceResult ref = renderReference(whole, request.view, request.width, request.height, request.transfer,
                                                request.settings, glm::vec2(volume->info().minValue, volume->info().maxValue));
    return maxAbsDifference(image, ref.image, ref.image.rect());
  }
};

// Both ways of running nodes: oneTBB tasks that suspend, and one thread per node. Sanitizer
// builds run only threads: ASan cannot follow an exception thrown on a task stack that was
// suspended and resumed (swapcontext), and reports its own stale poison later.
#if defined(KDSWAP_SANITIZED)
constexpr NodeExecution kExecutions[] = {NodeExecution::Threads};
#else
constexpr NodeExecution kExecutions[] = {NodeExecution::Tasks, NodeExecution::Threads};
#endif
const char* name(NodeExecution e) { return e == NodeExecution::Tasks ? "tasks" : "threads"; }

// Runs one faulty frame, returns its error message, then checks the next frame is right.
std::string failOnceThenRecover(FaultPlan fault, NodeExecution execution, const std::string& strategy = "binary-swap",
                                int nodes = 8) {
  CAPTURE(name(execution));
  Setup s;
  ClusterOptions options;
  options.execution = execution;
  options.nodes = nodes;
  options.strategy = strategy;
  options.stallSeconds = 1.0;
  options.checksums = true;
  VirtualCluster cluster(*s.volume, options);
  cluster.injectFault(fault);
  std::string message;
  const double start = nowSeconds();
  try {
    cluster.renderFrame(s.request);
  } catch (const Error& e) {
    message = e.what();
  }
  CHECK(nowSeconds() - start < 10.0);  // bounded: stall limit plus slack, never a hang
  const FrameResult next = cluster.renderFrame(s.request);
  CHECK(s.diffAgainstReference(next.image) <= 1e-5f);
  return message;
}

}  // namespace

TEST_CASE("a node that throws while rendering fails the frame with its name, and the next frame is right") {
  FaultPlan fault;
  fault.kind = FaultPlan::Kind::ThrowInRender;
  fault.node = 3;
  for (NodeExecution execution : kExecutions) {
    const std::string message = failOnceThenRecover(fault, execution);
    CHECK(message.find("node 3") != std::string::npos);
    CHECK(message.find("rendering") != std::string::npos);
  }
}

TEST_CASE("a node that throws while compositing fails the frame with its name") {
  FaultPlan fault;
  fault.kind = FaultPlan::Kind::ThrowInComposite;
  fault.node = 5;
  for (NodeExecution execution : kExecutions) {
    const std::string message = failOnceThenRecover(fault, execution);
    CHECK(message.find("node 5") != std::string::npos);
    CHECK(message.find("compositing") != std::string::npos);
  }
}

TEST_CASE("a dropped message stalls its receiver, which is reported after the time limit") {
  for (NodeExecution execution : kExecutions)
  for (const std::string strategy : {"binary-swap", "binary-tree", "sequential"}) {
    FaultPlan fault;
    fault.kind = FaultPlan::Kind::DropMessage;
    fault.node = 2;
    const std::string message = failOnceThenRecover(fault, execution, strategy);
    // A lost message between nodes stalls its receiver; a lost tile is missed by the host.
    const bool stalled = message.find("stalled") != std::string::npos && message.find("waits for node 2") != std::string::npos;
    const bool lostTile = message.find("no tile arrived from node 2") != std::string::npos;
    CHECK_MESSAGE((stalled || lostTile), strategy << ": " << message);
  }
}

TEST_CASE("a message delayed past the time limit fails the frame instead of hanging") {
  FaultPlan fault;
  fault.kind = FaultPlan::Kind::DelayMessage;
  fault.node = 1;
  fault.delaySeconds = 2.5;
  for (NodeExecution execution : kExecutions) {
    const std::string message = failOnceThenRecover(fault, execution, "binary-swap", 4);
    CHECK(message.find("stalled") != std::string::npos);
  }
}

TEST_CASE("a corrupted message is detected by its checksum and never composited") {
  FaultPlan fault;
  fault.kind = FaultPlan::Kind::CorruptMessage;
  fault.node = 6;
  for (NodeExecution execution : kExecutions) {
    const std::string message = failOnceThenRecover(fault, execution);
    CHECK(message.find("checksum") != std::string::npos);
    CHECK(message.find("from node 6") != std::string::npos);
  }
}

TEST_CASE("a render that takes longer than the stall limit is progress, not a stall") {
  // The limit is far below the frame's time: a node still rendering (P = 1, where nobody ever
  // waits; P = 2, where the first node done waits for the other) must not end the frame.
  Setup s;
  s.request.width = s.request.height = 384;
  s.request.settings.stepVoxels = 0.01f;
  for (NodeExecution execution : kExecutions)
    for (int nodes : {1, 2}) {
      CAPTURE(name(execution));
      CAPTURE(nodes);
      ClusterOptions options;
      options.execution = execution;
      options.nodes = nodes;
      options.stallSeconds = 0.001;  // the watchdog looks every 50 ms: the first look would end it
      VirtualCluster cluster(*s.volume, options);
      const double start = nowSeconds();
      const FrameResult frame = cluster.renderFrame(s.request);
      // The frame outlasted the limit and the watchdog's 50 ms looks (0.25 s on a quiet machine).
      CHECK(nowSeconds() - start > 0.1);
      CHECK(s.diffAgainstReference(frame.image) <= 1e-5f);
    }
}
