// Checks a kdswap-gui screenshot against the layout the app reported: the viewport shows a
// rendered volume (not just background), and the stages grid has the expected columns x rows,
// each cell drawn with visible content. Usage: kdswap-gui-check SHOT.png LAYOUT.json COLUMNS ROWS
#include <cstdio>
#include <fstream>
#include <set>
#include <string>

#include <nlohmann/json.hpp>

#include "core/image/image_io.h"
#include "core/util/error.h"

namespace {

// A pixel is content when it is clearly brighter than the app's dark backgrounds (<= ~0.12).
constexpr float kContentLevel = 0.22f;

struct Counts {
  long content = 0, total = 0;
};

Counts countContent(const kdswap::Image& shot, const nlohmann::json& rect) {
  const int x0 = int(rect[0].get<float>() + 0.5f), y0 = int(rect[1].get<float>() + 0.5f);
  const int w = int(rect[2].get<float>()), h = int(rect[3].get<float>());
  Counts c;
  for (int y = y0; y < y0 + h; ++y)
    for (int x = x0; x < x0 + w; ++x) {
      if (!shot.rect().contains(x, y)) continue;
      const kdswap::Rgba p = shot.at(x, y);
      ++c.total;
      if (std::max({p.r, p.g, p.b}) > kContentLevel) ++c.content;
    }
  return c;
}

int fail(const std::string& message) {
  std::fprintf(stderr, "check_screenshot: FAILED: %s\n", message.c_str());
  return 1;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 5) {
    std::fprintf(stderr, "usage: %s SHOT.png LAYOUT.json COLUMNS ROWS\n", argv[0]);
    return 2;
  }
  try {
    const kdswap::Image shot = kdswap::readImage(argv[1]);
    std::ifstream in(argv[2]);
    if (!in) return fail(std::string(argv[2]) + ": cannot open");
    const nlohmann::json layout = nlohmann::json::parse(in);
    const int columns = std::stoi(argv[3]), rows = std::stoi(argv[4]);

    const Counts view = countContent(shot, layout.at("viewport"));
    std::printf("viewport: %ld of %ld pixels show content\n", view.content, view.total);
    if (view.total < 10000) return fail("viewport is missing or tiny");
    if (view.content < view.total / 50) return fail("viewport is (nearly) blank: under 2% content pixels");

    const nlohmann::json& stages = layout.at("stages");
    if (stages.at("columns") != columns || stages.at("rows") != rows)
      return fail("stages grid is " + stages.at("columns").dump() + " x " + stages.at("rows").dump() + ", expected " +
                  std::to_string(columns) + " x " + std::to_string(rows));
    std::set<std::pair<int, int>> seen;
    std::set<float> xs, ys;
    long emptyCells = 0;
    for (const nlohmann::json& cell : stages.at("cells")) {
      seen.insert({cell.at("node").get<int>(), cell.at("phase").get<int>()});
      xs.insert(cell.at("rect")[0].get<float>());
      ys.insert(cell.at("rect")[1].get<float>());
      const Counts c = countContent(shot, cell.at("rect"));
      if (c.total < 16 || c.content == 0) ++emptyCells;
    }
    std::printf("stages: %zu cells in %zu columns x %zu rows, %ld without content\n", seen.size(), xs.size(), ys.size(),
                emptyCells);
    if (int(seen.size()) != columns * rows) return fail("expected " + std::to_string(columns * rows) + " distinct cells");
    if (int(xs.size()) != columns || int(ys.size()) != rows) return fail("cells are not laid out as a grid");
    if (emptyCells > 0) return fail(std::to_string(emptyCells) + " stage cells show nothing");
    std::printf("check_screenshot: OK\n");
    return 0;
  } catch (const std::exception& e) {
    return fail(e.what());
  }
}
