// Kernel micro benchmarks (`kdswap bench --micro`): ray-casting samples per second on one core,
// `over` compositing throughput quoted against a plain copy of the same buffers, and
// binary-swap compositing alone (synthetic full-frame partial images over an InprocNetwork).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "core/composite/strategy.h"

namespace kdswap {

struct RayCastFigure {
  std::string dataType;  //!< "uint8", "uint16", "float32": the source data, before the brick
  bool shaded = false;
  std::string voxels = "float";  //!< the brick's storage: "float" or "compact" (voxel_storage.h)
  std::string march;     //!< marchName: which sample loop (ray_march.h) was measured
  double samplesPerSecond = 0;  //!< one thread (tbb::task_arena(1)), median of the repeats
  double samples = 0;           //!< per render
};

struct CompositeFigure {
  int width = 0, height = 0;
  double overSeconds = 0;   //!< compositeInto of two full images, one thread, median
  double copySeconds = 0;   //!< memcpy of one image's bytes, one thread, median
  double overPixelsPerSecond() const { return overSeconds > 0 ? width * double(height) / overSeconds : 0; }
  double copyPixelsPerSecond() const { return copySeconds > 0 ? width * double(height) / copySeconds : 0; }
};

struct BinarySwapFigure {
  std::string strategy = "binary-swap";
  int nodes = 0, width = 0, height = 0;
  double compositeMaxSeconds = 0;  //!< max over nodes of compose time minus time suspended, median
  double wallSeconds = 0;          //!< whole exchange on this machine's cores, median
  double copySeconds = 0;          //!< memcpy of one full image, median
  std::uint64_t bytesSent = 0;     //!< by all nodes in one exchange
  //! One memcpy of as many bytes as the exchange sends (one buffer), timed after each run, median.
  double copySentSeconds = 0;
};

struct MicroOptions {
  int volumeSize = 128;  //!< the procedural volume's side, voxels
  int imageSize = 256;   //!< ray-casting image side
  int repeats = 5;
  //! Compositing runs take milliseconds and this machine's memory bandwidth varies from run to
  //! run (shared host), so they are repeated more for a stable median.
  int compositingRepeats = 21;
};

std::vector<RayCastFigure> measureRayCasting(const MicroOptions& options);
CompositeFigure measureOver(int width, int height, int repeats);
BinarySwapFigure measureBinarySwap(int nodes, int width, int height, int repeats);
//! Any registered strategy alone, on the same synthetic full-frame partial images.
BinarySwapFigure measureCompositing(const std::string& strategy, int nodes, int width, int height, int repeats,
                                    const CompositeOptions& options = {});

//! Issue 8's scale: Sandia's miniGraphics miniapp on this machine (MPI ranks sharing the 2 cores,
//! 1024x1024, float colour, run-length encoding), and kdswap's target of half its time.
struct CompositingReference {
  std::string strategy;
  int nodes;
  double miniGraphicsSeconds;
};
const std::vector<CompositingReference>& compositingReferences();
//! The strategies table: wall time of each against half of miniGraphics', MET or MISSED.
std::string formatCompositingTable(const std::vector<BinarySwapFigure>& figures);

//! The printed report of all three, with the honest caveats.
std::string formatMicro(const std::vector<RayCastFigure>& rays, const CompositeFigure& over,
                        const BinarySwapFigure& swap, const MicroOptions& options);

}  // namespace kdswap
