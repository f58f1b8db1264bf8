// RenderWorker: the GUI's background renderer. One std::thread owns the VolumeSource and the
// VirtualCluster (which runs its nodes on oneTBB); the UI thread submits requests and polls for
// finished snapshots, so rendering never blocks a UI frame. No ImGui in here.
#pragma once

#include <condition_variable>
#include <cstdint>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include <oneapi/tbb/task_scheduler_observer.h>

#include "core/cluster/frame_request.h"
#include "core/cluster/virtual_cluster.h"
#include "core/volume/reader.h"
#include "ui/frame_pixels.h"
#include "ui/histogram.h"

namespace kdswap {

//! What a cluster is built from; changing any of it rebuilds the cluster.
struct SceneSpec {
  std::string data = kDefaultDatasetSpec;  //!< built-in data set spec ("phantom:128") or a file path
  //! The layout given for the headerless .raw file `rawPath` (--raw-* on the command line, or the
  //! data panel's fields): used whenever `data` names that file, never for other data.
  std::string rawPath;
  RawLayout raw;
  ClusterOptions cluster;
  static constexpr const char* kDefaultDatasetSpec = "phantom:128";
  bool sameScene(const SceneSpec& o) const;
};

//! --balance cost for `cluster`, its work estimated from `transfer` over the data's range (the
//! transfer function of the moment: editing it later does not move the planes).
void useCostBalance(ClusterOptions& cluster, const TransferFunction& transfer);

//! A scene the worker built successfully (immutable once published).
struct SceneSnapshot {
  SceneSpec spec;
  VolumeInfo info;
  KdTree tree;
  Histogram histogram;                         //!< see computeHistogram
  std::shared_ptr<const VolumeSource> source;  //!< thread-safe reads, shared with the sweep
  double distributeSeconds = 0;
  double buildSeconds = 0;
};

//! One finished frame, with everything the panels draw from.
struct FrameSnapshot {
  std::uint64_t id = 0;  //!< the submit() number it answers
  bool preview = false;  //!< a quick frame rendered while the view moves
  //! Refinement: `image` is the mean of the first `passes` of `passesRequested` passes on shifted
  //! sampling lattices (RenderSettings::phaseShift); stats, stages and phases are the first's.
  int passes = 1, passesRequested = 1;
  FrameRequest request;
  std::shared_ptr<const SceneSnapshot> scene;
  FrameStats stats;
  Pixels image;                                //!< the final frame, full resolution
  std::shared_ptr<const PhaseRecord> phases;   //!< null for previews
  StageAtlas stages;                           //!< empty for previews
  double seconds = 0;                          //!< submit-to-finish
};

class RenderWorker {
 public:
  RenderWorker();
  ~RenderWorker();  //!< waits for the frame in flight, then joins
  RenderWorker(const RenderWorker&) = delete;
  RenderWorker& operator=(const RenderWorker&) = delete;

  //! Queues a frame; a request still pending is dropped (only the newest matters). Returns its id.
  //! A full frame with `passes` > 1 is refined: once it is published, the worker renders passes
  //! 2..`passes` on shifted lattices and publishes their running mean after each (same id), until
  //! the passes are done or a newer request arrives. busy() holds until then.
  std::uint64_t submit(const SceneSpec& scene, const FrameRequest& request, bool preview, int passes = 1);
  //! The newest scene built since the last call, or null.
  std::shared_ptr<const SceneSnapshot> takeScene();
  //! The newest finished frame since the last call, or null.
  std::shared_ptr<const FrameSnapshot> takeFrame();
  //! Errors since the last call (one line each): a scene that would not build, a failed frame.
  std::vector<std::string> takeErrors();
  //! True while a frame or a scene build is pending or in flight.
  bool busy() const;
  //! True while a scene is being built (data loading, distribution).
  bool building() const;
  //! Id of the newest request that ended without a frame (its scene would not build, or the frame
  //! failed; takeErrors says why), 0 if none. Set after its error is queued, so a caller that reads
  //! this before takeErrors gets the error too.
  std::uint64_t lastFailed() const;

 private:
  struct Job {
    std::uint64_t id;
    SceneSpec scene;
    FrameRequest request;
    bool preview;
    int passes;
    double submitted;
  };
  void run();
  void process(const Job& job);
  bool ensureScene(const SceneSpec& spec);

  mutable std::mutex mutex_;          //!< guards everything below up to worker_
  std::condition_variable wake_;
  std::optional<Job> pending_;
  bool inFlight_ = false, buildingScene_ = false, stop_ = false;
  std::uint64_t nextId_ = 1;
  std::uint64_t lastFailed_ = 0;
  std::shared_ptr<const SceneSnapshot> newScene_;
  std::shared_ptr<const FrameSnapshot> newFrame_;
  std::vector<std::string> errors_;

  // Touched only by the worker thread.
  std::shared_ptr<const SceneSnapshot> scene_;
  std::unique_ptr<VirtualCluster> cluster_;
  std::optional<SceneSpec> failedSpec_;  //!< not retried until the spec changes
  std::thread worker_;
};

//! Lowers the calling thread's scheduling priority to nice kBackgroundNice (Linux), so that when
//! the UI thread and the rasteriser want a core the background work yields it.
void lowerThreadPriority();
inline constexpr int kBackgroundNice = 10;

//! Lowers the calling thread's priority and, while it lives, that of every oneTBB worker joining
//! the thread's arena (the scene build's parallel loops). Workers keep the lowered priority: in
//! this process oneTBB runs background work only. Create it on the background thread.
class BackgroundThreads : public tbb::task_scheduler_observer {
 public:
  BackgroundThreads();
  ~BackgroundThreads() override;
  void on_scheduler_entry(bool isWorker) override;
};

//! Opens `data` as a built-in data set ("name[:size]") when the name is one, else as a file.
std::unique_ptr<VolumeSource> openVolumeSpec(const std::string& data, const RawLayout& layout = {});

}  // namespace kdswap
