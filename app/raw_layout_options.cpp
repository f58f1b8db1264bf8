// The --raw-* options: adding them to a command, parsing them into a RawLayout, refusing them where
// no raw file is read.
#include "app/raw_layout_options.h"

#include <array>
#include <cmath>
#include <limits>
#include <utility>

#include "app/scene_options.h"
#include "core/util/error.h"

namespace kdswap {
namespace {

//! Each option's name and its value as given on the command line ("" when not given).
std::array<std::pair<const char*, std::string>, 5> givenValues(const RawLayoutOptions& o) {
  return {{{"--raw-dims", o.dims},
           {"--raw-type", o.type},
           {"--raw-endian", o.endian},
           {"--raw-spacing", o.spacing},
           {"--raw-skip", o.skip != 0 ? std::to_string(o.skip) : std::string()}}};
}

}  // namespace

void addRawLayoutOptions(CLI::App* cmd, RawLayoutOptions& o) {
  // Empty values are refused: `--raw-type ""` would otherwise read as not given.
  cmd->add_option("--raw-dims", o.dims, "Raw files: dimensions WxHxD")->check(nonEmpty());
  cmd->add_option("--raw-type", o.type, "Raw files: int8 uint8 int16 uint16 int32 uint32 float32 float64")
      ->check(nonEmpty());
  cmd->add_option("--raw-endian", o.endian, "Raw files: little (default) or big")->check(nonEmpty());
  cmd->add_option("--raw-spacing", o.spacing, "Raw files: voxel spacing SX,SY,SZ")->check(nonEmpty());
  cmd->add_option("--raw-skip", o.skip, "Raw files: header bytes to skip")
      ->check(wholeNumber(std::numeric_limits<std::int64_t>::min(), std::numeric_limits<std::int64_t>::max()));
}

RawLayout parseRawLayout(const RawLayoutOptions& o) {
  RawLayout layout;
  if (!o.dims.empty()) {
    const auto d = parseNumbers(o.dims, 'x', "--raw-dims");
    if (d.size() != 3) throw Error("--raw-dims \"" + o.dims + "\": expected WxHxD");
    for (double v : d)
      if (v < 2 || v > 1e6 || v != std::floor(v))
        throw Error("--raw-dims \"" + o.dims + "\": each size must be a whole number from 2 to 1000000");
    layout.dims = glm::ivec3(int(d[0]), int(d[1]), int(d[2]));
  }
  if (!o.type.empty()) layout.type = o.type;
  if (!o.endian.empty()) {  // only when given: a header file refuses any raw layout
    if (o.endian != "little" && o.endian != "big") throw Error("--raw-endian \"" + o.endian + "\": expected little or big");
    layout.bigEndian = o.endian == "big";
  }
  if (!o.spacing.empty()) {
    const auto s = parseNumbers(o.spacing, ',', "--raw-spacing");
    if (s.size() != 3) throw Error("--raw-spacing \"" + o.spacing + "\": expected SX,SY,SZ");
    layout.spacing = glm::vec3(float(s[0]), float(s[1]), float(s[2]));
  }
  if (o.skip < 0) throw Error("--raw-skip " + std::to_string(o.skip) + ": expected a number of bytes >= 0");
  layout.headerBytes = std::uint64_t(o.skip);
  layout.rawOptions = true;
  return layout;
}

void checkNoRawLayout(const RawLayoutOptions& o, const std::string& other) {
  // Without a raw file to describe they would be silently ignored.
  for (const auto& [option, value] : givenValues(o))
    if (!value.empty()) throw Error(std::string(option) + " describes a raw --volume file; it does not apply to " + other);
}

std::string rawLayoutArguments(const RawLayoutOptions& o) {
  std::string arguments;
  for (const auto& [option, value] : givenValues(o))
    if (!value.empty()) arguments += std::string(" ") + option + " " + value;
  return arguments;
}

}  // namespace kdswap
