// StoredData: where and how a format's voxel array sits in a file, as its header says. Every
// reader ends by handing one to openStoredData, which streams uncompressed data brick by brick
// (RawFileSource) and decodes compressed data once (MemoryVolume).
#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "core/volume/readers/scalar_type.h"
#include "core/volume/volume_source.h"

namespace kdswap {

struct StoredData {
  std::string path;               //!< the file holding the voxels (may differ from the header's)
  std::uint64_t offset = 0;       //!< byte offset of the voxels (of the compressed stream if compressed)
  ScalarType type = ScalarType::Uint8;
  bool bigEndian = false;
  bool compressed = false;        //!< zlib or gzip stream starting at `offset`
  std::uint64_t skipDecoded = 0;  //!< decoded bytes to skip before the voxels (compressed only)
  bool allowTrailing = false;     //!< bytes after the voxels are allowed (else size must match)
  float scale = 1.0f;             //!< value = stored * scale + shift (NIfTI scl_slope / scl_inter)
  float shift = 0.0f;
};

//! Validates `info` (dims, spacing, memory) before any allocation, sets info.type from
//! `data.type`, opens the voxels and checks their range (checkValueRange: e.g. all NaN). Prints one
//! warning line on stderr when NaN/Inf were found and one when every voxel has the same value.
//! Throws kdswap::Error naming the file: truncated data, size mismatch, corrupt compression.
std::unique_ptr<VolumeSource> openStoredData(VolumeInfo info, const StoredData& data);

//! Wraps voxels a reader decoded itself (ASCII data) like a compressed file's: MemoryVolume
//! range and NaN/Inf replacement, plus the range check and warnings. `info` must already be validated.
std::unique_ptr<VolumeSource> openDecoded(VolumeInfo info, std::vector<float> voxels);

//! Offset at which the voxels are the last bytes of data.path (NRRD "byte skip: -1", MetaImage
//! "HeaderSize = -1"). Validates `info` first; throws kdswap::Error if the file is too short.
std::uint64_t trailingDataOffset(const VolumeInfo& info, const StoredData& data);

//! Throws kdswap::Error "WHERE: FIELD (DATAPATH): PROBLEM" unless `dataPath`, the data file a
//! header names, is a regular file: missing, a directory, or a device or FIFO (read forever or
//! blocking) are refused before it is opened.
void checkDataFile(const std::string& dataPath, const std::string& where, const std::string& field);

//! How messages name the data: the file itself, or "x.raw (data file of x.nhdr)".
std::string dataLabel(const StoredData& data, const VolumeInfo& info);

//! "256x256x113"
std::string dimsText(const glm::ivec3& dims);

//! Three sizes from a header field as dimensions; throws kdswap::Error naming `where` and the
//! field unless each is a whole number from 2 to 2^31 - 1 (zero, negative, overflowing sizes).
glm::ivec3 dimsFromSizes(const std::vector<std::int64_t>& sizes, const std::string& where, const std::string& field);

}  // namespace kdswap
