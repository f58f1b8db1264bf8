// SweepWorker: the speedup study behind the paper's Figures 7-8, run in the background. For each
// node count it builds a cluster on the current data, renders one frame and keeps the modelled
// parallel time (max render + per phase max composite); speedup = T(1) / T(P). No ImGui in here.
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
  double modelledSeconds = 0, renderMax = 0, compositeMax = 0;
};

class SweepWorker {
 public:
  ~SweepWorker();  //!< cancels and joins

  //! Starts a sweep (cancelling one in progress). The source must allow concurrent reads.
  void start(std::shared_ptr<const VolumeSource> source, const ClusterOptions& base, const FrameRequest& request,
             std::vector<int> nodeCounts);
  void cancel();
  bool running() const { return running_.load(); }
  //! Fraction of the node counts done, in [0, 1].
  float progress() const;
  std::vector<SweepPoint> points() const;
  std::string error() const;

 private:
  void run(std::shared_ptr<const VolumeSource> source, ClusterOptions base, FrameRequest request);

  std::thread thread_;
  std::atomic<bool> running_{false};  //!< written by the sweep thread at its end, read by the UI
  std::atomic<bool> cancel_{false};   //!< written by the UI, read between steps by the sweep
  mutable std::mutex mutex_;          //!< guards counts_, points_, error_
  std::vector<int> counts_;
  std::vector<SweepPoint> points_;
  std::string error_;
};

}  // namespace kdswap
