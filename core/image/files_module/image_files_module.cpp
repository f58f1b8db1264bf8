// The OpenImageIO glue, built as its own loadable module (libkdswap_image_files.so). OpenImageIO
// pulls in some 250 shared libraries whose start-up alone costs ~130 MB of resident memory and a
// noticeable delay; as a module they load on the first image read or write instead of in every
// process (peak memory is one of the benchmark's targets). A plain C interface: no C++ types or
// exceptions cross the boundary.
#include <cstdlib>
#include <cstring>
#include <string>

#include <vector>

#include <OpenImageIO/filesystem.h>
#include <OpenImageIO/imageio.h>

namespace {

int fail(const std::string& why, char* error, std::size_t errorSize) {
  if (errorSize > 0) {
    std::strncpy(error, why.c_str(), errorSize - 1);
    error[errorSize - 1] = '\0';
  }
  return 0;
}

}  // namespace

//! Writes interleaved float pixels (channels 3 or 4; alpha last) as 8-bit, or as float when
//! `floatOut`. Returns 1 on success, else 0 with a message in `error`.
extern "C" __attribute__((visibility("default"))) int kdswapWriteImageFile(const char* path, int width, int height,
                                                                           int channels, int floatOut,
                                                                           const float* pixels, char* error,
                                                                           std::size_t errorSize) {
  auto out = OIIO::ImageOutput::create(path);
  if (!out) return fail("OpenImageIO cannot write this format: " + OIIO::geterror(), error, errorSize);
  // The calling thread does the format conversion itself: kdswap schedules its own threads (oneTBB),
  // and a private OpenImageIO pool would only add threads still alive at exit.
  out->threads(1);
  OIIO::ImageSpec spec(width, height, channels, floatOut ? OIIO::TypeDesc::FLOAT : OIIO::TypeDesc::UINT8);
  if (channels == 4) spec.alpha_channel = 3;
  if (!out->open(path, spec)) return fail("cannot open for writing: " + out->geterror(), error, errorSize);
  if (!(out->write_image(OIIO::TypeDesc::FLOAT, pixels) && out->close()))
    return fail("write failed: " + out->geterror(), error, errorSize);
  return 1;
}

//! Encodes interleaved float pixels like kdswapWriteImageFile, in the format `path` names, into a
//! malloc'ed buffer (*bytes, *size; freed by the caller with free), so the caller writes and checks
//! the file itself: some writers (PNG) do not report a failed write, a full disk for one.
//! Returns 1 on success, 2 if this format cannot encode into memory (write the file instead),
//! else 0 with a message in `error`.
extern "C" __attribute__((visibility("default"))) int kdswapEncodeImage(const char* path, int width, int height,
                                                                        int channels, int floatOut,
                                                                        const float* pixels, unsigned char** bytes,
                                                                        std::size_t* size, char* error,
                                                                        std::size_t errorSize) {
  auto out = OIIO::ImageOutput::create(path);
  if (!out) return fail("OpenImageIO cannot write this format: " + OIIO::geterror(), error, errorSize);
  if (!out->supports("ioproxy")) return 2;
  out->threads(1);  // as for kdswapWriteImageFile
  std::vector<unsigned char> encoded;
  OIIO::Filesystem::IOVecOutput memory(encoded);
  if (!out->set_ioproxy(&memory)) return 2;
  OIIO::ImageSpec spec(width, height, channels, floatOut ? OIIO::TypeDesc::FLOAT : OIIO::TypeDesc::UINT8);
  if (channels == 4) spec.alpha_channel = 3;
  if (!out->open(path, spec)) return fail("cannot encode: " + out->geterror(), error, errorSize);
  if (!(out->write_image(OIIO::TypeDesc::FLOAT, pixels) && out->close()))
    return fail("encoding failed: " + out->geterror(), error, errorSize);
  if (encoded.empty()) return fail("encoding produced no bytes", error, errorSize);
  *bytes = static_cast<unsigned char*>(std::malloc(encoded.size()));
  if (!*bytes) return fail("out of memory for the encoded image", error, errorSize);
  std::memcpy(*bytes, encoded.data(), encoded.size());
  *size = encoded.size();
  return 1;
}

//! Reads an image as interleaved float pixels into a malloc'ed buffer (*pixels, freed by the
//! caller with free). Returns 1 on success, else 0 with a message in `error`.
extern "C" __attribute__((visibility("default"))) int kdswapReadImageFile(const char* path, int* width, int* height,
                                                                          int* channels, float** pixels, char* error,
                                                                          std::size_t errorSize) {
  auto in = OIIO::ImageInput::open(path);
  if (!in) return fail("cannot read image: " + OIIO::geterror(), error, errorSize);
  in->threads(1);  // as for writing
  const OIIO::ImageSpec& spec = in->spec();
  const std::size_t count = std::size_t(spec.width) * std::size_t(spec.height) * std::size_t(spec.nchannels);
  float* buffer = static_cast<float*>(std::malloc(count * sizeof(float)));
  if (!buffer) return fail("out of memory for a " + std::to_string(spec.width) + "x" + std::to_string(spec.height) + " image", error, errorSize);
  if (!in->read_image(0, 0, 0, spec.nchannels, OIIO::TypeDesc::FLOAT, buffer)) {
    std::free(buffer);
    return fail("read failed: " + in->geterror(), error, errorSize);
  }
  in->close();
  *width = spec.width;
  *height = spec.height;
  *channels = spec.nchannels;
  *pixels = buffer;
  return 1;
}
