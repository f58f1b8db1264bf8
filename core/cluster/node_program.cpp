// Node program: receive brick; per frame render -> compose -> send tile. Also the per-phase
// instrumentation (a PhaseObserver that timestamps phases and subtracts time spent waiting).
#include "core/cluster/node_program.h"

#include <algorithm>
#include <limits>

#include <glm/vector_relational.hpp>

#include "core/comm/mailbox.h"
#include "core/composite/image_message.h"
#include "core/render/ray_caster.h"
#include "core/util/clock.h"
#include "core/util/error.h"

namespace kdswap {
namespace {

//! Floats before a brick message's voxels: spacing (3) and VoxelStorage (4).
constexpr std::size_t kBrickPreamble = 7;

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
    const double end = nowSeconds();
    const CommCounters& now = comm_.counters();
    // One reading of the clock for both, so the wait and the compute time fill [start, end].
    current_.start = startTime_;
    current_.end = end;
    current_.waitSeconds = now.waitSeconds - startCounters_.waitSeconds;
    current_.computeSeconds = std::max(0.0, end - startTime_ - current_.waitSeconds);
    current_.bytesSent = now.bytesSent - startCounters_.bytesSent;
    current_.bytesReceived = now.bytesReceived - startCounters_.bytesReceived;
    current_.messagesSent = now.messagesSent - startCounters_.messagesSent;
    current_.messagesReceived = now.messagesReceived - startCounters_.messagesReceived;
    current_.pixels = pixels;
    current_.region = region;
    largestImage_ = std::max<std::uint64_t>(largestImage_, image.bytes());
    // A strategy may keep pixels outside its region (binary swap composites in place and crops
    // once at the end); the stage record shows only what the node owns.
    if (cells_)
      cells_->push_back(PhaseCell{current_.label, current_.partner, region,
                                  region.contains(image.rect()) ? image : image.crop(region),
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

Message brickMessage(const VoxelBox& owned, const glm::ivec3& dims, const glm::vec3& spacing,
                     const VoxelStorage& storage, std::vector<float> storedValues, int piece) {
  Message m;
  m.header = {owned.lo.x, owned.lo.y, owned.lo.z, owned.hi.x, owned.hi.y, owned.hi.z, dims.x, dims.y, dims.z};
  if (piece >= 0) m.header.push_back(piece);
  m.payload.reserve(kBrickPreamble + storedValues.size());
  m.payload = {spacing.x, spacing.y, spacing.z, storage.compactFormat() ? 1.0f : 0.0f, storage.valueOrigin,
               storage.valueStep, storage.gradientScale};
  m.payload.insert(m.payload.end(), storedValues.begin(), storedValues.end());
  return m;
}

void receiveBrick(NodeState& node, Communicator& comm, int source) {
  Message m = comm.receive(source, kBrickTag);
  // header: owned lo (3), owned hi (3), volume dims (3) [, piece]; spacing (3) and the voxel
  // storage (format, value origin and step, gradient scale) travel as the first payload values.
  const auto fitsInt = [](std::int64_t v) { return v >= 0 && v <= std::numeric_limits<int>::max(); };
  if ((m.header.size() != 9 && m.header.size() != 10) || m.payload.size() < kBrickPreamble ||
      (m.payload[3] != 0.0f && m.payload[3] != 1.0f) || !std::all_of(m.header.begin(), m.header.begin() + 9, fitsInt))
    throw Error("malformed brick message");
  const VoxelBox owned{glm::ivec3(int(m.header[0]), int(m.header[1]), int(m.header[2])),
                       glm::ivec3(int(m.header[3]), int(m.header[4]), int(m.header[5]))};
  const glm::ivec3 dims(int(m.header[6]), int(m.header[7]), int(m.header[8]));
  // Samples lie in [0, dims - 1) and a brick keeps one more layer: a box reaching past dims - 1
  // would build the brick from voxels beyond those the message holds.
  if (!owned.empty() && glm::any(glm::greaterThan(owned.hi, dims - 1)))
    throw Error("brick message: its box lies outside the volume");
  const glm::vec3 spacing(m.payload[0], m.payload[1], m.payload[2]);
  VoxelStorage storage;
  storage.format = m.payload[3] == 1.0f ? VoxelFormat::Compact : VoxelFormat::Float;
  storage.valueOrigin = m.payload[4], storage.valueStep = m.payload[5], storage.gradientScale = m.payload[6];
  m.payload.erase(m.payload.begin(), m.payload.begin() + kBrickPreamble);
  if (Brick::storedBoxFor(owned, dims).count() != std::int64_t(m.payload.size()))
    throw Error("brick message holds the wrong number of voxels");
  node.rank = comm.rank();
  if (m.header.size() == 10) {
    const int piece = int(m.header[9]);
    node.pieces.insert_or_assign(piece,
                                 Brick(owned, dims, spacing, std::move(m.payload), Brick::Shipping::Yes,
                                       Brick::kCellShiftByVolume, storage));
    node.pieceEmptySpace.erase(piece);
  } else {
    node.brick =
        Brick(owned, dims, spacing, std::move(m.payload), Brick::Shipping::No, Brick::kCellShiftByVolume, storage);
    node.brickEmptySpace.clear();
  }
}

namespace {

std::shared_ptr<const EmptySpaceMap> emptySpaceFor(EmptySpaceCache& cache, const Brick& brick, const FramePlan& plan) {
  const glm::vec2 map = normalisingScaleBias(plan.valueRange);
  return cache.mapFor(brick, plan.table, map.x, map.y, plan.request.settings.skipEmptySpace);
}

// Over-decomposition: ship the bricks others render this frame, render the assigned bricks,
// send each foreign brick's image to its home and composite the home's bricks front to back
// (one "bricks" phase). The result is exactly the partial image of the node's whole brick.
Image renderPieces(NodeState& node, Communicator& comm, const FramePlan& plan, NodeReport& report,
                   NodePhaseObserver& observer) {
  const BrickSchedule& s = *plan.bricks;
  const BrickLayout& layout = *s.layout;
  const int rank = comm.rank();
  for (auto [brick, dest] : s.ships[std::size_t(rank)]) {
    const Brick& b = node.pieces.at(brick);
    comm.send(dest, kBrickTag,
              brickMessage(b.owned(), b.volumeDims(), b.spacing(), b.storage(), b.storedValues(), brick));
  }
  for (int i = 0; i < s.receives[std::size_t(rank)]; ++i) receiveBrick(node, comm, Mailbox::kAnySource);

  std::vector<std::pair<int, Image>> rendered;
  for (int brick : s.renders[std::size_t(rank)]) {
    const auto it = node.pieces.find(brick);
    if (it == node.pieces.end())
      throw Error("was given brick " + std::to_string(brick) + " but does not hold it");
    RenderCounters counters;
    const double start = nowSeconds();
    const RayCaster caster(it->second, plan.table, plan.request.settings, plan.valueRange, plan.occlusion,
                           emptySpaceFor(node.pieceEmptySpace[brick], it->second, plan));
    rendered.emplace_back(brick, caster.render(plan.camera, counters));
    report.renderSeconds += counters.seconds;
    report.rays += counters.rays;
    report.samples += counters.samples;
    report.occluded += counters.occluded;
    report.bricks.push_back({brick, counters.seconds, counters.rays, counters.samples, start, nowSeconds()});
  }
  report.renderEnd = nowSeconds();

  observer.beginPhase("bricks", -1);
  std::map<int, Image> mine;
  for (auto& [brick, image] : rendered) {
    if (layout.home(brick) == rank) {
      mine.emplace(brick, std::move(image));
      continue;
    }
    Message m = imageToMessage(std::move(image));
    m.header.push_back(brick);
    comm.send(layout.home(brick), kPieceImageTag, std::move(m));
  }
  while (int(mine.size()) < layout.perNode()) {
    Message m = comm.receive(Mailbox::kAnySource, kPieceImageTag);
    if (m.header.size() != 5) throw Error("malformed brick image");
    const int brick = int(m.header[4]);
    m.header.resize(4);
    if (layout.home(brick) != rank || mine.count(brick))
      throw Error("unexpected image of brick " + std::to_string(brick));
    mine.emplace(brick, imageFromMessage(m));
  }
  Rect bounds;
  for (const auto& [brick, image] : mine)
    if (!image.rect().empty()) bounds = bounds.empty() ? image.rect() : bounds.unite(image.rect());
  Image partial(bounds);
  std::int64_t pixels = 0;
  for (int brick : layout.frontToBack(rank, plan.camera, plan.spacing))
    pixels += compositeInto(partial, mine.at(brick), /*otherInFront=*/false);
  observer.endPhase(plan.frame(), partial, pixels);
  return partial;
}

//! Front-to-back waves: the node's brick, once the waves have rendered it (the host says so).
RenderedBrick renderedInWaves(Communicator& comm, const FramePlan& plan) {
  comm.receive(Communicator::kHost, kBrickRenderedTag);
  return std::move((*plan.waves)[std::size_t(comm.rank())]);
}

}  // namespace

Rect ownBrickScreenRect(NodeState& node, const FramePlan& plan) {
  return RayCaster::screenRect(*emptySpaceFor(node.brickEmptySpace, node.brick, plan), node.brick.spacing(), plan.camera);
}

std::unique_ptr<RayCaster> ownBrickCaster(NodeState& node, const FramePlan& plan, FrontTransmittance* front) {
  return std::make_unique<RayCaster>(node.brick, plan.table, plan.request.settings, plan.valueRange, plan.occlusion,
                                     emptySpaceFor(node.brickEmptySpace, node.brick, plan), front);
}

RenderedBrick renderOwnBrick(NodeState& node, const FramePlan& plan, FrontTransmittance* front) {
  RenderedBrick out;
  out.start = nowSeconds();
  out.image = ownBrickCaster(node, plan, front)->render(plan.camera, out.counters, &out.content);
  out.end = nowSeconds();
  return out;
}

NodeReport runNodeFrame(NodeState& node, Communicator& comm, const FramePlan& plan, PhaseRecord* record) {
  NodeReport report;
  report.rank = comm.rank();
  // The render step starts when this node's task does: on a machine with fewer cores than nodes
  // that is when a core became free, so a timeline shows the node's wait for one.
  report.timed = true;
  report.renderStart = nowSeconds();
  std::vector<PhaseCell>* cells = record ? &record->cells[std::size_t(comm.rank())] : nullptr;
  NodePhaseObserver observer(comm, report, cells);

  Image partial;
  if (plan.bricks) {
    partial = renderPieces(node, comm, plan, report, observer);
  } else {
    RenderedBrick rendered = plan.waves ? renderedInWaves(comm, plan) : renderOwnBrick(node, plan);
    // Keep only the rectangle the brick's rays reached: the pixels around it are empty ("over"
    // with an empty pixel changes nothing), and with every node's partial image alive at once
    // before compositing, those margins were most of a frame's memory at large P.
    partial = trimTo(std::move(rendered.image), rendered.content);
    if (plan.waves) report.renderStart = rendered.start;  // rendered in its wave, while this task waited
    report.renderEnd = plan.waves ? rendered.end : nowSeconds();
    report.renderSeconds = rendered.counters.seconds;
    report.rays = rendered.counters.rays;
    report.samples = rendered.counters.samples;
    report.occluded = rendered.counters.occluded;
    report.renderedAfter = std::move(rendered.renderedAfter);
    if (cells) cells->push_back(PhaseCell{"render", -1, partial.rect(), partial, 0});
  }
  observer.noteImage(partial);
  if (plan.nodesRendered && !plan.waves) plan.nodesRendered->fetch_add(1, std::memory_order_relaxed);  // waves count their own

  Tile tile = plan.strategy.compose(std::move(partial), plan.frame(), plan.order, comm, observer);

  Message out = lendPixels(tile.pixels, std::move(tile.owner));  // the host reads it in place
  const Rect& r = tile.region;
  out.header.insert(out.header.end(), {r.x, r.y, r.w, r.h});
  comm.send(Communicator::kHost, kTileTag, std::move(out));
  std::uint64_t brickBytes = node.brick.bytes();
  for (const auto& [id, piece] : node.pieces) brickBytes += piece.bytes();
  report.privateBytes = brickBytes + observer.largestImage();
  return report;
}

}  // namespace kdswap
