// NRRD writer: any VolumeSource as one attached .nrrd file (raw encoding, little endian), so a
// built-in data set can be opened by other tools (VTK, ParaView, 3D Slicer, teem) or read back.
#pragma once

#include <functional>
#include <string>

#include "core/volume/volume_source.h"

namespace kdswap {

//! Sample type written: float32 keeps the values; uint8 and uint16 store each value as its level
//! round((v - min) / (max - min) * (2^bits - 1)), the header keeping min and max ("old min",
//! "old max"), which is exact for a source quantised to that many bits.
enum class NrrdSample { Float32, Uint8, Uint16 };

//! Parses "float32", "uint8" or "uint16"; throws kdswap::Error naming `option` otherwise.
NrrdSample parseNrrdSample(const std::string& text, const std::string& option);

//! What a written file holds, in the file's own units (values for float32, levels for uint8 and
//! uint16): the range its voxels span, and the source's value range (info().minValue .. maxValue,
//! which a built-in data set declares rather than measures). A reader of the file sees only the
//! first.
struct NrrdWritten {
  float voxelMin = 0, voxelMax = 0;
  float rangeMin = 0, rangeMax = 0;
};

//! Writes `source` to `path`, slice by slice; `progress(done, total)` after each slice. Throws
//! kdswap::Error naming the file when it cannot be created or written (a partial file is removed).
NrrdWritten writeNrrd(const std::string& path, const VolumeSource& source, NrrdSample sample,
                      const std::function<void(int, int)>& progress = {});

}  // namespace kdswap
