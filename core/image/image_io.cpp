// Image files: format choice, premultiplied-alpha handling and atomic replacement here; the
// encoding itself in the OpenImageIO module (files_module/), loaded on first use.
#include "core/image/image_io.h"

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <dlfcn.h>
#include <filesystem>
#include <memory>
#include <mutex>
#include <unistd.h>

#include "core/util/error.h"

namespace kdswap {
namespace {

using WriteFn = int (*)(const char*, int, int, int, int, const float*, char*, std::size_t);
using ReadFn = int (*)(const char*, int*, int*, int*, float**, char*, std::size_t);

struct ImageFilesModule {
  WriteFn write = nullptr;
  ReadFn read = nullptr;
};

//! The module, loaded once per process. KDSWAP_IMAGE_MODULE (environment) overrides the path the
//! build placed it at.
const ImageFilesModule& imageFilesModule() {
  static ImageFilesModule module;
  static std::string failure;
  static std::once_flag once;
  std::call_once(once, [] {
    const char* override = std::getenv("KDSWAP_IMAGE_MODULE");
    const std::string path = override && *override ? override : KDSWAP_IMAGE_MODULE_PATH;
    void* handle = dlopen(path.c_str(), RTLD_NOW | RTLD_LOCAL);
    if (!handle) {
      const char* why = dlerror();
      failure = "cannot load the image file module " + path + ": " + (why ? why : "unknown error");
      return;
    }
    module.write = reinterpret_cast<WriteFn>(dlsym(handle, "kdswapWriteImageFile"));
    module.read = reinterpret_cast<ReadFn>(dlsym(handle, "kdswapReadImageFile"));
    if (!module.write || !module.read) failure = path + ": not a kdswap image file module";
  });
  if (!failure.empty()) throw Error(failure);
  return module;
}

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
  char why[512] = "";
  if (!imageFilesModule().write(temp.string().c_str(), w, h, channels, floatOut ? 1 : 0, pixels.data(), why,
                                sizeof why)) {
    std::error_code ignored;  // the temp file is ours; the error below is what matters
    std::filesystem::remove(temp, ignored);
    throw Error(path + ": " + why);
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
  int w = 0, h = 0, c = 0;
  float* pixels = nullptr;
  char why[512] = "";
  if (!imageFilesModule().read(path.c_str(), &w, &h, &c, &pixels, why, sizeof why)) throw Error(path + ": " + why);
  const std::unique_ptr<float, decltype(&std::free)> raw(pixels, &std::free);
  if (w < 1 || h < 1 || c < 1) throw Error(path + ": image has no pixels");
  Image img(Rect{0, 0, w, h});
  Rgba* dst = img.data();
  for (std::size_t i = 0; i < std::size_t(w) * h; ++i) {
    const float* s = raw.get() + i * std::size_t(c);
    const float gray = s[0];
    dst[i].r = gray;
    dst[i].g = c >= 3 ? s[1] : gray;
    dst[i].b = c >= 3 ? s[2] : gray;
    dst[i].a = c == 4 ? s[3] : (c == 2 ? s[1] : 1.0f);
  }
  return img;
}

}  // namespace kdswap
