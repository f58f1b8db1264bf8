// GlTexture: one RGBA8 OpenGL texture for ImGui::Image; must live and die on the GL thread.
#pragma once

#include <cstdint>

#include <imgui.h>

#include "ui/frame_pixels.h"

namespace kdswap {

class GlTexture {
 public:
  GlTexture() = default;
  ~GlTexture() { reset(); }
  GlTexture(const GlTexture&) = delete;
  GlTexture& operator=(const GlTexture&) = delete;

  //! Replaces the contents (re-allocating when the size changes). Linear filtering.
  void upload(const Pixels& pixels);
  //! Deletes the texture; call before the GL context goes away.
  void reset();
  bool valid() const { return id_ != 0 && width_ > 0; }
  ImTextureID imguiId() const { return reinterpret_cast<ImTextureID>(static_cast<std::intptr_t>(id_)); }
  int width() const { return width_; }
  int height() const { return height_; }

 private:
  unsigned id_ = 0;
  int width_ = 0, height_ = 0;
};

}  // namespace kdswap
