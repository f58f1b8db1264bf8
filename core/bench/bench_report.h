// Bench output: the paper-layout tables (rows: image size x {render, composite}; columns: node
// count; maximum over nodes), the per-cell figures, and the CSV and JSON files.
#pragma once

#include <string>
#include <vector>

#include <nlohmann/json_fwd.hpp>

#include "core/bench/bench_grid.h"
#include "core/bench/machine_info.h"

namespace kdswap {

//! What was measured, for the JSON header and the printed title.
struct BenchContext {
  std::string commandLine;
  std::string dataset;      //!< spec or file path
  std::string volumeType;   //!< "uint8", "float32", ...
  int dims[3] = {0, 0, 0};
  float stepVoxels = 0;
  bool shading = true;
  int frames = 0;
  float degreesPerFrame = 0;
  std::string voxels = "float";  //!< the bricks' storage: "float" or "compact"
  float viewDistance = 0;        //!< eye distance, bounding-sphere radii
  bool interleaved = false;      //!< frames measured in rounds over the cells (BenchGridOptions::interleave)
  MachineInfo machine;           //!< where it ran ("machine" in bench.json)
};

//! Paper layout, one table per strategy: times in ms, maximum over nodes.
std::string formatPaperLayout(const std::vector<BenchCell>& cells);
//! Per cell: wall ms, Msamples/s, MB sent, modelled ms and modelled speedup, one table per strategy.
std::string formatCellDetails(const std::vector<BenchCell>& cells);

std::string benchCsv(const BenchContext& context, const std::vector<BenchCell>& cells);
nlohmann::json benchJson(const BenchContext& context, const BenchResult& result);


}  // namespace kdswap
