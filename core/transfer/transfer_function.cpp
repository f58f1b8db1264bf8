// Transfer function evaluation, step correction, and JSON (kdswap and ParaView colour maps).
#include "core/transfer/transfer_function.h"

#include <algorithm>
#include <cmath>

#include <nlohmann/json.hpp>

#include "core/util/error.h"
#include "core/util/json_error.h"

namespace kdswap {
namespace {

template <typename Point, typename Value, typename Get>
Value interpolate(const std::vector<Point>& points, float s, Get get) {
  if (points.empty()) return Value(0.0f);
  if (!(s > points.front().x)) return get(points.front());  // also NaN: never search with it
  if (s >= points.back().x) return get(points.back());
  auto hi = std::upper_bound(points.begin(), points.end(), s, [](float v, const Point& p) { return v < p.x; });
  auto lo = hi - 1;
  const float span = hi->x - lo->x;
  const float t = span > 0.0f ? (s - lo->x) / span : 0.0f;
  return get(*lo) + t * (get(*hi) - get(*lo));
}

bool finiteIn01(float v) { return std::isfinite(v) && v >= 0.0f && v <= 1.0f; }

//! Item `index` of `list` as a float; a string, null or list there is named, not left to the JSON
//! library's message ("nan.json: opacity point 1: item 1 is a string, expected a number").
float numberAt(const nlohmann::json& list, std::size_t index, const std::string& where, const std::string& what) {
  const nlohmann::json& v = list.at(index);
  if (!v.is_number()) {
    const std::string kind = v.type_name();  // "string", "boolean", "null", "array", "object"
    const std::string is = v.is_null() ? kind : (kind[0] == 'a' || kind[0] == 'o' ? "an " : "a ") + kind;
    throw Error(where + ": " + what + ": item " + std::to_string(index) + " is " + is + ", expected a number");
  }
  return v.get<float>();
}

}  // namespace

TransferFunction::TransferFunction(std::vector<ColorStop> colors, std::vector<OpacityPoint> opacity, std::string name)
    : colors_(std::move(colors)), opacity_(std::move(opacity)), name_(std::move(name)) {
  validate(name_.empty() ? "transfer function" : name_);
}

void TransferFunction::setColors(std::vector<ColorStop> colors) {
  colors_ = std::move(colors);
  std::stable_sort(colors_.begin(), colors_.end(), [](auto& a, auto& b) { return a.x < b.x; });
}

void TransferFunction::setOpacity(std::vector<OpacityPoint> opacity) {
  opacity_ = std::move(opacity);
  std::stable_sort(opacity_.begin(), opacity_.end(), [](auto& a, auto& b) { return a.x < b.x; });
}

void TransferFunction::validate(const std::string& where) const {
  if (colors_.empty()) throw Error(where + ": transfer function has no colour stops");
  if (opacity_.empty()) throw Error(where + ": transfer function has no opacity points");
  for (std::size_t i = 0; i < colors_.size(); ++i) {
    const ColorStop& c = colors_[i];
    if (!finiteIn01(c.x) || !finiteIn01(c.rgb.r) || !finiteIn01(c.rgb.g) || !finiteIn01(c.rgb.b))
      throw Error(where + ": colour stop " + std::to_string(i) + " has a value outside [0, 1]");
    if (i > 0 && c.x < colors_[i - 1].x)
      throw Error(where + ": colour stops must be in increasing order of x");
  }
  for (std::size_t i = 0; i < opacity_.size(); ++i) {
    const OpacityPoint& p = opacity_[i];
    if (!finiteIn01(p.x) || !finiteIn01(p.alpha))
      throw Error(where + ": opacity point " + std::to_string(i) + " has a value outside [0, 1]");
    if (i > 0 && p.x < opacity_[i - 1].x)
      throw Error(where + ": opacity points must be in increasing order of x");
  }
}

glm::vec4 TransferFunction::evaluate(float s) const {
  const glm::vec3 rgb = interpolate<ColorStop, glm::vec3>(colors_, s, [](const ColorStop& c) { return c.rgb; });
  const float a = interpolate<OpacityPoint, float>(opacity_, s, [](const OpacityPoint& p) { return p.alpha; });
  return glm::vec4(rgb, a);
}

nlohmann::json TransferFunction::toJson() const {
  nlohmann::json j;
  j["name"] = name_;
  j["colors"] = nlohmann::json::array();
  for (const ColorStop& c : colors_) j["colors"].push_back({c.x, c.rgb.r, c.rgb.g, c.rgb.b});
  j["opacity"] = nlohmann::json::array();
  for (const OpacityPoint& p : opacity_) j["opacity"].push_back({p.x, p.alpha});
  return j;
}

TransferFunction TransferFunction::fromJson(const nlohmann::json& input, const std::string& where) {
  try {
    // ParaView exports a list holding one colour map object.
    const nlohmann::json& j = input.is_array() && !input.empty() ? input.front() : input;
    if (!j.is_object()) throw Error(where + ": expected a JSON object describing a transfer function");
    std::vector<ColorStop> colors;
    std::vector<OpacityPoint> opacity;
    std::string name = j.value("name", j.value("Name", std::string()));
    if (j.contains("RGBPoints")) {
      // ParaView: flat [x, r, g, b, ...] in data units; we rescale x to [0, 1].
      const auto& pts = j.at("RGBPoints");
      if (!pts.is_array() || pts.size() < 8 || pts.size() % 4 != 0)
        throw Error(where + ": RGBPoints must hold at least two groups of 4 numbers (x r g b)");
      const auto point = [&](std::size_t i) { return numberAt(pts, i, where, "RGBPoints"); };
      const float x0 = point(0), x1 = point(pts.size() - 4);
      const float span = x1 > x0 ? x1 - x0 : 1.0f;
      for (std::size_t i = 0; i < pts.size(); i += 4)
        colors.push_back({(point(i) - x0) / span, {point(i + 1), point(i + 2), point(i + 3)}});
      if (j.contains("Points")) {
        const auto& op = j.at("Points");  // [x, alpha, midpoint, sharpness, ...]
        if (!op.is_array() || op.size() < 8 || op.size() % 4 != 0)
          throw Error(where + ": Points must hold at least two groups of 4 numbers (x alpha mid sharp)");
        for (std::size_t i = 0; i < op.size(); i += 4)
          opacity.push_back({(numberAt(op, i, where, "Points") - x0) / span, numberAt(op, i + 1, where, "Points")});
      } else {
        opacity = {{0.0f, 0.0f}, {1.0f, 1.0f}};  // ParaView's default ramp
      }
    } else {
      if (!j.contains("colors") || !j.contains("opacity"))
        throw Error(where + ": expected \"colors\" and \"opacity\" (kdswap) or \"RGBPoints\" (ParaView)");
      if (!j.at("colors").is_array() || !j.at("opacity").is_array())
        throw Error(where + ": \"colors\" and \"opacity\" must be lists");
      for (const auto& c : j.at("colors")) {
        if (!c.is_array() || c.size() != 4) throw Error(where + ": each colour stop is [x, r, g, b]");
        const std::string what = "colour stop " + std::to_string(colors.size());
        colors.push_back({numberAt(c, 0, where, what),
                          {numberAt(c, 1, where, what), numberAt(c, 2, where, what), numberAt(c, 3, where, what)}});
      }
      for (const auto& p : j.at("opacity")) {
        if (!p.is_array() || p.size() != 2) throw Error(where + ": each opacity point is [x, alpha]");
        const std::string what = "opacity point " + std::to_string(opacity.size());
        opacity.push_back({numberAt(p, 0, where, what), numberAt(p, 1, where, what)});
      }
    }
    TransferFunction tf;
    tf.name_ = name;
    tf.colors_ = std::move(colors);
    tf.opacity_ = std::move(opacity);
    tf.validate(where);
    return tf;
  } catch (const nlohmann::json::exception& e) {
    throw Error(where + ": malformed transfer function: " + jsonErrorText(e));
  }
}

TransferFunction TransferFunction::ramp(float start, float peak) {
  return TransferFunction({{0.0f, glm::vec3(0.0f)}, {1.0f, glm::vec3(1.0f)}},
                          {{0.0f, 0.0f}, {start, 0.0f}, {1.0f, peak}}, "ramp");
}

TransferTable::TransferTable(const TransferFunction& tf, float stepVoxels) : entries_(kSize + 1) {
  for (int i = 0; i < kSize; ++i) {
    glm::vec4 e = tf.evaluate(float(i) / float(kSize - 1));
    // Opacity correction for the sampling distance (Levoy; Engel et al., Real-Time Volume Graphics).
    e.a = e.a >= 1.0f ? 1.0f : 1.0f - std::pow(1.0f - e.a, stepVoxels);
    entries_[i] = e;
  }
  entries_[kSize] = entries_[kSize - 1];
  visibleBefore_.assign(kSize + 1, 0);
  for (int i = 0; i < kSize; ++i) {
    const bool visible = entries_[i].a > 0.0f;
    visibleBefore_[i + 1] = visibleBefore_[i] + (visible ? 1 : 0);
    visibleMask_[std::size_t(i / 64)] |= std::uint64_t(visible) << (i % 64);
  }
  minAlphaRuns_.emplace_back(kSize);
  for (int i = 0; i < kSize; ++i) minAlphaRuns_[0][std::size_t(i)] = entries_[std::size_t(i)].a;
  for (int len = 2; len <= kSize; len *= 2) {
    const std::vector<float>& half = minAlphaRuns_.back();
    std::vector<float> run(std::size_t(kSize - len + 1));
    for (std::size_t i = 0; i < run.size(); ++i) run[i] = std::min(half[i], half[i + std::size_t(len / 2)]);
    minAlphaRuns_.push_back(std::move(run));
  }
}

float TransferTable::minAlpha(float s0, float s1) const {
  if (entries_.empty() || !(s0 <= s1)) return 0.0f;
  const float f0 = std::max(s0 * float(kSize - 1), -1.0f), f1 = std::min(s1 * float(kSize - 1), float(kSize));
  const int i0 = std::clamp(int(std::floor(f0)) - 1, 0, kSize - 1);
  const int i1 = std::clamp(int(std::ceil(f1)) + 1, 0, kSize - 1);
  int level = 0;
  while ((2 << level) <= i1 - i0 + 1) ++level;
  const std::vector<float>& run = minAlphaRuns_[std::size_t(level)];
  return std::min(run[std::size_t(i0)], run[std::size_t(i1 - (1 << level) + 1)]);
}

bool TransferTable::anyVisible(float s0, float s1) const {
  if (entries_.empty()) return false;
  if (!(s0 <= s1)) return true;  // NaN or reversed: do not skip
  const float f0 = std::max(s0 * float(kSize - 1), -1.0f), f1 = std::min(s1 * float(kSize - 1), float(kSize));
  const int i0 = std::clamp(int(std::floor(f0)) - 1, 0, kSize - 1);
  const int i1 = std::clamp(int(std::ceil(f1)) + 1, 0, kSize - 1);
  return visibleBefore_[i1 + 1] - visibleBefore_[i0] > 0;
}

float TransferTable::maxAlpha(float s0, float s1) const {
  if (entries_.empty()) return 0.0f;
  if (s1 < s0) std::swap(s0, s1);
  const int i0 = std::clamp(int(std::floor(s0 * float(kSize - 1))), 0, kSize - 1);
  const int i1 = std::clamp(int(std::ceil(s1 * float(kSize - 1))), 0, kSize - 1);
  float m = 0.0f;
  for (int i = i0; i <= i1; ++i) m = std::max(m, entries_[i].a);
  return m;
}

}  // namespace kdswap
