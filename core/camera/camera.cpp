// Orbit camera: eye on a sphere around the volume centre, looking at it; pinhole or parallel rays.
#include "core/camera/camera.h"

#include <algorithm>
#include <cmath>
#include <cstdint>

#include <glm/geometric.hpp>
#include <glm/trigonometric.hpp>

namespace kdswap {
namespace {

// Up axis and the "front" axis that azimuth 0 looks from.
void axesFor(UpAxis up, glm::vec3& upAxis, glm::vec3& frontAxis) {
  const int axis = int(up) / 2;
  const float sign = int(up) % 2 == 0 ? 1.0f : -1.0f;
  upAxis = glm::vec3(0.0f);
  upAxis[axis] = sign;
  frontAxis = axis == 1 ? glm::vec3(0, 0, -1) : glm::vec3(0, -1, 0);
}

}  // namespace

Camera::Camera(const View& view, const glm::vec3& worldMin, const glm::vec3& worldMax, int width, int height)
    : width_(width), height_(height), orthographic_(view.projection == Projection::Orthographic) {
  const glm::vec3 centre = 0.5f * (worldMin + worldMax);
  const float radius = std::max(0.5f * glm::length(worldMax - worldMin), 1e-6f);
  glm::vec3 upAxis, frontAxis;
  axesFor(view.up, upAxis, frontAxis);
  const glm::vec3 sideAxis = glm::cross(upAxis, frontAxis);
  const float az = glm::radians(view.azimuthDeg);
  const float el = glm::radians(std::clamp(view.elevationDeg, -89.9f, 89.9f));
  const glm::vec3 toEye =
      std::cos(el) * (std::cos(az) * frontAxis + std::sin(az) * sideAxis) + std::sin(el) * upAxis;

  forward_ = -glm::normalize(toEye);
  right_ = glm::normalize(glm::cross(forward_, upAxis));
  up_ = glm::cross(right_, forward_);
  const glm::vec3 target = centre - view.pan.x * radius * right_ - view.pan.y * radius * up_;
  eye_ = target - forward_ * (view.distance * radius);
  aspect_ = float(width) / float(std::max(height, 1));
  twoOverWidth_ = 2.0f / float(std::max(width, 1));
  twoOverHeight_ = 2.0f / float(std::max(height, 1));
  const float tanHalf = std::tan(glm::radians(std::clamp(view.fovDeg, 1.0f, 170.0f)) * 0.5f);
  halfHeight_ = orthographic_ ? tanHalf * view.distance * radius : tanHalf;
}

std::optional<glm::vec2> Camera::project(const glm::vec3& world) const {
  const glm::vec3 v = world - eye_;
  float sx = glm::dot(v, right_), sy = glm::dot(v, up_);
  if (!orthographic_) {
    const float depth = glm::dot(v, forward_);
    if (depth <= 1e-4f) return std::nullopt;
    sx /= depth;
    sy /= depth;
  }
  return pixelOfPlanePoint(sx, sy);
}

Rect Camera::projectBox(const glm::vec3& lo, const glm::vec3& hi) const {
  float minX = 1e30f, minY = 1e30f, maxX = -1e30f, maxY = -1e30f;
  for (int corner = 0; corner < 8; ++corner) {
    const glm::vec3 p(corner & 1 ? hi.x : lo.x, corner & 2 ? hi.y : lo.y, corner & 4 ? hi.z : lo.z);
    const std::optional<glm::vec2> pixel = project(p);
    if (!pixel) return frame();  // a corner at or behind the eye: cover everything
    const float px = pixel->x, py = pixel->y;
    if (!std::isfinite(px) || !std::isfinite(py)) return frame();
    minX = std::min(minX, px), maxX = std::max(maxX, px);
    minY = std::min(minY, py), maxY = std::max(maxY, py);
  }
  return conservativePixels(glm::vec2(minX, minY), glm::vec2(maxX, maxY));
}

Rect Camera::conservativePixels(glm::vec2 lo, glm::vec2 hi) const {
  float minX = lo.x, minY = lo.y, maxX = hi.x, maxY = hi.y;
  const float limit = 4.0f * float(std::max(width_, height_)) + 4.0f;  // keeps int conversion defined
  minX = std::clamp(minX, -limit, limit), maxX = std::clamp(maxX, -limit, limit);
  minY = std::clamp(minY, -limit, limit), maxY = std::clamp(maxY, -limit, limit);
  // One pixel of slack on each side keeps the rectangle conservative under rounding.
  const int x0 = int(std::floor(minX)) - 1, y0 = int(std::floor(minY)) - 1;
  const int x1 = int(std::ceil(maxX)) + 1, y1 = int(std::ceil(maxY)) + 1;
  return Rect{x0, y0, x1 - x0, y1 - y0}.intersect(frame());
}

}  // namespace kdswap
