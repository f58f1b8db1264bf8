// DamageRenderer: draws an ImGui frame only where it differs from the previous one. With a software
// rasteriser (Mesa llvmpipe under Xvfb, or a desktop without a GPU) filling the whole window costs
// tens of milliseconds; most UI frames change nothing (a frame is rendering in the background) or
// one panel (the view is being dragged). On GLX with GLX_MESA_copy_sub_buffer (every Mesa driver)
// the changed rectangle is drawn into the back buffer, which then always holds the whole picture,
// and only that rectangle is copied to the window; elsewhere a changed frame is drawn whole and
// swapped, and an unchanged one is not drawn at all. Must live and die on the GL thread.
#pragma once

#include <cstdint>
#include <string>
#include <unordered_map>
#include <vector>

#include <imgui.h>

struct GLFWwindow;

namespace kdswap {

class DamageRenderer {
 public:
  //! Needs the window's GL context current. `everyFrame`: draw and swap the whole window every
  //! frame, changed or not (for comparison, and in case a driver misbehaves).
  DamageRenderer(GLFWwindow* window, bool everyFrame);

  //! True when only changed rectangles are drawn and copied (GLX_MESA_copy_sub_buffer).
  bool partial() const { return copySubBuffer_ != nullptr; }
  //! The contents of texture `id` changed: every window drawing it is redrawn next frame.
  void textureChanged(ImTextureID id) { changedTextures_.push_back(id); }
  //! Redraw the whole window next frame (it was exposed, or a capture needs every pixel).
  void invalidate() { fullNext_ = true; }

  //! Draws what changed in `data` into the back buffer (modifying its clip rectangles). Returns
  //! false when nothing changed, so nothing was drawn and present() has nothing to do.
  bool render(ImDrawData* data, int width, int height, const ImVec4& clearColour);
  //! The back buffer's pixels (RGBA8, top row first). Complete after a render() that drew, or
  //! at any time when partial(); otherwise call invalidate() before that render().
  std::vector<std::uint8_t> readPixels(int width, int height) const;
  //! Shows what the last render() drew: copies the changed rectangle, or swaps.
  void present();

  //! Self-check of partial redraw: on the next frame that changes nothing, draw the whole window
  //! anyway and count the pixels that differ from the incrementally kept picture.
  void requestVerification() { verifyPending_ = partial(); }
  //! Pixels that differed in the last verification (0 when partial redraw is exact), -1 if none ran.
  long verificationMismatches() const { return mismatches_; }

  //! Fraction of the window the last render() drew (0: nothing changed, 1: everything).
  double lastDamagedFraction() const { return lastFraction_; }

 private:
  struct ListCopy {
    std::vector<ImDrawVert> vertices;
    std::vector<ImDrawIdx> indices;
    std::vector<ImDrawCmd> commands;
    ImVec4 bounds;  //!< where its pixels can be
  };
  ImVec4 damage(const ImDrawData& data);

  GLFWwindow* window_;
  bool everyFrame_;
  using CopySubBuffer = void (*)(void* display, unsigned long drawable, int x, int y, int width, int height);
  CopySubBuffer copySubBuffer_ = nullptr;  //!< glXCopySubBufferMESA, when the context has it
  int width_ = 0, height_ = 0;
  bool fullNext_ = true, drawn_ = false, verifyPending_ = false;
  long mismatches_ = -1;
  int copy_[4] = {0, 0, 0, 0};                        //!< x, y (GL: bottom-up), w, h to present
  std::vector<std::string> order_;                    //!< window names in last frame's draw order
  std::unordered_map<std::string, ListCopy> lists_;  //!< last frame's draw lists by window name
  std::vector<ImTextureID> changedTextures_;
  double lastFraction_ = 0;
};

}  // namespace kdswap
