// The GUI's background renderer: a single-slot mailbox (newest request wins) and one thread.
#include "ui/render_worker.h"

#include <algorithm>
#include <filesystem>
#include <system_error>

#if defined(__linux__)
#include <sys/resource.h>
#include <sys/syscall.h>
#include <unistd.h>
#endif

#include <nlohmann/json.hpp>

#include "core/cluster/lattice_passes.h"
#include "core/util/clock.h"
#include "core/util/error.h"
#include "core/volume/datasets/dataset.h"
#include "core/volume/reader.h"
#include "ui/histogram.h"

namespace kdswap {
namespace {

constexpr int kStageCellSide = 192;

}  // namespace

bool SceneSpec::sameScene(const SceneSpec& o) const {
  const ClusterOptions &a = cluster, &b = o.cluster;
  // The layout matters only for the file it describes; a corrected one must open the file again.
  const bool raw = data == rawPath, otherRaw = o.data == o.rawPath;
  return data == o.data && raw == otherRaw && (!raw || this->raw == o.raw) && a.nodes == b.nodes &&
         a.partition == b.partition && a.slabAxis == b.slabAxis &&
         a.strategy == b.strategy && a.threads == b.threads && a.bricksPerNode == b.bricksPerNode &&
         a.balance == b.balance &&
         (a.balance != "cost" || a.balanceTransfer.toJson() == b.balanceTransfer.toJson());
}

void useCostBalance(ClusterOptions& cluster, const TransferFunction& transfer) {
  cluster.balance = "cost";
  cluster.balanceTransfer = transfer;
  cluster.balanceRange = glm::vec2(0.0f);  // empty: the data's range
}

void lowerThreadPriority() {
#if defined(__linux__)
  // On Linux the nice value is per thread; failing to lower it only costs responsiveness.
  const id_t tid = id_t(syscall(SYS_gettid));
  if (getpriority(PRIO_PROCESS, tid) < kBackgroundNice) setpriority(PRIO_PROCESS, tid, kBackgroundNice);
#endif
}

BackgroundThreads::BackgroundThreads() {
  lowerThreadPriority();
  observe(true);
}

BackgroundThreads::~BackgroundThreads() { observe(false); }

void BackgroundThreads::on_scheduler_entry(bool isWorker) {
  if (isWorker) lowerThreadPriority();
}

std::unique_ptr<VolumeSource> openVolumeSpec(const std::string& data, const RawLayout& layout) {
  if (isDatasetSpec(data)) return openDataset(data);
  // Neither a built-in name nor a file: say what would have been accepted.
  const std::string builtIn = "a built-in data set NAME[:SIZE] (" + datasetNameList() + "; e.g. phantom:128)";
  if (data.empty()) throw Error("no data set given: expected " + builtIn + " or a volume file");
  std::error_code ec;
  if (!std::filesystem::exists(std::filesystem::status(data, ec)))
    throw Error("\"" + data + "\": no such file, and not " + builtIn);
  return openVolumeFile(data, layout);
}

RenderWorker::RenderWorker() : worker_([this] { run(); }) {}

RenderWorker::~RenderWorker() {
  {
    std::lock_guard lock(mutex_);
    stop_ = true;
    pending_.reset();
  }
  wake_.notify_all();
  worker_.join();
}

std::uint64_t RenderWorker::submit(const SceneSpec& scene, const FrameRequest& request, bool preview, int passes) {
  std::uint64_t id;
  {
    std::lock_guard lock(mutex_);
    id = nextId_++;
    pending_ = Job{id, scene, request, preview, preview ? 1 : std::max(1, passes), nowSeconds()};
  }
  wake_.notify_one();
  return id;
}

std::shared_ptr<const SceneSnapshot> RenderWorker::takeScene() {
  std::lock_guard lock(mutex_);
  return std::exchange(newScene_, nullptr);
}

std::shared_ptr<const FrameSnapshot> RenderWorker::takeFrame() {
  std::lock_guard lock(mutex_);
  return std::exchange(newFrame_, nullptr);
}

std::vector<std::string> RenderWorker::takeErrors() {
  std::lock_guard lock(mutex_);
  return std::exchange(errors_, {});
}

bool RenderWorker::busy() const {
  std::lock_guard lock(mutex_);
  return inFlight_ || pending_.has_value();
}

bool RenderWorker::building() const {
  std::lock_guard lock(mutex_);
  return buildingScene_;
}

std::uint64_t RenderWorker::lastFailed() const {
  std::lock_guard lock(mutex_);
  return lastFailed_;
}

void RenderWorker::run() {
  BackgroundThreads background;
  for (;;) {
    Job job;
    {
      std::unique_lock lock(mutex_);
      wake_.wait(lock, [this] { return stop_ || pending_.has_value(); });
      if (stop_) return;
      job = std::move(*pending_);
      pending_.reset();
      inFlight_ = true;
    }
    try {
      process(job);
    } catch (const std::exception& e) {
      // A failed frame leaves the cluster usable (VirtualCluster's contract): report and go on.
      std::lock_guard lock(mutex_);
      errors_.push_back(e.what());
      lastFailed_ = job.id;
    }
    std::lock_guard lock(mutex_);
    inFlight_ = false;
  }
}

// Builds the scene when the spec changed. On failure the previous scene stays (and the failed
// spec is remembered so that view changes submitted meanwhile do not retry it).
bool RenderWorker::ensureScene(const SceneSpec& spec) {
  if (scene_ && scene_->spec.sameScene(spec)) return true;
  if (failedSpec_ && failedSpec_->sameScene(spec)) return scene_ != nullptr;
  {
    std::lock_guard lock(mutex_);
    buildingScene_ = true;
  }
  try {
    const double start = nowSeconds();
    std::shared_ptr<const VolumeSource> source =
        openVolumeSpec(spec.data, spec.data == spec.rawPath ? spec.raw : RawLayout{});
    auto cluster = std::make_unique<VirtualCluster>(*source, spec.cluster);
    auto scene = std::make_shared<SceneSnapshot>();
    scene->spec = spec;
    scene->info = source->info();
    scene->tree = cluster->tree();
    scene->histogram = computeHistogram(*source);
    scene->source = source;
    scene->distributeSeconds = cluster->distributeSeconds();
    scene->buildSeconds = nowSeconds() - start;
    cluster_.reset();  // free the old bricks before publishing
    cluster_ = std::move(cluster);
    scene_ = scene;
    failedSpec_.reset();
    std::lock_guard lock(mutex_);
    buildingScene_ = false;
    newScene_ = scene;
    return true;
  } catch (const std::exception& e) {
    failedSpec_ = spec;
    std::lock_guard lock(mutex_);
    buildingScene_ = false;
    errors_.push_back(e.what());
    return scene_ != nullptr;
  }
}

void RenderWorker::process(const Job& job) {
  if (!ensureScene(job.scene)) {  // no scene at all: ensureScene queued the error
    std::lock_guard lock(mutex_);
    lastFailed_ = job.id;
    return;
  }
  FrameRequest request = job.request;
  request.recordPhases = !job.preview;
  // Pass 1 is the frame; a refined job's later passes publish the running mean with pass 1's
  // stats and stages, until they are done or a newer request waits.
  const Rect frameRect{0, 0, request.width, request.height};
  std::shared_ptr<const FrameSnapshot> first;
  renderPasses(*cluster_, request, job.passes, [&](int pass, const FrameResult& result, const ImageAverage& mean) {
    std::shared_ptr<FrameSnapshot> frame;
    if (pass == 0) {
      frame = std::make_shared<FrameSnapshot>();
      frame->id = job.id;
      frame->preview = job.preview;
      frame->request = request;
      frame->scene = scene_;
      frame->stats = result.stats;
      frame->image = toPixels(result.image, frameRect, std::max(request.width, request.height));
      if (result.phases) {
        frame->stages = buildStageAtlas(*result.phases, kStageCellSide);
        frame->phases = result.phases;
      }
      frame->passesRequested = job.passes;
      first = frame;
    } else {
      frame = std::make_shared<FrameSnapshot>(*first);
      frame->image = toPixels(mean.mean(), frameRect, std::max(request.width, request.height));
      frame->passes = pass + 1;
    }
    frame->seconds = nowSeconds() - job.submitted;
    std::lock_guard lock(mutex_);
    newFrame_ = frame;
    return !stop_ && !pending_.has_value();  // a newer request ends the refinement
  });
}

}  // namespace kdswap
