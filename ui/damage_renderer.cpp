// Partial redraw of ImGui frames: compare each window's draw list with the previous frame's, clip
// every draw command to the bounding rectangle of what changed, draw into the back buffer and copy
// that rectangle to the window. Outside the rectangle the back buffer keeps last frame's pixels,
// which equal what a full redraw would produce there: a command only touches pixels inside its
// clip rectangle and its vertices' bounding box, and no command touching them changed.
#include "ui/damage_renderer.h"

#include <algorithm>
#include <cfloat>
#include <cmath>
#include <cstring>

#include <GL/gl.h>
#include <GLFW/glfw3.h>
#include <imgui_impl_opengl3.h>


namespace kdswap {
namespace {

// GLFW's native accessors (glfw3native.h would pull in X11 extension headers for two calls).
extern "C" struct _XDisplay* glfwGetX11Display();
extern "C" unsigned long glfwGetGLXWindow(GLFWwindow* window);

bool emptyRect(const ImVec4& r) { return r.z <= r.x || r.w <= r.y; }

ImVec4 unite(const ImVec4& a, const ImVec4& b) {
  if (emptyRect(a)) return b;
  if (emptyRect(b)) return a;
  return ImVec4(std::min(a.x, b.x), std::min(a.y, b.y), std::max(a.z, b.z), std::max(a.w, b.w));
}

ImVec4 intersect(const ImVec4& a, const ImVec4& b) {
  return ImVec4(std::max(a.x, b.x), std::max(a.y, b.y), std::min(a.z, b.z), std::min(a.w, b.w));
}

// Every pixel a command draws lies inside its clip rectangle and inside the bounding box of its
// vertices (widened by a pixel for rounding). Window decorations are clipped to the whole
// display, so the clip rectangle alone would not say much.
ImVec4 bounds(const ImDrawList& list) {
  ImVec4 r(0, 0, 0, 0);
  for (const ImDrawCmd& c : list.CmdBuffer) {
    if (c.UserCallback || c.ElemCount == 0) continue;
    ImVec4 box(FLT_MAX, FLT_MAX, -FLT_MAX, -FLT_MAX);
    for (unsigned i = c.IdxOffset; i < c.IdxOffset + c.ElemCount; ++i) {
      const ImVec2& p = list.VtxBuffer[int(c.VtxOffset + list.IdxBuffer[int(i)])].pos;
      box = ImVec4(std::min(box.x, p.x), std::min(box.y, p.y), std::max(box.z, p.x), std::max(box.w, p.y));
    }
    r = unite(r, intersect(c.ClipRect, ImVec4(box.x - 1, box.y - 1, box.z + 1, box.w + 1)));
  }
  return r;
}

template <typename T>
bool sameBytes(const std::vector<T>& copy, const ImVector<T>& now) {
  return copy.size() == std::size_t(now.Size) && (copy.empty() || std::memcmp(copy.data(), now.Data, copy.size() * sizeof(T)) == 0);
}

// Window names in draw order; a name seen twice gets its occurrence number appended.
std::vector<std::string> listNames(const ImDrawData& data) {
  std::vector<std::string> names;
  for (int i = 0; i < data.CmdListsCount; ++i) {
    const char* owner = data.CmdLists[i]->_OwnerName;
    std::string name = owner ? owner : "#list";
    const std::string base = name;
    for (int k = 1; std::find(names.begin(), names.end(), name) != names.end(); ++k) name = base + "#" + std::to_string(k);
    names.push_back(name);
  }
  return names;
}

// True when the windows present in both frames are drawn in the same relative order.
bool sameOrder(const std::vector<std::string>& before, const std::vector<std::string>& now) {
  std::vector<std::string> a, b;
  for (const std::string& n : before)
    if (std::find(now.begin(), now.end(), n) != now.end()) a.push_back(n);
  for (const std::string& n : now)
    if (std::find(before.begin(), before.end(), n) != before.end()) b.push_back(n);
  return a == b;
}

}  // namespace

DamageRenderer::DamageRenderer(GLFWwindow* window, bool everyFrame) : window_(window), everyFrame_(everyFrame) {
  if (!everyFrame && glfwGetX11Display() && glfwGetGLXWindow(window) && glfwExtensionSupported("GLX_MESA_copy_sub_buffer"))
    copySubBuffer_ = reinterpret_cast<CopySubBuffer>(glfwGetProcAddress("glXCopySubBufferMESA"));
}

// The region (ImGui display coordinates) whose pixels may differ from the previous frame.
ImVec4 DamageRenderer::damage(const ImDrawData& data) {
  const ImVec4 all(data.DisplayPos.x, data.DisplayPos.y, data.DisplayPos.x + data.DisplaySize.x,
                   data.DisplayPos.y + data.DisplaySize.y);
  const std::vector<std::string> names = listNames(data);
  ImVec4 region(0, 0, 0, 0);
  if (fullNext_ || !sameOrder(order_, names)) region = all;
  auto usesChangedTexture = [&](const ImDrawList& list) {
    for (const ImDrawCmd& c : list.CmdBuffer)
      if (std::find(changedTextures_.begin(), changedTextures_.end(), c.TextureId) != changedTextures_.end()) return true;
    return false;
  };
  std::unordered_map<std::string, ListCopy> now;
  for (int i = 0; i < data.CmdListsCount; ++i) {
    const ImDrawList& list = *data.CmdLists[i];
    const auto before = lists_.find(names[std::size_t(i)]);
    const ImVec4 area = bounds(list);
    if (before == lists_.end()) {
      region = unite(region, area);
    } else {
      const ListCopy& old = before->second;
      if (!sameBytes(old.commands, list.CmdBuffer) || !sameBytes(old.vertices, list.VtxBuffer) ||
          !sameBytes(old.indices, list.IdxBuffer) || usesChangedTexture(list))
        region = unite(region, unite(old.bounds, area));
      lists_.erase(before);
    }
    ListCopy& copy = now[names[std::size_t(i)]];
    copy.bounds = area;
    copy.vertices.assign(list.VtxBuffer.begin(), list.VtxBuffer.end());
    copy.indices.assign(list.IdxBuffer.begin(), list.IdxBuffer.end());
    copy.commands.assign(list.CmdBuffer.begin(), list.CmdBuffer.end());
  }
  for (const auto& gone : lists_) region = unite(region, gone.second.bounds);  // windows that closed
  lists_ = std::move(now);
  order_ = names;
  changedTextures_.clear();
  fullNext_ = false;
  return intersect(region, all);
}

bool DamageRenderer::render(ImDrawData* data, int width, int height, const ImVec4& clearColour) {
  drawn_ = false;
  lastFraction_ = 0;
  if (width <= 0 || height <= 0) return false;
  if (width != width_ || height != height_) fullNext_ = true, width_ = width, height_ = height;
  // Without a preserved back buffer a changed frame is drawn whole.
  const bool whole = fullNext_ || !partial();
  ImVec4 region = damage(*data);
  std::vector<std::uint8_t> kept;
  if (verifyPending_ && !whole && emptyRect(region)) kept = readPixels(width, height);
  if (emptyRect(region) && kept.empty() && !everyFrame_) return false;
  if (whole || !kept.empty() || everyFrame_)
    region = ImVec4(data->DisplayPos.x, data->DisplayPos.y, data->DisplayPos.x + data->DisplaySize.x,
                    data->DisplayPos.y + data->DisplaySize.y);
  // Whole pixels, rounded outwards, so the clear and the clipped draws cover the same pixels.
  region = ImVec4(std::floor(region.x), std::floor(region.y), std::ceil(region.z), std::ceil(region.w));
  for (int i = 0; i < data->CmdListsCount; ++i)
    for (ImDrawCmd& c : data->CmdLists[i]->CmdBuffer) {
      c.ClipRect = intersect(c.ClipRect, region);
      if (emptyRect(c.ClipRect)) c.ClipRect.z = c.ClipRect.x;  // the backend skips empty clips
    }
  const ImVec2 scale = data->FramebufferScale, origin = data->DisplayPos;
  const int x0 = std::max(0, int((region.x - origin.x) * scale.x)), x1 = std::min(width, int((region.z - origin.x) * scale.x));
  const int y0 = std::max(0, int((region.y - origin.y) * scale.y)), y1 = std::min(height, int((region.w - origin.y) * scale.y));
  if (x1 <= x0 || y1 <= y0) return false;
  copy_[0] = x0, copy_[1] = height - y1, copy_[2] = x1 - x0, copy_[3] = y1 - y0;
  lastFraction_ = double(copy_[2]) * double(copy_[3]) / (double(width) * double(height));

  glViewport(0, 0, width, height);
  glEnable(GL_SCISSOR_TEST);
  glScissor(copy_[0], copy_[1], copy_[2], copy_[3]);
  glClearColor(clearColour.x, clearColour.y, clearColour.z, clearColour.w);
  glClear(GL_COLOR_BUFFER_BIT);
  glDisable(GL_SCISSOR_TEST);
  ImGui_ImplOpenGL3_RenderDrawData(data);
  drawn_ = true;
  if (!kept.empty()) {
    const std::vector<std::uint8_t> redrawn = readPixels(width, height);
    mismatches_ = 0;
    for (std::size_t i = 0; i < kept.size(); i += 4) mismatches_ += std::memcmp(&kept[i], &redrawn[i], 3) != 0;
    verifyPending_ = false;
  }
  return true;
}

void DamageRenderer::present() {
  if (!drawn_) return;
  if (partial()) copySubBuffer_(glfwGetX11Display(), glfwGetGLXWindow(window_), copy_[0], copy_[1], copy_[2], copy_[3]);
  else glfwSwapBuffers(window_);
  drawn_ = false;
}

std::vector<std::uint8_t> DamageRenderer::readPixels(int width, int height) const {
  std::vector<std::uint8_t> bottomUp(std::size_t(width) * height * 4), topDown(bottomUp.size());
  if (bottomUp.empty()) return topDown;
  glReadBuffer(GL_BACK);
  glPixelStorei(GL_PACK_ALIGNMENT, 1);
  glReadPixels(0, 0, width, height, GL_RGBA, GL_UNSIGNED_BYTE, bottomUp.data());
  const std::size_t row = std::size_t(width) * 4;
  for (int y = 0; y < height; ++y) std::memcpy(&topDown[std::size_t(y) * row], &bottomUp[std::size_t(height - 1 - y) * row], row);
  return topDown;
}

}  // namespace kdswap
