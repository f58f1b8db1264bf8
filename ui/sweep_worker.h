// SweepWorker: the speedup study behind the paper's Figures 7-8, run in the background. For each
// node count it builds a cluster on the current data, renders one warm-up frame (first touch of
// buffers and caches, not kept) and then K measured frames of the same view, and keeps the median
// modelled parallel time (max render + per phase max composite), like `kdswap bench`;
// speedup = T(1) / T(P). No ImGui in here.
#pragma once

#include <atomic>
#include <memory>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

#include "core/cluster/frame_request.h"
#include "core/cluster/virtual_cluster.h"

namespace kdswap {

struct SweepPoint {
  int nodes = 0;
  int frames = 0;  //!< measured frames the medians are over (the warm-up frame not counted)
  double modelledSeconds = 0, renderMax = 0, compositeMax = 0;  //!< medians over the frames
  double modelledMin = 0, modelledMax = 0;                      //!< spread of the modelled time
};

class SweepWorker {
 public:
  ~SweepWorker();  //!< cancels and joins

  static constexpr int kDefaultFrames = 5;

  //! Starts a sweep (cancelling one in progress): per node count one warm-up frame, then
  //! `frames` measured ones. The source must allow concurrent reads.
  void start(std::shared_ptr<const VolumeSource> source, const ClusterOptions& base, const FrameRequest& request,
             std::vector<int> nodeCounts, int frames = kDefaultFrames);
  void cancel();
  bool running() const { return running_.load(); }
  //! Fraction of the frames (warm-up included) rendered, in [0, 1].
  float progress() const;
  int framesPerPoint() const;
  std::vector<SweepPoint> points() const;
  std::string error() const;

 private:
  void run(std::shared_ptr<const VolumeSource> source, ClusterOptions base, FrameRequest request, int frames);

  std::thread thread_;
  std::atomic<bool> running_{false};  //!< written by the sweep thread at its end, read by the UI
  std::atomic<bool> cancel_{false};   //!< written by the UI, read between steps by the sweep
  mutable std::mutex mutex_;          //!< guards counts_, frames_, framesDone_, points_, error_
  std::vector<int> counts_;
  int frames_ = kDefaultFrames;
  int framesDone_ = 0;
  std::vector<SweepPoint> points_;
  std::string error_;
};

}  // namespace kdswap
