// Checks what tests/gui/interaction.script did to kdswap-gui, from its --dump-state file and the
// pictures saved at each checkpoint: orbit, preview then refine, zoom, pan, R, a transfer-function
// drag, a stage cell's tooltip and enlargement, and partial redraw equal to a full one.
// Usage: kdswap-gui-check-interaction STATE.json
#include <cmath>
#include <cstdio>
#include <fstream>
#include <string>

#include <nlohmann/json.hpp>

#include "core/image/image_io.h"

namespace {

using nlohmann::json;

int failures = 0;

void check(bool ok, const std::string& what) {
  std::printf("%s: %s\n", ok ? "ok" : "FAILED", what.c_str());
  if (!ok) ++failures;
}

struct Difference {
  double mean = 0, max = 0;
  bool sameSize = false;
};

Difference compare(const std::string& a, const std::string& b) {
  const kdswap::Image x = kdswap::readImage(a), y = kdswap::readImage(b);
  Difference d;
  d.sameSize = x.width() == y.width() && x.height() == y.height();
  if (!d.sameSize) return d;
  for (int j = 0; j < x.height(); ++j)
    for (int i = 0; i < x.width(); ++i) {
      const kdswap::Rgba p = x.at(i, j), q = y.at(i, j);
      for (const double e : {double(p.r - q.r), double(p.g - q.g), double(p.b - q.b)}) {
        d.mean += std::abs(e);
        d.max = std::max(d.max, std::abs(e));
      }
    }
  d.mean /= 3.0 * double(x.width()) * double(x.height());
  return d;
}

// Fraction of the pixels inside rect [x, y, w, h] of a picture brighter than `level`.
double brightFraction(const std::string& png, const json& rect, float level) {
  const kdswap::Image shot = kdswap::readImage(png);
  long bright = 0, total = 0;
  for (int y = int(rect[1].get<float>()); y < int(rect[1].get<float>() + rect[3].get<float>()); ++y)
    for (int x = int(rect[0].get<float>()); x < int(rect[0].get<float>() + rect[2].get<float>()); ++x) {
      if (!shot.rect().contains(x, y)) continue;
      const kdswap::Rgba p = shot.at(x, y);
      ++total;
      bright += std::max({p.r, p.g, p.b}) > level;
    }
  return total ? double(bright) / double(total) : 0.0;
}

bool sameExcept(const json& a, const json& b, const std::string& field) {
  json x = a, y = b;
  x.erase(field);
  y.erase(field);
  return x == y;
}

std::string show(const json& j) { return j.dump(); }

// A full-quality frame of the current view and transfer function is on screen.
void checkSettled(const json& c, const std::string& name) {
  const json& f = c.at("frame");
  check(!f.is_null() && !f.at("preview").get<bool>() && f.at("width") == c.at("image")[0] && f.at("view_is_current").get<bool>() &&
            f.at("transfer_is_current").get<bool>(),
        name + ": the full-resolution frame of the current view is shown (" + show(f) + ")");
}

void checkDiffers(const json& a, const json& b, const std::string& what) {
  const Difference d = compare(a.at("frame_png"), b.at("frame_png"));
  char text[160];
  std::snprintf(text, sizeof text, " (mean difference %.4f)", d.mean);
  check(d.sameSize && d.mean > 0.002, what + text);
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 2) {
    std::fprintf(stderr, "usage: %s STATE.json\n", argv[0]);
    return 2;
  }
  try {
    std::ifstream in(argv[1]);
    if (!in) throw std::runtime_error(std::string(argv[1]) + ": cannot open");
    const json dump = json::parse(in);
    const json& cp = dump.at("checkpoints");
    for (const char* name : {"start", "dragging", "held", "orbit", "zoom", "pan", "reset", "tf", "hover", "enlarged"})
      if (!cp.contains(name)) throw std::runtime_error(std::string("checkpoint '") + name + "' missing: the script did not finish");
    const json &start = cp["start"], &dragging = cp["dragging"], &held = cp["held"], &orbit = cp["orbit"], &zoom = cp["zoom"],
               &pan = cp["pan"], &reset = cp["reset"], &tf = cp["tf"], &hover = cp["hover"], &enlarged = cp["enlarged"];
    const json& shown = dump.at("shown");

    checkSettled(start, "start");

    // Orbit with preview and refinement.
    const json& preview = dragging.at("frame");
    check(preview.at("preview").get<bool>() && preview.at("width").get<int>() < start.at("frame").at("width").get<int>(),
          "while dragging a lower-resolution preview is shown (" + show(preview) + ")");
    bool previewWhileDown = false, fullWhileDown = false;
    for (const json& f : shown) {
      previewWhileDown |= f.at("preview").get<bool>() && f.at("mouse_down").get<bool>();
      fullWhileDown |= !f.at("preview").get<bool>() && f.at("mouse_down").get<bool>();
    }
    check(previewWhileDown, "a preview arrived while the button was held");
    checkSettled(held, "held (mouse still, button down)");
    check(fullWhileDown, "holding the mouse still refined to a full frame before the button was released");
    const json &v0 = start.at("view"), &v1 = orbit.at("view");
    const double dAz = std::remainder(v1.at("azimuth").get<double>() - v0.at("azimuth").get<double>(), 360.0);
    const double dEl = v1.at("elevation").get<double>() - v0.at("elevation").get<double>();
    check(std::abs(dAz) > 5 && std::abs(dEl) > 5 && v1.at("distance") == v0.at("distance") && v1.at("pan") == v0.at("pan"),
          "left-drag orbits: azimuth " + show(v0["azimuth"]) + " -> " + show(v1["azimuth"]) + ", elevation " +
              show(v0["elevation"]) + " -> " + show(v1["elevation"]));
    checkSettled(orbit, "orbit, after release");
    checkDiffers(start, orbit, "the orbited image differs from the start");

    // Zoom and pan.
    const json& v2 = zoom.at("view");
    check(v2.at("distance").get<double>() < v1.at("distance").get<double>() && sameExcept(v1, v2, "distance"),
          "wheel zooms in: distance " + show(v1["distance"]) + " -> " + show(v2["distance"]));
    checkSettled(zoom, "zoom");
    checkDiffers(orbit, zoom, "the zoomed image differs");
    const json& v3 = pan.at("view");
    const double dPan = std::hypot(v3.at("pan")[0].get<double>() - v2.at("pan")[0].get<double>(),
                                   v3.at("pan")[1].get<double>() - v2.at("pan")[1].get<double>());
    check(dPan > 0.01 && sameExcept(v2, v3, "pan"), "right-drag pans: " + show(v2["pan"]) + " -> " + show(v3["pan"]));
    checkSettled(pan, "pan");
    checkDiffers(zoom, pan, "the panned image differs");

    // R restores the initial view and picture.
    check(reset.at("view") == start.at("view"), "R restores the initial view (" + show(reset["view"]) + ")");
    checkSettled(reset, "reset");
    const Difference back = compare(start.at("frame_png"), reset.at("frame_png"));
    check(back.sameSize && back.max <= 1.0 / 255.0 + 1e-6, "after R the image equals the initial one (max difference " +
                                                                std::to_string(back.max) + ")");

    // Transfer function: point 4 dragged up and right, nothing else changed.
    const json &before = reset.at("transfer").at("opacity"), &after = tf.at("transfer").at("opacity");
    bool othersKept = before.size() == after.size();
    for (std::size_t i = 0; othersKept && i < before.size(); ++i) othersKept = i == 4 || before[i] == after[i];
    check(othersKept && after[4][0].get<double>() > before[4][0].get<double>() &&
              after[4][1].get<double>() > before[4][1].get<double>() && tf.at("tf_edited").get<bool>(),
          "dragging opacity point 4 moved it: " + show(before[4]) + " -> " + show(after[4]));
    checkSettled(tf, "transfer function");
    checkDiffers(reset, tf, "the image with the edited transfer function differs");

    // Stage cells.
    const json& tip = hover.at("layout").at("tooltip");
    check(tip.at("node") == 3 && tip.at("phase") == 1 && tip.at("rect")[2].get<float>() > 20 && tip.at("rect")[3].get<float>() > 20,
          "hovering cell (3, 1) shows its tooltip at " + show(tip["rect"]));
    const double text = brightFraction(hover.at("window_png"), tip.at("rect"), 0.6f);
    check(text > 0.02, "the tooltip shows text (" + std::to_string(text * 100) + "% bright pixels)");
    json cell;
    for (const json& c : hover.at("layout").at("cells"))
      if (c.at("node") == 3 && c.at("phase") == 1) cell = c.at("rect");
    const json& big = enlarged.at("layout").at("enlarged");
    check(enlarged.at("selected") == json({{"node", 3}, {"phase", 1}}) && big.at("node") == 3 && big.at("phase") == 1 &&
              !cell.is_null() && big.at("rect")[2].get<float>() > 2 * cell[2].get<float>(),
          "clicking cell (3, 1) enlarges it: " + show(cell) + " -> " + show(big["rect"]));
    const double content = brightFraction(enlarged.at("window_png"), big.at("rect"), 0.22f);
    check(content > 0.02, "the enlarged cell shows the node's image (" + std::to_string(content * 100) + "% content pixels)");

    // Partial redraw.
    const json& redraw = dump.at("redraw");
    if (redraw.at("partial").get<bool>())
      check(redraw.at("verified_mismatched_pixels") == 0,
            "partial redraw equals a full redraw (" + show(redraw["verified_mismatched_pixels"]) + " pixels differ)");
    else
      std::printf("note: no GLX_MESA_copy_sub_buffer, whole frames are drawn; partial-redraw check skipped\n");
  } catch (const std::exception& e) {
    std::fprintf(stderr, "check_interaction: FAILED: %s\n", e.what());
    return 1;
  }
  std::printf("check_interaction: %s\n", failures ? "FAILED" : "OK");
  return failures ? 1 : 0;
}
