// Image files through OpenImageIO: PNG (8-bit), EXR (float RGBA) or TIFF, chosen by extension.
#pragma once

#include <optional>
#include <string>

#include <glm/vec3.hpp>

#include "core/image/image.h"

namespace kdswap {

struct ImageWriteOptions {
  //! For 8-bit formats: composite over this colour and write opaque RGB. Empty: write RGBA.
  //! Float formats (EXR) always keep premultiplied RGBA.
  std::optional<glm::vec3> background = glm::vec3(0.0f);
};

//! Writes `image` (its rect is taken as the whole frame) to `path`. The file appears whole or not
//! at all: it is written beside the target and renamed. Throws kdswap::Error naming the path.
void writeImage(const std::string& path, const Image& image, const ImageWriteOptions& options = {});

//! Reads an image as premultiplied RGBA float with rect (0, 0, w, h). Throws kdswap::Error.
Image readImage(const std::string& path);

//! True when `path` ends in an extension writeImage understands (.png .exr .tif .tiff .jpg).
bool isSupportedImagePath(const std::string& path);

//! True when the format of `path` keeps an alpha channel (.png .exr .tif .tiff; not .jpg).
bool imageFormatHasAlpha(const std::string& path);

}  // namespace kdswap
