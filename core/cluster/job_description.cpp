// JobDescription: fields as text, compared field by field so a mismatch names what differs.
#include "core/cluster/job_description.h"

#include <algorithm>
#include <cstdio>

#include <nlohmann/json.hpp>
#include <zlib.h>

#include "core/cluster/frame_request.h"
#include "core/camera/view.h"
#include "core/cluster/virtual_cluster.h"
#include "core/partition/kd_tree.h"
#include "core/util/error.h"
#include "core/volume/volume_source.h"

namespace kdswap {
namespace {

//! Shortest text that reads back as the same float (9 significant digits always do).
std::string exact(float v) {
  char text[32];
  std::snprintf(text, sizeof text, "%.9g", double(v));
  return text;
}

std::string exact(const glm::vec3& v) { return exact(v.x) + " " + exact(v.y) + " " + exact(v.z); }

std::string sizeText(const glm::ivec3& d) {
  char text[48];
  std::snprintf(text, sizeof text, "%dx%dx%d", d.x, d.y, d.z);
  return text;
}

//! A slice of at most this many voxels is read whole; a larger one, its centre square of that area.
constexpr std::int64_t kMaxSampledVoxels = std::int64_t(1) << 22;
//! Slices sampled besides the middle one: one in each of this many equal bands of z.
constexpr int kSampledBands = 8;

//! The voxels whose checksum stands for the file's content: the middle z slice (for a stack of
//! images, the middle image) and one slice in each of kSampledBands bands of z, each whole or, when
//! very large, its central part. Not the whole file: every rank reads this before any brick.
struct SampledSlices {
  std::vector<int> z;  //!< ascending
  int x0 = 0, x1 = 0, y0 = 0, y1 = 0;  //!< [x0, x1) x [y0, y1) of each
};

SampledSlices sampledSlices(const glm::ivec3& dims) {
  SampledSlices s;
  s.z.push_back(dims.z / 2);
  const int bands = std::min(dims.z, kSampledBands);
  for (int k = 0; k < bands; ++k) s.z.push_back(int((2 * std::int64_t(k) + 1) * dims.z / (2 * bands)));
  std::sort(s.z.begin(), s.z.end());
  s.z.erase(std::unique(s.z.begin(), s.z.end()), s.z.end());
  s.x1 = dims.x, s.y1 = dims.y;
  const int side = 1 << 11;  // side * side == kMaxSampledVoxels
  if (std::int64_t(dims.x) * dims.y > kMaxSampledVoxels) {
    if (dims.x > side) s.x0 = (dims.x - side) / 2, s.x1 = s.x0 + side;
    if (dims.y > side) s.y0 = (dims.y - side) / 2, s.y1 = s.y0 + side;
  }
  return s;
}

std::string slicesText(const SampledSlices& s, const glm::ivec3& dims) {
  std::string text = "CRC-32 of the voxels of z slices";
  for (std::size_t i = 0; i < s.z.size(); ++i) text += (i ? ", " : " ") + std::to_string(s.z[i]);
  if (s.x0 > 0 || s.x1 < dims.x || s.y0 > 0 || s.y1 < dims.y)
    text += ", x " + std::to_string(s.x0) + ".." + std::to_string(s.x1 - 1) + ", y " + std::to_string(s.y0) + ".." +
            std::to_string(s.y1 - 1);
  return text;
}

uLong crc32Update(uLong crc, const unsigned char* bytes, std::size_t size) {
  while (size > 0) {  // crc32 takes a uInt length
    const uInt chunk = uInt(std::min<std::size_t>(size, std::size_t(1) << 30));
    crc = crc32(crc, bytes, chunk);
    bytes += chunk, size -= chunk;
  }
  return crc;
}

std::string crc32Text(uLong crc) {
  char text[16];
  std::snprintf(text, sizeof text, "%08lx", static_cast<unsigned long>(crc));
  return text;
}

std::string crc32Text(const unsigned char* bytes, std::size_t size) {
  return crc32Text(crc32Update(crc32(0L, Z_NULL, 0), bytes, size));
}

std::string contentChecksum(const VolumeSource& source, const SampledSlices& s) {
  uLong crc = crc32(0L, Z_NULL, 0);
  std::vector<float> voxels(std::size_t(s.x1 - s.x0) * std::size_t(s.y1 - s.y0));
  for (int z : s.z) {
    source.read(VoxelBox{{s.x0, s.y0, z}, {s.x1, s.y1, z + 1}}, voxels.data());
    crc = crc32Update(crc, reinterpret_cast<const unsigned char*>(voxels.data()), voxels.size() * sizeof(float));
  }
  return crc32Text(crc);
}

std::string viewText(const View& v) {
  return "azimuth " + exact(v.azimuthDeg) + ", elevation " + exact(v.elevationDeg) + ", distance " +
         exact(v.distance) + ", fov " + exact(v.fovDeg) + ", " + toString(v.projection) + ", up " + toString(v.up) +
         ", pan " + exact(v.pan.x) + " " + exact(v.pan.y);
}

std::string settingsText(const RenderSettings& s) {
  std::string text = "step " + exact(s.stepVoxels) + ", ert " + exact(s.earlyTermination) + ", shading " +
                     (s.shading ? "on" : "off") + ", jitter " + (s.jitter ? "on" : "off") + ", skip " +
                     (s.skipEmptySpace ? "on" : "off") + ", phong " + exact(s.ambient) + " " + exact(s.diffuse) + " " +
                     exact(s.specular) + " " + exact(s.shininess);
  if (s.valueRange) text += ", range " + exact(s.valueRange->x) + " " + exact(s.valueRange->y);
  if (s.phaseShift != 0.0f) text += ", phase shift " + exact(s.phaseShift);
  return text;
}

//! The curve's size and a CRC-32 of its points: short enough for a one-line error. Not its name:
//! the same curve under another name renders the same.
std::string transferText(const TransferFunction& tf) {
  nlohmann::json j = tf.toJson();
  j.erase("name");
  const std::string points = j.dump();
  return std::to_string(tf.colors().size()) + " colour stops, " + std::to_string(tf.opacity().size()) +
         " opacity points, CRC-32 " + crc32Text(reinterpret_cast<const unsigned char*>(points.data()), points.size());
}

std::string compositingText(const ClusterOptions& o) {
  std::string text = o.strategy + (o.composite.sparse ? ", sparse" : "");
  if (!o.composite.radices.empty()) {
    text += ", radices";
    for (int r : o.composite.radices) text.append(" ").append(std::to_string(r));
  }
  return text;
}

std::string balanceText(const ClusterOptions& o) {
  if (o.balance != "cost") return o.balance;
  return "cost, transfer function " + transferText(o.balanceTransfer) + ", range " + exact(o.balanceRange.x) + " " +
         exact(o.balanceRange.y);
}

std::string speedsText(const std::vector<double>& speeds) {
  if (speeds.empty()) return "all 1";
  std::string text;
  for (double v : speeds) {
    char number[32];
    std::snprintf(number, sizeof number, "%.17g", v);  // doubles: 17 digits read back exactly
    text.append(text.empty() ? "" : " ").append(number);
  }
  return text;
}

}  // namespace

std::string JobDescription::serialize() const {
  nlohmann::json j = nlohmann::json::array();
  for (const auto& [what, value] : fields) j.push_back({what, value});
  return j.dump();
}

JobDescription JobDescription::parse(const std::string& text, const std::string& from) {
  try {
    JobDescription d;
    for (const auto& field : nlohmann::json::parse(text))
      d.fields.emplace_back(field.at(0).get<std::string>(), field.at(1).get<std::string>());
    return d;
  } catch (const nlohmann::json::exception& e) {
    throw Error(from + ": malformed job description: " + e.what());
  }
}

std::string JobDescription::firstDifference(const JobDescription& reference, const std::string& name,
                                            const std::string& referenceName) const {
  const std::size_t n = std::max(fields.size(), reference.fields.size());
  for (std::size_t i = 0; i < n; ++i) {
    if (i >= fields.size() || i >= reference.fields.size() || fields[i].first != reference.fields[i].first)
      return "the job descriptions have different fields (different kdswap builds?)";
    if (fields[i].second != reference.fields[i].second)
      return fields[i].first + ": " + fields[i].second + " " + name + ", " + reference.fields[i].second + " " +
             referenceName;
  }
  return "";
}

JobDescription describeJob(const VolumeSource& source, const FrameRequest& request, const ClusterOptions& options,
                           int nodesPerRank) {
  const VolumeInfo& info = source.info();
  const SampledSlices sampled = sampledSlices(info.dims);
  JobDescription d;
  d.fields = {
      {"volume size", sizeText(info.dims)},
      {"volume spacing", exact(info.spacing)},
      {"volume type", info.type},
      {"volume value range", exact(info.minValue) + " " + exact(info.maxValue) + ", " +
                                 std::to_string(info.nonFinite) + " non-finite"},
      {"volume content (" + slicesText(sampled, info.dims) + ")", contentChecksum(source, sampled)},
      {"image size", std::to_string(request.width) + "x" + std::to_string(request.height)},
      {"view", viewText(request.view)},
      {"transfer function", transferText(request.transfer)},
      {"render settings", settingsText(request.settings)},
      {"compositing", compositingText(options)},
      {"partition", toString(options.partition) + ", slab axis " + std::to_string(options.slabAxis)},
      {"load balance", balanceText(options)},
      {"node speeds", speedsText(options.speeds)},
      {"voxel storage", voxelChoiceName(options.voxels)},
      {"bricks per node", std::to_string(options.bricksPerNode)},
      {"nodes per rank", std::to_string(nodesPerRank)},
  };
  return d;
}

}  // namespace kdswap
