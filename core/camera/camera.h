// Camera: one ray per pixel centre for a View, an image size and a volume's world box.
// World space is voxel index times spacing; the volume's data domain is [0, (dims-1)*spacing].
#pragma once

#include <cstdint>
#include <optional>

#include <glm/geometric.hpp>
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include "core/camera/blue_noise.h"
#include "core/camera/view.h"
#include "core/image/rect.h"

namespace kdswap {

struct Ray {
  glm::vec3 origin;     //!< world space; sample k sits at origin + direction * ((k + offset) * step)
  glm::vec3 direction;  //!< unit length, world space
  float offset = 0.0f;  //!< this ray's lattice phase in (0, 1): the pixel's blue-noise value, so
                        //!< every brick uses the same lattice for a ray while neighbouring rays
                        //!< differ (jitter turns the rings of a fixed lattice into fine grain)
};

class Camera {
 public:
  Camera(const View& view, const glm::vec3& worldMin, const glm::vec3& worldMax, int width, int height);

  //! The ray through the centre of pixel (px, py); y grows downward. Inline: every brick asks for
  //! every pixel it covers, and a call returning the ray through memory cost more than the math.
  Ray ray(int px, int py) const {
    const float sx = ((float(px) + 0.5f) * twoOverWidth_ - 1.0f) * aspect_ * halfHeight_;
    const float sy = (1.0f - (float(py) + 0.5f) * twoOverHeight_) * halfHeight_;
    const float offset = pixelOffset(px, py);
    if (orthographic_) return Ray{eye_ + sx * right_ + sy * up_, forward_, offset};
    return Ray{eye_, glm::normalize(forward_ + sx * right_ + sy * up_), offset};
  }
  //! A ray's lattice phase: the pixel's value in the blue-noise tile (blue_noise.h), in (0, 1).
  static float pixelOffset(int px, int py) { return BlueNoiseTile::instance().at(px, py); }
  //! Pixel coordinates (continuous; pixel centres at +0.5) of a world point, or nothing when the
  //! point is at or behind the eye (perspective).
  std::optional<glm::vec2> project(const glm::vec3& world) const;
  //! Conservative pixel rectangle (clipped to the frame) covering the projection of a world box.
  Rect projectBox(const glm::vec3& lo, const glm::vec3& hi) const;
  //! The last steps of project(): pixel coordinates of a point at (sx, sy) along right and up in
  //! the image plane one unit in front of the eye (already divided by depth for perspective).
  glm::vec2 pixelOfPlanePoint(float sx, float sy) const {
    return glm::vec2((sx / (aspect_ * halfHeight_) + 1.0f) * 0.5f * float(width_),
                     (1.0f - sy / halfHeight_) * 0.5f * float(height_));
  }
  //! The last step of projectBox(): the pixels whose centres may lie in [lo, hi] (projected pixel
  //! coordinates), with a pixel of slack on each side for rounding, clipped to the frame.
  Rect conservativePixels(glm::vec2 lo, glm::vec2 hi) const;

  //! What ray() computes from: setups that compute several rays at once (core/render/ray_setup.h)
  //! repeat its arithmetic exactly, operation by operation.
  struct Basis {
    bool orthographic;
    glm::vec3 eye, forward, right, up;
    float halfHeight, aspect, twoOverWidth, twoOverHeight;
  };
  Basis basis() const {
    return Basis{orthographic_, eye_, forward_, right_, up_, halfHeight_, aspect_, twoOverWidth_, twoOverHeight_};
  }

  bool orthographic() const { return orthographic_; }
  const glm::vec3& eye() const { return eye_; }
  const glm::vec3& forward() const { return forward_; }
  int width() const { return width_; }
  int height() const { return height_; }
  Rect frame() const { return Rect{0, 0, width_, height_}; }

 private:
  int width_, height_;
  bool orthographic_;
  glm::vec3 eye_, forward_, right_, up_;
  float halfHeight_;  //!< tan(fov/2) for perspective; world half-height of the frame for orthographic
  float aspect_;
  float twoOverWidth_, twoOverHeight_;  //!< 2 / width, 2 / height: a ray multiplies (a division per ray and brick was a stall)
};

}  // namespace kdswap
