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
#include <string_view>
#include <unistd.h>

#include "core/util/error.h"
#include "core/util/file_writer.h"

namespace kdswap {
namespace {

using WriteFn = int (*)(const char*, int, int, int, int, const float*, char*, std::size_t);
using EncodeFn = int (*)(const char*, int, int, int, int, const float*, unsigned char**, std::size_t*, char*,
                         std::size_t);
using ReadFn = int (*)(const char*, int*, int*, int*, float**, char*, std::size_t);

struct ImageFilesModule {
  WriteFn write = nullptr;
  EncodeFn encode = nullptr;
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
    module.encode = reinterpret_cast<EncodeFn>(dlsym(handle, "kdswapEncodeImage"));
    module.read = reinterpret_cast<ReadFn>(dlsym(handle, "kdswapReadImageFile"));
    if (!module.write || !module.encode || !module.read) failure = path + ": not a kdswap image file module";
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

bool imageFormatHasAlpha(const std::string& path) {
  const std::string ext = lowerExtension(path);
  return isSupportedImagePath(path) && ext != ".jpg" && ext != ".jpeg";
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

  // Encoded in memory and written by writeFileAtomically, which checks every step (OpenImageIO's
  // PNG writer reports no error on a full disk); formats that cannot encode into memory are
  // written by OpenImageIO next to the target, read back whole, then renamed into place.
  char why[512] = "";
  unsigned char* bytes = nullptr;
  std::size_t size = 0;
  const ImageFilesModule& module = imageFilesModule();
  const int encoded = module.encode(path.c_str(), w, h, channels, floatOut ? 1 : 0, pixels.data(), &bytes, &size, why,
                                    sizeof why);
  if (encoded == 0) throw Error(path + ": " + why);
  if (encoded == 1) {
    const std::unique_ptr<unsigned char, decltype(&std::free)> owned(bytes, &std::free);
    writeFileAtomically(path, std::string_view(reinterpret_cast<const char*>(owned.get()), size));
    return;
  }
  if (std::filesystem::is_directory(path)) throw Error(path + ": is a directory, not a file to write");
  reportFileSizeLimitAsError();
  const std::filesystem::path target(path);
  const std::filesystem::path temp =
      target.parent_path() / (".kdswap-tmp-" + std::to_string(::getpid()) + "-" + target.filename().string());
  const auto removeTemp = [&] {
    std::error_code ignored;  // the temp file is ours; the error thrown is what matters
    std::filesystem::remove(temp, ignored);
  };
  if (!module.write(temp.string().c_str(), w, h, channels, floatOut ? 1 : 0, pixels.data(), why, sizeof why)) {
    removeTemp();
    throw Error(path + ": " + why);
  }
  int rw = 0, rh = 0, rc = 0;
  float* check = nullptr;
  const bool readable = module.read(temp.string().c_str(), &rw, &rh, &rc, &check, why, sizeof why);
  std::free(check);
  if (!readable || rw != w || rh != h) {
    removeTemp();
    throw Error(path + ": the written image does not read back (" + (readable ? "wrong size" : why) +
                "): is the disk full?");
  }
  std::error_code ec;
  std::filesystem::rename(temp, target, ec);
  if (ec) {
    removeTemp();
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
