// Background node-count sweep: one cluster per P, one measured frame each.
#include "ui/sweep_worker.h"

#include "ui/render_worker.h"

namespace kdswap {

SweepWorker::~SweepWorker() { cancel(); }

void SweepWorker::cancel() {
  cancel_ = true;
  if (thread_.joinable()) thread_.join();
  cancel_ = false;
}

void SweepWorker::start(std::shared_ptr<const VolumeSource> source, const ClusterOptions& base,
                        const FrameRequest& request, std::vector<int> nodeCounts) {
  cancel();
  {
    std::lock_guard lock(mutex_);
    counts_ = std::move(nodeCounts);
    points_.clear();
    error_.clear();
  }
  running_ = true;
  thread_ = std::thread([this, source, base, request] { run(source, base, request); });
}

float SweepWorker::progress() const {
  std::lock_guard lock(mutex_);
  return counts_.empty() ? 0.0f : float(points_.size()) / float(counts_.size());
}

std::vector<SweepPoint> SweepWorker::points() const {
  std::lock_guard lock(mutex_);
  return points_;
}

std::string SweepWorker::error() const {
  std::lock_guard lock(mutex_);
  return error_;
}

void SweepWorker::run(std::shared_ptr<const VolumeSource> source, ClusterOptions base, FrameRequest request) {
  // One worker thread: the nodes' times are then each one processor's work, which is what the
  // modelled time assumes, and the interactive renderer keeps the other cores.
  base.threads = 1;
  BackgroundThreads background;
  request.recordPhases = false;
  std::vector<int> counts;
  {
    std::lock_guard lock(mutex_);
    counts = counts_;
  }
  try {
    for (int p : counts) {
      if (cancel_) break;
      ClusterOptions options = base;
      options.nodes = p;
      VirtualCluster cluster(*source, options);
      if (cancel_) break;
      const FrameResult result = cluster.renderFrame(request);
      SweepPoint point{p, result.stats.modelledParallelSeconds(), result.stats.renderMax(), result.stats.compositeMax()};
      std::lock_guard lock(mutex_);
      points_.push_back(point);
    }
  } catch (const std::exception& e) {
    std::lock_guard lock(mutex_);
    error_ = e.what();
  }
  running_ = false;
}

}  // namespace kdswap
