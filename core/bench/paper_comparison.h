// `kdswap bench --paper`: runs each sourced cell of the paper's tables with our stand-in data set
// at the paper's size and prints our time beside the paper's, with the ratio (n/a when unknown).
#pragma once

#include <atomic>
#include <functional>
#include <string>

#include "core/bench/bench_grid.h"
#include "core/bench/paper_tables.h"
#include "core/volume/volume_source.h"

namespace kdswap {

//! One paper cell on `standIn` (the cell's stand-in data set, opened by the caller so that both
//! modes can share it): its preset, the default settings (step 0.5, shading), binary-swap,
//! `frames` measured frames; with `waves`, front-to-back waves (beyond the paper).
//! `interrupted` is set when `stop` cut it short.
BenchCell measurePaperCell(const PaperCell& cell, const VolumeSource& standIn, int frames,
                           const std::atomic<bool>* stop, bool& interrupted, bool waves = false);

//! Runs every cell of paperCells() (`frames` measured frames each; with `waves`, front-to-back
//! waves) and returns the printed table. `log` gets a line per cell as it starts; `stop` (may be
//! null) ends the run after a frame.
std::string runPaperComparison(int frames, const std::function<void(const std::string&)>& log,
                               const std::atomic<bool>* stop, bool waves = false);

}  // namespace kdswap
