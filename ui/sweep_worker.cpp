// Background node-count sweep: one cluster per P, a warm-up frame, then the median of K frames.
#include "ui/sweep_worker.h"

#include <algorithm>

#include "core/bench/statistics.h"

namespace kdswap {

SweepWorker::~SweepWorker() { cancel(); }

void SweepWorker::cancel() {
  cancel_ = true;
  if (thread_.joinable()) thread_.join();
  cancel_ = false;
}

void SweepWorker::start(std::shared_ptr<const VolumeSource> source, const ClusterOptions& base,
                        const FrameRequest& request, std::vector<int> nodeCounts, int frames) {
  cancel();
  frames = std::max(frames, 1);
  {
    std::lock_guard lock(mutex_);
    counts_ = std::move(nodeCounts);
    frames_ = frames;
    framesDone_ = 0;
    points_.clear();
    error_.clear();
  }
  running_ = true;
  thread_ = std::thread([this, source, base, request, frames] { run(source, base, request, frames); });
}

float SweepWorker::progress() const {
  std::lock_guard lock(mutex_);
  const double total = double(counts_.size()) * double(frames_ + 1);
  return total <= 0 ? 0.0f : float(std::min(1.0, double(framesDone_) / total));
}

int SweepWorker::framesPerPoint() const {
  std::lock_guard lock(mutex_);
  return frames_;
}

std::vector<SweepPoint> SweepWorker::points() const {
  std::lock_guard lock(mutex_);
  return points_;
}

std::string SweepWorker::error() const {
  std::lock_guard lock(mutex_);
  return error_;
}

void SweepWorker::run(std::shared_ptr<const VolumeSource> source, ClusterOptions base, FrameRequest request,
                      int frames) {
  // One worker thread: the nodes' times are then each one processor's work, which is what the
  // modelled time assumes, and the interactive renderer keeps the other cores. Unlike the
  // interactive renderer this thread keeps its normal priority: it measures wall-clock work, and
  // at nice 10 any other busy process on this shared machine took most of its core mid-frame (in
  // one comparison the slowest of a P's five frames was up to 5x its fastest at nice 10, under
  // 2x at normal priority).
  base.threads = 1;
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
      // Frame 0 warms up (first touch of image buffers, caches) and is not kept; the median of
      // the others is what one slow frame (another process on this shared machine) cannot move.
      std::vector<double> modelled, render, composite;
      for (int frame = 0; frame <= frames && !cancel_; ++frame) {
        const FrameResult result = cluster.renderFrame(request);
        if (frame > 0) {
          modelled.push_back(result.stats.modelledParallelSeconds());
          render.push_back(result.stats.renderMax());
          composite.push_back(result.stats.compositeMax());
        }
        std::lock_guard lock(mutex_);
        ++framesDone_;
      }
      if (cancel_) break;
      SweepPoint point;
      point.nodes = p;
      point.frames = int(modelled.size());
      point.modelledSeconds = median(modelled);
      point.renderMax = median(render);
      point.compositeMax = median(composite);
      point.modelledMin = *std::min_element(modelled.begin(), modelled.end());
      point.modelledMax = *std::max_element(modelled.begin(), modelled.end());
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
