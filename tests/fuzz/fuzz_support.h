// Shared by the libFuzzer targets (issue 9): a scratch folder per fuzzing process for the inputs
// (the readers take paths), and a small read of whatever a reader accepted.
#pragma once

#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <string>
#include <vector>

#include <glm/common.hpp>

#include "core/util/error.h"
#include "core/volume/reader.h"
#include "core/volume/volume_source.h"

namespace kdswap::fuzz {

//! A folder only this process writes to, removed at exit; inputs are rewritten there per run.
inline const std::string& scratchFolder() {
  struct Folder {
    std::string path;
    Folder() {
      char name[] = "/tmp/kdswap-fuzz-XXXXXX";
      if (!mkdtemp(name)) {
        std::perror("kdswap fuzz: mkdtemp");
        std::abort();
      }
      path = name;
    }
    ~Folder() {
      std::error_code ec;
      std::filesystem::remove_all(path, ec);
    }
  };
  static const Folder folder;
  return folder.path;
}

//! Writes `size` bytes to `fileName` inside the scratch folder (after removing what the last
//! input left there) and returns its path.
inline std::string writeScratch(const std::string& fileName, const std::uint8_t* data, std::size_t size) {
  std::error_code ec;
  for (const auto& entry : std::filesystem::directory_iterator(scratchFolder(), ec))
    std::filesystem::remove_all(entry.path(), ec);
  const std::string path = scratchFolder() + "/" + fileName;
  std::FILE* f = std::fopen(path.c_str(), "wb");
  if (!f || (size && std::fwrite(data, 1, size, f) != size) || std::fclose(f) != 0) {
    std::perror(("kdswap fuzz: writing " + path).c_str());
    std::abort();
  }
  return path;
}

//! Reads the first and the last corner boxes (at most 4 voxels a side) of an accepted volume;
//! aborts when the values break VolumeSource's contract (finite, within [minValue, maxValue]).
inline void readSmallBoxes(const VolumeSource& source) {
  const VolumeInfo& info = source.info();
  if (info.dims.x < 2 || info.dims.y < 2 || info.dims.z < 2) std::abort();  // validateVolumeInfo's promise
  const glm::ivec3 side = glm::min(info.dims, glm::ivec3(4));
  for (const VoxelBox& box : {VoxelBox{glm::ivec3(0), side}, VoxelBox{info.dims - side, info.dims}}) {
    std::vector<float> out(std::size_t(box.count()), -12345.0f);
    source.read(box, out.data());
    for (float v : out)
      if (!std::isfinite(v) || v < info.minValue || v > info.maxValue) {
        std::fprintf(stderr, "kdswap fuzz: %s read %g outside [%g, %g]\n", info.name.c_str(), v,
                     info.minValue, info.maxValue);
        std::abort();
      }
  }
}

//! Opens `path` as a volume; kdswap::Error is the only accepted failure.
inline void openAndRead(const std::string& path, const RawLayout& layout = {}) {
  try {
    const auto source = openVolumeFile(path, layout);
    readSmallBoxes(*source);
  } catch (const Error&) {
  }
}

}  // namespace kdswap::fuzz
