// Node program: receive brick; per frame render -> compose -> send tile. Also the per-phase
// instrumentation (a PhaseObserver that timestamps phases and subtracts time spent waiting).
#include "core/cluster/node_program.h"

#include <algorithm>

#include "core/composite/image_message.h"
#include "core/render/ray_caster.h"
#include "core/util/clock.h"
#include "core/util/error.h"

namespace kdswap {
namespace {

class NodePhaseObserver : public PhaseObserver {
 public:
  NodePhaseObserver(Communicator& comm, NodeReport& report, std::vector<PhaseCell>* cells)
      : comm_(comm), report_(report), cells_(cells) {}

  void beginPhase(std::string_view label, int partner) override {
    current_ = PhaseStats{};
    current_.label = std::string(label);
    current_.partner = partner;
    startCounters_ = comm_.counters();
    startTime_ = nowSeconds();
  }

  void endPhase(const Rect& region, const Image& image, std::int64_t pixels) override {
    const CommCounters& now = comm_.counters();
    current_.waitSeconds = now.waitSeconds - startCounters_.waitSeconds;
    current_.computeSeconds = std::max(0.0, nowSeconds() - startTime_ - current_.waitSeconds);
    current_.bytesSent = now.bytesSent - startCounters_.bytesSent;
    current_.bytesReceived = now.bytesReceived - startCounters_.bytesReceived;
    current_.messagesSent = now.messagesSent - startCounters_.messagesSent;
    current_.messagesReceived = now.messagesReceived - startCounters_.messagesReceived;
    current_.pixels = pixels;
    current_.region = region;
    largestImage_ = std::max<std::uint64_t>(largestImage_, image.bytes());
    if (cells_)
      cells_->push_back(PhaseCell{current_.label, current_.partner, region, image,
                                  current_.bytesSent + current_.bytesReceived});
    report_.phases.push_back(current_);
  }

  void noteImage(const Image& image) { largestImage_ = std::max<std::uint64_t>(largestImage_, image.bytes()); }
  std::uint64_t largestImage() const { return largestImage_; }

 private:
  Communicator& comm_;
  NodeReport& report_;
  std::vector<PhaseCell>* cells_;
  PhaseStats current_;
  CommCounters startCounters_;
  double startTime_ = 0;
  std::uint64_t largestImage_ = 0;
};

}  // namespace

void receiveBrick(NodeState& node, Communicator& comm) {
  Message m = comm.receive(Communicator::kHost, kBrickTag);
  // header: owned lo (3), owned hi (3), volume dims (3); spacing travels as the first 3 payload values.
  if (m.header.size() != 9 || m.payload.size() < 3)
    throw Error("node " + std::to_string(comm.rank()) + ": malformed brick message");
  const VoxelBox owned{glm::ivec3(int(m.header[0]), int(m.header[1]), int(m.header[2])),
                       glm::ivec3(int(m.header[3]), int(m.header[4]), int(m.header[5]))};
  const glm::ivec3 dims(int(m.header[6]), int(m.header[7]), int(m.header[8]));
  const glm::vec3 spacing(m.payload[0], m.payload[1], m.payload[2]);
  m.payload.erase(m.payload.begin(), m.payload.begin() + 3);
  node.rank = comm.rank();
  node.brick = Brick(owned, dims, spacing, std::move(m.payload));
}

NodeReport runNodeFrame(NodeState& node, Communicator& comm, const FramePlan& plan, PhaseRecord* record) {
  NodeReport report;
  report.rank = comm.rank();
  std::vector<PhaseCell>* cells = record ? &record->cells[std::size_t(comm.rank())] : nullptr;
  NodePhaseObserver observer(comm, report, cells);

  RenderCounters counters;
  const RayCaster caster(node.brick, plan.table, plan.request.settings, plan.valueRange);
  Image partial = caster.render(plan.camera, counters);
  report.renderSeconds = counters.seconds;
  report.rays = counters.rays;
  report.samples = counters.samples;
  observer.noteImage(partial);
  if (cells) cells->push_back(PhaseCell{"render", -1, partial.rect(), partial, 0});

  Tile tile = plan.strategy.compose(std::move(partial), plan.frame(), plan.order, comm, observer);

  Message out = imageToMessage(std::move(tile.image));
  const Rect& r = tile.region;
  out.header.insert(out.header.end(), {r.x, r.y, r.w, r.h});
  comm.send(Communicator::kHost, kTileTag, std::move(out));
  report.privateBytes = node.brick.bytes() + observer.largestImage();
  return report;
}

}  // namespace kdswap
