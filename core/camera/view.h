// View: the user's orbit-camera parameters, independent of image size and volume.
#pragma once

#include <string>

#include <glm/vec2.hpp>

namespace kdswap {

enum class Projection { Perspective, Orthographic };

//! A view's or a key's azimuth is at most this many degrees either way (100 turns): a float
//! azimuth keeps a 0.004-degree step there, where 1e9 degrees would be some angle no one chose.
inline constexpr float kMaxAzimuthDegrees = 36000.0f;
//! Within the bound (NaN is not): the one test for --view and key files.
inline bool validAzimuth(float degrees) { return degrees >= -kMaxAzimuthDegrees && degrees <= kMaxAzimuthDegrees; }

//! Which volume axis points up on screen ("+z" by default; CT stacks often want "-z").
enum class UpAxis { PlusX, MinusX, PlusY, MinusY, PlusZ, MinusZ };

struct View {
  float azimuthDeg = 30.0f;    //!< orbit angle around the up axis; 0 looks from the "front" (-y side)
  float elevationDeg = 15.0f;  //!< angle above the equator, in (-90, 90)
  //! Eye distance from the centre, in bounding-sphere radii. The default shows the whole sphere
  //! (so the whole volume, from any side) within the vertical field of view: 1 / sin(35 / 2) = 3.33.
  float distance = 3.4f;
  float fovDeg = 35.0f;        //!< vertical field of view; orthographic uses it to set the frame size
  Projection projection = Projection::Perspective;
  UpAxis up = UpAxis::PlusZ;
  glm::vec2 pan{0.0f};         //!< screen-space shift of the orbit centre, in bounding-sphere radii
};

// Each throws Error starting with `what`: a command-line option ("--up") or a file's field.
//! "perspective" | "orthographic"
Projection parseProjection(const std::string& text, const std::string& what = "projection");
//! "+x" "-x" "+y" "-y" "+z" "-z"
UpAxis parseUpAxis(const std::string& text, const std::string& what = "up axis");
std::string toString(Projection p);
std::string toString(UpAxis u);

}  // namespace kdswap
