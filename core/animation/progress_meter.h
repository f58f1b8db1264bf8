// ProgressMeter: "frames done / total, frames per second, time left" for long batch runs; one
// line rewritten with \r on a terminal, a plain line every ~10% otherwise (logs stay short).
#pragma once

#include <chrono>
#include <cstdio>

namespace kdswap {

class ProgressMeter {
 public:
  //! `alreadyDone` frames (kept from an earlier run) count as done but not in the frame rate.
  //! `unit` and `units` name what is counted ("pass", "passes" for kdswap render --passes).
  ProgressMeter(std::FILE* out, bool terminal, int total, int alreadyDone, const char* unit = "frame",
                const char* units = "frames");
  //! One more frame finished.
  void frameDone();
  //! Ends the updating line on a terminal so later output starts on a fresh line.
  void finish();

 private:
  void print();
  std::FILE* out_;
  const char* unit_;
  const char* units_;
  bool terminal_;
  int total_, done_, renderedThisRun_ = 0;
  int lastDecile_ = -1;
  std::chrono::steady_clock::time_point start_ = std::chrono::steady_clock::now();
};

}  // namespace kdswap
