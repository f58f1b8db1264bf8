// Scripted input: parse the command list, then per UI frame set the synthetic mouse and keys and
// move to the next command once the current one is done. One command starts per frame, so every
// change of input is seen by ImGui on a frame of its own, as with a real mouse.
#include "ui/input_script.h"

#include <algorithm>
#include <cctype>
#include <cstdint>
#include <fstream>
#include <sstream>

#include <GLFW/glfw3.h>

#include "core/util/error.h"

namespace kdswap {
namespace {

constexpr double kWaitTimeoutSeconds = 300;

struct Shape {
  const char* verb;
  std::size_t minArgs, maxArgs;
};
constexpr Shape kShapes[] = {{"move", 1, 3}, {"glide", 3, 3}, {"down", 1, 1}, {"up", 1, 1}, {"click", 1, 1},
                             {"wheel", 1, 1}, {"key", 1, 1},  {"frames", 1, 1}, {"wait", 1, 1}, {"checkpoint", 1, 1},
                             {"verify-redraw", 0, 0}, {"type", 1, SIZE_MAX}};

int buttonIndex(const std::string& name) {
  if (name == "left") return ImGuiMouseButton_Left;
  if (name == "right") return ImGuiMouseButton_Right;
  if (name == "middle") return ImGuiMouseButton_Middle;
  return -1;
}

float number(const std::string& text, bool& ok) {
  std::istringstream in(text);
  float v = 0;
  ok = static_cast<bool>(in >> v) && in.eof();
  return v;
}

}  // namespace

InputScript InputScript::load(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw Error(path + ": cannot open the input script");
  InputScript script;
  script.path_ = path;
  std::string text;
  for (int line = 1; std::getline(in, text); ++line) {
    text = text.substr(0, text.find('#'));
    std::istringstream words(text);
    Command c;
    c.line = line;
    if (!(words >> c.verb)) continue;
    for (std::string w; words >> w;) c.args.push_back(w);
    const Shape* shape = nullptr;
    for (const Shape& s : kShapes)
      if (c.verb == s.verb) shape = &s;
    if (!shape) script.fail(c, "unknown command '" + c.verb + "'");
    if (c.args.size() < shape->minArgs || c.args.size() > shape->maxArgs) script.fail(c, "wrong number of arguments");
    bool ok = true;
    if ((c.verb == "down" || c.verb == "up" || c.verb == "click") && buttonIndex(c.args[0]) < 0)
      script.fail(c, "expected left, right or middle");
    if (c.verb == "glide" || c.verb == "wheel" || c.verb == "frames")
      for (const std::string& a : c.args) number(a, ok);
    if (!ok) script.fail(c, "expected numbers");
    if (c.verb == "key" && (c.args[0].size() != 1 || !std::isalpha(static_cast<unsigned char>(c.args[0][0]))))
      script.fail(c, "expected one letter");
    if (c.verb == "wait" && c.args[0] != "full" && c.args[0] != "preview") script.fail(c, "expected 'full' or 'preview'");
    script.commands_.push_back(c);
  }
  return script;
}

void InputScript::fail(const Command& c, const std::string& what) const {
  throw Error(path_ + ":" + std::to_string(c.line) + ": " + c.verb + ": " + what);
}

void InputScript::apply(ImGuiIO& io) const {
  io.MousePos = mouse_;
  for (int b = 0; b < 3; ++b) io.MouseDown[b] = down_[b];
  io.MouseWheel = wheel_;
  for (int k = GLFW_KEY_A; k <= GLFW_KEY_Z; ++k) io.KeysDown[k] = k == key_;
  if (!text_.empty()) io.AddInputCharactersUTF8(text_.c_str());
}

ImVec2 InputScript::target(const Command& c, const GuiState& state) const {
  const std::string& kind = c.args[0];
  bool ok = true;
  auto arg = [&](std::size_t i) { return i < c.args.size() ? number(c.args[i], ok) : 0.0f; };
  ImVec2 p;
  if (kind == "viewport") {
    const ImVec4& r = state.layout.viewport;
    if (r.z <= 0) fail(c, "the viewport has not been drawn");
    p = ImVec2(r.x + arg(1) * r.z, r.y + arg(2) * r.w);
  } else if (kind == "cell") {
    const int node = int(arg(1)), phase = int(arg(2));
    const auto& cells = state.layout.cells;
    const auto it = std::find_if(cells.begin(), cells.end(), [&](const DrawnLayout::Cell& x) { return x.node == node && x.phase == phase; });
    if (it == cells.end()) fail(c, "no stage cell for node " + std::to_string(node) + ", phase " + std::to_string(phase));
    p = ImVec2(it->rect.x + 0.5f * it->rect.z, it->rect.y + 0.5f * it->rect.w);
  } else if (kind == "tf-point") {
    const std::size_t k = std::size_t(arg(1));
    if (k >= state.layout.tfPoints.size()) fail(c, "no opacity point " + c.args[1]);
    p = state.layout.tfPoints[k];
  } else if (kind == "item") {
    if (c.args.size() != 2) fail(c, "expected one name after 'item'");
    const auto it = state.layout.items.find(c.args[1]);
    if (it == state.layout.items.end()) fail(c, "no widget named '" + c.args[1] + "' is drawn");
    p = ImVec2(it->second.x + 0.5f * it->second.z, it->second.y + 0.5f * it->second.w);
  } else if (kind == "at") {
    p = ImVec2(arg(1), arg(2));
  } else {
    fail(c, "unknown target '" + kind + "' (viewport, cell, tf-point, item, at)");
  }
  if (!ok) fail(c, "expected numbers after the target");
  return p;
}

InputScript::Step InputScript::advance(const GuiState& state, double now) {
  Step out;
  wheel_ = 0;  // wheel, key and text events last one frame
  key_ = -1;
  text_.clear();
  if (next_ >= commands_.size()) {
    out.finished = true;
    return out;
  }
  const Command& c = commands_[next_];
  const bool first = !started_;
  if (first) {
    started_ = true;
    startedAt_ = now;
    shownAtStart_ = state.shownLog.size();
  }
  bool done = true;
  bool ok = true;
  if (c.verb == "move") {
    mouse_ = target(c, state);
  } else if (c.verb == "glide") {
    if (first) {
      from_ = mouse_;
      by_ = ImVec2(number(c.args[0], ok), number(c.args[1], ok));
      glideFrames_ = framesLeft_ = std::max(1, int(number(c.args[2], ok)));
    }
    const float t = float(glideFrames_ - --framesLeft_) / float(glideFrames_);
    mouse_ = ImVec2(from_.x + by_.x * t, from_.y + by_.y * t);
    done = framesLeft_ <= 0;
  } else if (c.verb == "down" || c.verb == "up") {
    down_[buttonIndex(c.args[0])] = c.verb == "down";
  } else if (c.verb == "click") {
    down_[buttonIndex(c.args[0])] = first;
    done = !first;
  } else if (c.verb == "wheel") {
    wheel_ = number(c.args[0], ok);
  } else if (c.verb == "key") {
    key_ = GLFW_KEY_A + (std::toupper(static_cast<unsigned char>(c.args[0][0])) - 'A');
  } else if (c.verb == "type") {
    for (const std::string& word : c.args) text_ += (text_.empty() ? "" : " ") + word;
  } else if (c.verb == "frames") {
    if (first) framesLeft_ = int(number(c.args[0], ok));
    done = --framesLeft_ <= 0;
  } else if (c.verb == "wait") {
    if (c.args[0] == "full") {
      done = state.frame && !state.frame->preview && state.frame->id == state.lastSubmitted && !state.rendering &&
             !state.building && !state.refinePending;
    } else {
      // A preview on screen, or one that arrived since: previews may finish before the wait begins.
      done = (state.frame && state.frame->preview) ||
             std::any_of(state.shownLog.begin() + std::ptrdiff_t(shownAtStart_), state.shownLog.end(),
                         [](const ShownFrame& f) { return f.preview; });
    }
    // The newest request ended without a frame (data that would not open): none will come.
    if (!done && state.lastSubmitted != 0 && state.lastFailed == state.lastSubmitted)
      fail(c, "no frame will come: " + (state.errors.empty() ? std::string("the newest request failed") : state.errors.back()));
    if (!done && now - startedAt_ > kWaitTimeoutSeconds) fail(c, "timed out");
  } else if (c.verb == "checkpoint") {
    out.checkpoint = c.args[0];
  } else if (c.verb == "verify-redraw") {
    out.verifyRedraw = true;
  }
  if (done) ++next_, started_ = false;
  out.finished = next_ >= commands_.size();
  return out;
}

}  // namespace kdswap
