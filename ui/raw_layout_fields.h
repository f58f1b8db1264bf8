// RawLayoutFields: the data panel's fields describing a headerless .raw file (dimensions, voxel
// type, byte order, spacing, header bytes), what fills them in and the RawLayout they give.
#pragma once

#include <cstdint>
#include <map>
#include <optional>
#include <string>

#include "core/volume/reader.h"
#include "core/volume/readers/scalar_type.h"

namespace kdswap {

//! The fields as typed. Nothing is checked here: opening the file refuses a bad layout with the
//! reader's own message, as for a bad --raw-* option.
struct RawLayoutFields {
  int dims[3] = {0, 0, 0};  //!< 0: not known yet
  ScalarType type = ScalarType::Uint8;
  bool bigEndian = false;
  float spacing[3] = {1.0f, 1.0f, 1.0f};
  std::uint64_t headerBytes = 0;
  bool operator==(const RawLayoutFields&) const = default;
};

//! The fields for `path`: the layout given for it before (the start-up --raw-* options, an earlier
//! Open; `given` maps paths to them), what the layout leaves out taken from the file name, then
//! the defaults; else the layout its name NAME_WxHxD_TYPE.raw gives. Nullopt when neither says
//! anything: the caller keeps what is typed (the user may be correcting the path).
std::optional<RawLayoutFields> knownRawLayout(const std::string& path, const std::map<std::string, RawLayout>& given);

//! The layout the fields describe, every part given (so it overrides the file name).
RawLayout toRawLayout(const RawLayoutFields& fields);

}  // namespace kdswap
