// OpenImageIO glue: the only file that knows OIIO's API.
#include "core/image/image_io.h"

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <unistd.h>

#include <OpenImageIO/imageio.h>

#include "core/util/error.h"

namespace kdswap {
namespace {

std::string lowerExtension(const std::string& path) {
  std::string ext = std::filesystem::path(path).extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return char(std::tolower(c)); });
  return ext;
}

bool isFloatFormat(const std::string& ext) { return ext == ".exr"; }

}  // namespace

bool isSupportedImagePath(const std::string& path) {
  const std::string ext = lowerExtension(path);
  return ext == ".png" || ext == ".exr" || ext == ".tif" || ext == ".tiff" || ext == ".jpg" || ext == ".jpeg";
}

void writeImage(const std::string& path, const Image& image, const ImageWriteOptions& options) {
  if (!isSupportedImagePath(path))
    throw Error(path + ": unsupported image extension (expected .png, .exr, .tif, .tiff or .jpg)");
  if (image.empty()) throw Error(path + ": refusing to write an empty image");
  const std::string ext = lowerExtension(path);
  const bool floatOut = isFloatFormat(ext);
  const bool opaque = !floatOut && (options.background.has_value() || ext == ".jpg" || ext == ".jpeg");
  const glm::vec3 bg = options.background.value_or(glm::vec3(0.0f));

  const int w = image.width(), h = image.height();
  const int channels = opaque ? 3 : 4;
  std::vector<float> pixels(std::size_t(w) * h * channels);
  const Rgba* src = image.data();
  for (std::size_t i = 0; i < std::size_t(w) * h; ++i) {
    const Rgba& p = src[i];
    float* d = &pixels[i * channels];
    if (opaque) {
      d[0] = p.r + (1.0f - p.a) * bg.r;
      d[1] = p.g + (1.0f - p.a) * bg.g;
      d[2] = p.b + (1.0f - p.a) * bg.b;
    } else {
      d[0] = p.r, d[1] = p.g, d[2] = p.b, d[3] = p.a;
    }
  }

  // Write next to the target, then rename: a failed write never leaves a partial file.
  const std::filesystem::path target(path);
  const std::filesystem::path temp =
      target.parent_path() / (".kdswap-tmp-" + std::to_string(::getpid()) + "-" + target.filename().string());
  auto out = OIIO::ImageOutput::create(temp.string());
  if (!out) throw Error(path + ": OpenImageIO cannot write this format: " + OIIO::geterror());
  OIIO::ImageSpec spec(w, h, channels, floatOut ? OIIO::TypeDesc::HALF : OIIO::TypeDesc::UINT8);
  if (floatOut) spec.set_format(OIIO::TypeDesc::FLOAT);
  if (channels == 4) spec.alpha_channel = 3;
  if (!out->open(temp.string(), spec)) {
    const std::string why = out->geterror();
    throw Error(path + ": cannot open for writing: " + why);
  }
  const bool ok = out->write_image(OIIO::TypeDesc::FLOAT, pixels.data()) && out->close();
  if (!ok) {
    const std::string why = out->geterror();
    std::error_code ignored;  // the temp file is ours; the error below is what matters
    std::filesystem::remove(temp, ignored);
    throw Error(path + ": write failed: " + why);
  }
  std::error_code ec;
  std::filesystem::rename(temp, target, ec);
  if (ec) {
    std::error_code ignored;
    std::filesystem::remove(temp, ignored);
    throw Error(path + ": cannot move the finished image into place: " + ec.message());
  }
}

Image readImage(const std::string& path) {
  auto in = OIIO::ImageInput::open(path);
  if (!in) throw Error(path + ": cannot read image: " + OIIO::geterror());
  const OIIO::ImageSpec& spec = in->spec();
  const int w = spec.width, h = spec.height, c = spec.nchannels;
  std::vector<float> raw(std::size_t(w) * h * c);
  if (!in->read_image(0, 0, 0, c, OIIO::TypeDesc::FLOAT, raw.data())) {
    const std::string why = in->geterror();
    throw Error(path + ": read failed: " + why);
  }
  in->close();
  Image img(Rect{0, 0, w, h});
  Rgba* dst = img.data();
  for (std::size_t i = 0; i < std::size_t(w) * h; ++i) {
    const float* s = &raw[i * c];
    const float gray = s[0];
    dst[i].r = gray;
    dst[i].g = c >= 3 ? s[1] : gray;
    dst[i].b = c >= 3 ? s[2] : gray;
    dst[i].a = c == 4 ? s[3] : (c == 2 ? s[1] : 1.0f);
  }
  return img;
}

}  // namespace kdswap
