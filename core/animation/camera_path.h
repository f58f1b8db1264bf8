// CameraPath: the view (and transfer-function switch) of every frame of an animation, either an
// orbit around the up axis or key views interpolated linearly; key files are JSON (format below).
#pragma once

#include <optional>
#include <string>
#include <vector>

#include <glm/vec2.hpp>
#include <nlohmann/json_fwd.hpp>

#include "core/camera/view.h"

namespace kdswap {

inline constexpr int kMaxAnimationFrames = 100000;
//! An orbit turns at most this many degrees either way: the 100 turns a view's azimuth may take.
inline constexpr float kMaxOrbitDegrees = kMaxAzimuthDegrees;

//! One key view. Unset angles or distance repeat the previous key's (the first key's: the base
//! view's). `tf`, when set, switches the transfer function from this key's frame on.
struct CameraKey {
  std::optional<float> azimuthDeg, elevationDeg, distance;
  std::optional<std::string> tf;
};

//! What one frame shows: the full view and the transfer function in force ("" = the base one).
struct PathFrame {
  View view;
  std::string tf;
};

class CameraPath {
 public:
  //! Frame i looks from azimuth start + degrees * i / frames, so a 360-degree orbit loops without
  //! repeating a frame. With `elevationSweep` (FROM, TO) the elevation goes linearly from FROM at
  //! the first frame to TO at the last. Throws kdswap::Error for a bad count or angle.
  static CameraPath orbit(const View& start, float degrees, int frames,
                          std::optional<glm::vec2> elevationSweep = std::nullopt);
  //! Keys spread evenly: the first at frame 0, the last at frame frames - 1, views interpolated
  //! linearly between them (azimuth is not wrapped: 0 to 360 is a full turn). Throws kdswap::Error.
  static CameraPath fromKeys(const View& base, const std::vector<CameraKey>& keys, int frames);

  int frameCount() const { return int(frames_.size()); }
  const PathFrame& frame(int i) const { return frames_.at(std::size_t(i)); }
  //! Every transfer function a key switches to, in order of first use.
  std::vector<std::string> transferFunctions() const;

 private:
  std::vector<PathFrame> frames_;
};

//! Parses a key list: a JSON array of keys, or an object with a "keys" array. Each key is an
//! object with optional "azimuth", "elevation" (degrees, in (-90, 90)), "distance" (> 0) and "tf".
//! `where` names the source; errors name it and the key index. Throws kdswap::Error.
std::vector<CameraKey> parseCameraKeys(const nlohmann::json& j, const std::string& where);
//! Reads and parses a key file. A relative "tf" path ending in .json is taken relative to the
//! key file's folder. Throws kdswap::Error naming the file.
std::vector<CameraKey> loadCameraKeys(const std::string& path);

}  // namespace kdswap
