// SequenceWriter: the files of an animation in one folder (numbered frames, optional phase grids)
// and its JSON-lines stats file, which is also the resume bookkeeping: a frame counts as done only
// when its image reads back whole and its stats line, recorded after the image was written, matches.
#pragma once

#include <functional>
#include <map>
#include <string>

#include <nlohmann/json.hpp>

namespace kdswap {

struct SequenceOptions {
  std::string dir;             //!< created if missing
  std::string extension = "png";
  std::string statsPath;       //!< empty: DIR/stats.jsonl
  int frames = 1;              //!< sets the width of the frame numbers (at least 4 digits)
  bool resume = false;         //!< keep the finished frames instead of starting afresh
  //! What decides frame i's pixels (view, transfer function, settings). On resume a recorded line
  //! is kept only if it holds every key of this object with an equal value.
  std::function<nlohmann::json(int frame)> identity;
};

class SequenceWriter {
 public:
  //! Creates the folder and opens the stats file: truncated for a fresh run; on resume, the lines
  //! of frames whose image still exists are kept (rewritten atomically) and the rest dropped.
  //! Frame and stage pictures this sequence will not write (an earlier run's, with more frames or
  //! another format) are removed, so the folder, and a video made of it, holds this run's only.
  //! Throws kdswap::Error naming the folder or file when it cannot be created or written.
  explicit SequenceWriter(const SequenceOptions& options);

  //! How many stale pictures the constructor removed.
  int staleRemoved() const { return staleRemoved_; }

  std::string framePath(int frame) const;   //!< DIR/frame_0000.png
  std::string phasesPath(int frame) const;  //!< DIR/phases_0000.png
  std::string framePattern() const;         //!< DIR/frame_%04d.png, for ffmpeg
  const std::string& statsPath() const { return statsPath_; }

  //! True on resume when the frame's image reads back whole and a matching line was kept for it.
  bool isDone(int frame) const;
  //! Appends `line` (which must hold "frame") to the stats file and flushes it.
  void record(const nlohmann::json& line);
  //! Every recorded line by frame index, including those kept from an earlier run.
  const std::map<int, nlohmann::json>& records() const { return records_; }

 private:
  std::string dir_, extension_, statsPath_;
  int digits_ = 4;
  int staleRemoved_ = 0;
  std::map<int, nlohmann::json> records_;
};

//! Medians over the recorded frames of the figures the summary prints.
struct SequenceSummary {
  int frames = 0;
  double medianWallSeconds = 0, medianModelledSeconds = 0, medianGatherSeconds = 0;
};
SequenceSummary summarizeSequence(const std::map<int, nlohmann::json>& records);

}  // namespace kdswap
