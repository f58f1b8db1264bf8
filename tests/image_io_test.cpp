// Image files round-trip through OpenImageIO (a module loaded on first use): PNG (8-bit) and EXR (float).
#include <doctest/doctest.h>

#include <unistd.h>

#include <algorithm>
#include <filesystem>

#include "core/image/image_io.h"
#include "test_files.h"
#include "core/util/error.h"

using namespace kdswap;

namespace {

Image gradientImage() {
  Image img(Rect{0, 0, 17, 9});
  for (int y = 0; y < 9; ++y)
    for (int x = 0; x < 17; ++x) {
      const float a = float(x) / 16.0f;
      img.at(x, y) = Rgba{0.8f * a, float(y) / 8.0f * a, 0.3f * a, a};
    }
  return img;
}

std::filesystem::path tempPath(const std::string& name) {
  const auto dir = std::filesystem::temp_directory_path() / ("kdswap-image-io-test-" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  return dir / name;
}

}  // namespace

TEST_CASE("EXR keeps premultiplied float RGBA exactly") {
  const Image img = gradientImage();
  const auto path = tempPath("round.exr");
  writeImage(path.string(), img);
  const Image back = readImage(path.string());
  REQUIRE(back.width() == 17);
  REQUIRE(back.height() == 9);
  CHECK(maxAbsDifference(img, back, img.rect()) <= 1e-6f);
}

TEST_CASE("PNG with alpha round-trips to 8-bit precision") {
  const Image img = gradientImage();
  const auto path = tempPath("round.png");
  ImageWriteOptions options;
  options.background.reset();
  writeImage(path.string(), img, options);
  const Image back = readImage(path.string());
  CHECK(maxAbsDifference(img, back, img.rect()) <= 2.0f / 255.0f);
}

TEST_CASE("PNG over a background is opaque and shows the background where the image is empty") {
  Image img(Rect{0, 0, 4, 1});
  img.at(3, 0) = Rgba{1.0f, 0.0f, 0.0f, 1.0f};
  const auto path = tempPath("bg.png");
  ImageWriteOptions options;
  options.background = glm::vec3(0.0f, 0.0f, 1.0f);
  writeImage(path.string(), img, options);
  const Image back = readImage(path.string());
  CHECK(back.at(0, 0).b == doctest::Approx(1.0f));
  CHECK(back.at(0, 0).a == doctest::Approx(1.0f));
  CHECK(back.at(3, 0).r == doctest::Approx(1.0f));
  CHECK(back.at(3, 0).b == doctest::Approx(0.0f));
}

TEST_CASE("writing into a missing folder fails with the path and leaves no file") {
  const Image img = gradientImage();
  CHECK_THROWS_WITH_AS(writeImage("/nonexistent-folder/x.png", img), doctest::Contains("/nonexistent-folder/x.png"), Error);
  CHECK_THROWS_WITH_AS(writeImage(tempPath("x.bmpx").string(), img), doctest::Contains("unsupported"), Error);
  CHECK_FALSE(std::filesystem::exists(tempPath("x.bmpx")));
}

TEST_CASE("the OpenImageIO module loads on first use; a missing module is a one-line error naming it") {
  const test::TempDir dir;
  const std::string out = dir.file("frame.png");
  CHECK(test::runKdswap("render --dataset phantom:24 --size 16x16 -q -o " + out).code == 0);
  CHECK(std::filesystem::exists(out));
  const test::Run noModule = test::runKdswap("render --dataset phantom:24 --size 16x16 -q -o " + dir.file("x.png"),
                                             "KDSWAP_IMAGE_MODULE=/nonexistent/mod.so");
  CHECK(noModule.code != 0);
  CHECK(noModule.err.find("cannot load the image file module /nonexistent/mod.so") != std::string::npos);
  CHECK(std::count(noModule.err.begin(), noModule.err.end(), '\n') == 1);
  CHECK(!std::filesystem::exists(dir.file("x.png")));
}
