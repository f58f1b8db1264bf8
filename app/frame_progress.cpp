// The progress line's thread: it only reads the cluster's counter, so it never slows the nodes.
#include "app/frame_progress.h"

#include <unistd.h>

#include <chrono>
#include <cstdio>

namespace kdswap {

FrameProgress::FrameProgress(const VirtualCluster& cluster, bool show) {
  if (!show || !::isatty(2)) return;
  thread_ = std::thread([this, &cluster] {
    const auto start = std::chrono::steady_clock::now();
    std::unique_lock<std::mutex> lock(mutex_);
    bool printed = false;
    for (auto next = start + std::chrono::seconds(1); !wake_.wait_until(lock, next, [this] { return done_; });
         next += std::chrono::milliseconds(500)) {
      const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
      const int rendered = cluster.nodesRendered(), nodes = cluster.options().nodes;
      std::fprintf(stderr, "\rrendering: %d of %d nodes rendered%s, %.0f s   ", rendered, nodes,
                   rendered == nodes ? ", compositing" : "", seconds);
      printed = true;
    }
    if (printed) std::fprintf(stderr, "\r%60s\r", "");
  });
}

FrameProgress::~FrameProgress() {
  if (!thread_.joinable()) return;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    done_ = true;
  }
  wake_.notify_one();
  thread_.join();
}

}  // namespace kdswap
