// The speed targets of issue 6 (`kdswap bench --targets`): a short run that measures exactly
// those figures and says MET or MISSED for each, with the command that measures it alone.
#pragma once

#include <atomic>
#include <functional>
#include <string>
#include <vector>

namespace kdswap {

struct SpeedTarget {
  std::string name;     //!< "phantom 256^3 uint8, 512x512, P=64, step 1, shading: wall"
  std::string command;  //!< reproduces the measurement
  double measured = 0, limit = 0;
  std::string unit;     //!< "ms", "x", "MB", "fps"
  bool atLeast = false; //!< true: met when measured >= limit; false: when measured <= limit
  bool ran = false;     //!< false when skipped (missing file, interrupted)
  std::string note;
  //! Judged by the first of several runs only (medianOfRuns): a process-wide peak, which later
  //! runs inherit from the targets before them.
  bool firstRunOnly = false;
  bool met() const { return ran && (atLeast ? measured >= limit : measured <= limit); }
};

struct TargetOptions {
  int frames = 5;
  std::string headPath = "../shared/data/headsq.nhdr";  //!< the CT head of the third target
  //! VTK's medians on this machine for turbulence, phantom and CT head, in ms, as
  //! scripts/vtk_baseline.py prints them (same voxels and camera). Empty: only the fixed
  //! figures, which were measured on another machine. Given: each scene also gets a target of half
  //! of VTK's time here.
  std::vector<double> vtkMs;
};

//! Runs every target in an order that keeps the peak-RSS figure honest (P=64 on 256^3 first).
//! `log` receives a line as each target starts; `stop` (may be null) ends the run early, leaving
//! the remaining targets not run. Throws Error only for failures other than a missing head file.
std::vector<SpeedTarget> runSpeedTargets(const TargetOptions& options, const std::function<void(const std::string&)>& log,
                                         const std::atomic<bool>* stop);

std::string formatSpeedTargets(const std::vector<SpeedTarget>& targets);

//! One list from several runs of runSpeedTargets (the same targets in the same order; a run cut
//! short has fewer): each target's measurement is the median over the runs that measured it, and
//! its note gives every run's figure. On a shared machine whose speed moves between minutes, one
//! run's verdict can flip; the median of runs spread over time is the figure to judge. Peak RSS is
//! taken from the first run alone: only a fresh process's peak is the P=64 frame's own.
std::vector<SpeedTarget> medianOfRuns(const std::vector<std::vector<SpeedTarget>>& runs);

//! The note of a "P=64 wall <= 1.15 x P=1 wall" target: both walls and both cells' samples a
//! frame, and what the miss comes from as far as they tell: more samples at P = 64 are rays
//! sampled behind matter that ends the single-node ray (independent nodes cannot see it); the
//! same samples leave the per-brick and per-phase costs. `p1Label` follows the P = 1 wall.
std::string wallRatioNote(double p1Seconds, double pSeconds, double p1Samples, double pSamples,
                          const std::string& p1Label = "");

//! "Faster than VTK" judged against VTK measured on this machine: `fixed` (the target for
//! `scene`, already measured) with the limit half of `vtkMs`.
SpeedTarget halfOfVtkHere(const SpeedTarget& fixed, const std::string& scene, double vtkMs);

}  // namespace kdswap
