// A progress line for one long frame (a large image on thousands of nodes can take minutes, and
// a silent terminal looks hung): on a terminal, after the first second, "rendering: N of P nodes
// rendered, T s" is rewritten twice a second until the frame is done, then erased.
#pragma once

#include <condition_variable>
#include <mutex>
#include <thread>

#include "core/cluster/virtual_cluster.h"

namespace kdswap {

class FrameProgress {
 public:
  //! Shows nothing unless `show` and stderr is a terminal. Create it just before renderFrame.
  FrameProgress(const VirtualCluster& cluster, bool show);
  //! Stops the line (call it, or let it go out of scope, as soon as the frame returns).
  ~FrameProgress();
  FrameProgress(const FrameProgress&) = delete;
  FrameProgress& operator=(const FrameProgress&) = delete;

 private:
  std::mutex mutex_;
  std::condition_variable wake_;
  bool done_ = false;
  std::thread thread_;
};

}  // namespace kdswap
