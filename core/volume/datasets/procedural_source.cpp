// Procedural volume source.
#include "core/volume/datasets/procedural_source.h"

namespace kdswap {

ProceduralSource::ProceduralSource(VolumeInfo info, Generator generate)
    : info_(std::move(info)), generate_(std::move(generate)) {
  validateVolumeInfo(info_, info_.name);
}

}  // namespace kdswap
