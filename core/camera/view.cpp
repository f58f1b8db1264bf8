// Parsing and printing of view enums for the command line and JSON.
#include "core/camera/view.h"

#include "core/util/error.h"

namespace kdswap {

Projection parseProjection(const std::string& text, const std::string& what) {
  if (text == "perspective" || text == "persp") return Projection::Perspective;
  if (text == "orthographic" || text == "ortho") return Projection::Orthographic;
  throw Error(what + " \"" + text + "\": expected perspective or orthographic");
}

UpAxis parseUpAxis(const std::string& text, const std::string& what) {
  const char* names[] = {"+x", "-x", "+y", "-y", "+z", "-z"};
  for (int i = 0; i < 6; ++i)
    if (text == names[i]) return UpAxis(i);
  if (text == "x" || text == "y" || text == "z") return parseUpAxis("+" + text, what);
  throw Error(what + " \"" + text + "\": expected one of +x -x +y -y +z -z");
}

std::string toString(Projection p) { return p == Projection::Perspective ? "perspective" : "orthographic"; }

std::string toString(UpAxis u) {
  const char* names[] = {"+x", "-x", "+y", "-y", "+z", "-z"};
  return names[int(u)];
}

}  // namespace kdswap
