// Camera paths for `kdswap animate`: orbit and linear key-frame interpolation, and key-file parsing.
#include "core/animation/camera_path.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>

#include <nlohmann/json.hpp>

#include "core/util/error.h"

namespace kdswap {
namespace {

void checkFrameCount(int frames) {
  if (frames < 1 || frames > kMaxAnimationFrames)
    throw Error("frames " + std::to_string(frames) + ": must be from 1 to " + std::to_string(kMaxAnimationFrames));
}

bool validElevation(float e) { return std::isfinite(e) && e > -90.0f && e < 90.0f; }

//! Fills every key's unset angle or distance from the key before it (the first from `base`).
struct ResolvedKey {
  float azimuth, elevation, distance;
};

std::vector<ResolvedKey> resolveKeys(const View& base, const std::vector<CameraKey>& keys) {
  std::vector<ResolvedKey> out;
  ResolvedKey last{base.azimuthDeg, base.elevationDeg, base.distance};
  for (const CameraKey& k : keys) {
    last = {k.azimuthDeg.value_or(last.azimuth), k.elevationDeg.value_or(last.elevation),
            k.distance.value_or(last.distance)};
    out.push_back(last);
  }
  return out;
}

float readNumber(const nlohmann::json& key, const char* name, const std::string& where, std::size_t index) {
  const nlohmann::json& v = key.at(name);
  // Checked as float too: 1e300 is a finite double but an infinite float angle.
  if (!v.is_number() || !std::isfinite(v.get<double>()) || !std::isfinite(v.get<float>()))
    throw Error(where + ": key " + std::to_string(index) + ": \"" + name + "\" must be a finite number");
  return v.get<float>();
}

//! e.what() without nlohmann's "[json.exception.out_of_range.406] " prefix.
std::string jsonReason(const nlohmann::json::exception& e) {
  const std::string what = e.what();
  const std::size_t end = what.find("] ");
  return what.compare(0, 1, "[") == 0 && end != std::string::npos ? what.substr(end + 2) : what;
}

}  // namespace

CameraPath CameraPath::orbit(const View& start, float degrees, int frames, std::optional<glm::vec2> elevationSweep) {
  checkFrameCount(frames);
  // Beyond a hundred turns a float azimuth loses the step between frames (1e9 degrees over 36
  // frames would draw views no one asked for).
  if (!(std::fabs(degrees) <= kMaxOrbitDegrees))
    throw Error("orbit: degrees must be from -36000 to 36000 (100 turns)");
  if (elevationSweep && (!validElevation(elevationSweep->x) || !validElevation(elevationSweep->y)))
    throw Error("elevation sweep: both angles must be in (-90, 90) degrees");
  CameraPath path;
  path.frames_.reserve(std::size_t(frames));
  for (int i = 0; i < frames; ++i) {
    PathFrame f{start, ""};
    f.view.azimuthDeg = start.azimuthDeg + degrees * float(i) / float(frames);
    if (elevationSweep) {
      const float t = frames > 1 ? float(i) / float(frames - 1) : 0.0f;
      f.view.elevationDeg = elevationSweep->x + (elevationSweep->y - elevationSweep->x) * t;
    }
    path.frames_.push_back(f);
  }
  return path;
}

CameraPath CameraPath::fromKeys(const View& base, const std::vector<CameraKey>& keys, int frames) {
  checkFrameCount(frames);
  if (keys.empty()) throw Error("camera keys: the list is empty; give at least one key");
  const std::vector<ResolvedKey> resolved = resolveKeys(base, keys);
  for (std::size_t k = 0; k < resolved.size(); ++k) {
    if (!validElevation(resolved[k].elevation))
      throw Error("camera keys: key " + std::to_string(k) + ": elevation must be in (-90, 90) degrees");
    if (!(resolved[k].distance > 0.0f && resolved[k].distance < 1000.0f))
      throw Error("camera keys: key " + std::to_string(k) + ": distance must be between 0 and 1000 radii");
  }
  const int segments = int(keys.size()) - 1;
  CameraPath path;
  path.frames_.reserve(std::size_t(frames));
  std::string tf;
  std::size_t nextTfKey = 0;  // keys before this one have had their "tf" applied
  for (int i = 0; i < frames; ++i) {
    // Key k sits at frame k * (frames - 1) / segments; t is frame i's position in key units.
    const double t = segments > 0 && frames > 1 ? double(i) * segments / double(frames - 1) : 0.0;
    const int k = std::min(int(std::floor(t)), std::max(segments - 1, 0));
    const float u = segments > 0 ? float(t - k) : 0.0f;
    const ResolvedKey& a = resolved[std::size_t(k)];
    const ResolvedKey& b = resolved[std::size_t(std::min(k + 1, segments))];
    PathFrame f{base, ""};
    f.view.azimuthDeg = a.azimuth + (b.azimuth - a.azimuth) * u;
    f.view.elevationDeg = a.elevation + (b.elevation - a.elevation) * u;
    f.view.distance = a.distance + (b.distance - a.distance) * u;
    // A transfer function switches (it is not blended) when its key's frame is reached.
    for (; nextTfKey < keys.size() && double(nextTfKey) <= t + 1e-9; ++nextTfKey)
      if (keys[nextTfKey].tf) tf = *keys[nextTfKey].tf;
    f.tf = tf;
    path.frames_.push_back(f);
  }
  return path;
}

std::vector<std::string> CameraPath::transferFunctions() const {
  std::vector<std::string> names;
  for (const PathFrame& f : frames_)
    if (!f.tf.empty() && std::find(names.begin(), names.end(), f.tf) == names.end()) names.push_back(f.tf);
  return names;
}

std::vector<CameraKey> parseCameraKeys(const nlohmann::json& j, const std::string& where) {
  const nlohmann::json* list = &j;
  if (j.is_object()) {
    if (!j.contains("keys")) throw Error(where + ": expected a list of keys or an object with a \"keys\" list");
    list = &j.at("keys");
  }
  if (!list->is_array()) throw Error(where + ": expected a list of keys or an object with a \"keys\" list");
  if (list->empty()) throw Error(where + ": the key list is empty; give at least one key");
  std::vector<CameraKey> keys;
  for (std::size_t i = 0; i < list->size(); ++i) {
    const nlohmann::json& item = (*list)[i];
    const std::string at = where + ": key " + std::to_string(i);
    if (!item.is_object()) throw Error(at + ": expected an object like {\"azimuth\": 30, \"elevation\": 15}");
    for (const auto& [name, value] : item.items())
      if (name != "azimuth" && name != "elevation" && name != "distance" && name != "tf")
        throw Error(at + ": unknown field \"" + name + "\" (expected azimuth, elevation, distance, tf)");
    CameraKey key;
    if (item.contains("azimuth")) {
      key.azimuthDeg = readNumber(item, "azimuth", where, i);
      if (!validAzimuth(*key.azimuthDeg))
        throw Error(at + ": \"azimuth\" must be from -36000 to 36000 degrees (100 turns)");
    }
    if (item.contains("elevation")) {
      key.elevationDeg = readNumber(item, "elevation", where, i);
      if (!validElevation(*key.elevationDeg)) throw Error(at + ": \"elevation\" must be in (-90, 90) degrees");
    }
    if (item.contains("distance")) {
      key.distance = readNumber(item, "distance", where, i);
      if (!(*key.distance > 0.0f && *key.distance < 1000.0f))
        throw Error(at + ": \"distance\" must be between 0 and 1000 radii");
    }
    if (item.contains("tf")) {
      if (!item["tf"].is_string() || item["tf"].get<std::string>().empty())
        throw Error(at + ": \"tf\" must be a preset name or a JSON file path");
      key.tf = item["tf"].get<std::string>();
    }
    keys.push_back(std::move(key));
  }
  return keys;
}

std::vector<CameraKey> loadCameraKeys(const std::string& path) {
  std::error_code ec;
  // A folder opens as a stream on Linux and fails only when read, with a library message.
  if (std::filesystem::is_directory(path, ec)) throw Error(path + ": is a folder, not a key file");
  std::ifstream in(path);
  if (!in) throw Error(path + ": cannot open the key file");
  nlohmann::json j;
  try {
    j = nlohmann::json::parse(in);
  } catch (const nlohmann::json::parse_error& e) {
    throw Error(path + ": not valid JSON (byte " + std::to_string(e.byte) + ")");
  } catch (const nlohmann::json::out_of_range& e) {  // 406: a number too large for a double
    throw Error(path + ": not valid JSON: a number is out of range (" + jsonReason(e) + ")");
  } catch (const std::exception& e) {  // a read error from the stream
    throw Error(path + ": cannot read the key file (" + e.what() + ")");
  }
  std::vector<CameraKey> keys = parseCameraKeys(j, path);
  const std::filesystem::path folder = std::filesystem::path(path).parent_path();
  for (CameraKey& k : keys) {
    if (!k.tf) continue;
    const std::filesystem::path tf(*k.tf);
    if (tf.is_relative() && tf.extension() == ".json") k.tf = (folder / tf).lexically_normal().string();
  }
  return keys;
}

}  // namespace kdswap
