// compare_images A B TOLERANCE: exit 0 if the images have the same size and max |A - B| over
// premultiplied RGBA is <= TOLERANCE; 1 otherwise (and writes A's name + ".diff.exr"); 2 on error.
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>

#include "core/image/image_io.h"
#include "core/util/error.h"

int main(int argc, char** argv) {
  if (argc != 4) {
    std::fprintf(stderr, "usage: compare_images A B TOLERANCE\n");
    return 2;
  }
  try {
    const kdswap::Image a = kdswap::readImage(argv[1]);
    const kdswap::Image b = kdswap::readImage(argv[2]);
    const float tolerance = std::strtof(argv[3], nullptr);
    if (a.rect().w != b.rect().w || a.rect().h != b.rect().h) {
      std::printf("compare_images: %s is %dx%d but %s is %dx%d\n", argv[1], a.rect().w, a.rect().h, argv[2],
                  b.rect().w, b.rect().h);
      return 1;
    }
    const float diff = kdswap::maxAbsDifference(a, b, a.rect());
    const bool same = diff <= tolerance;
    std::printf("compare_images: max |%s - %s| = %.3g (tolerance %.3g): %s\n", argv[1], argv[2], diff, tolerance,
                same ? "OK" : "DIFFERENT");
    if (!same) {
      kdswap::Image d(a.rect());
      for (int y = 0; y < a.rect().h; ++y)
        for (int x = 0; x < a.rect().w; ++x) {
          const kdswap::Rgba pa = a.sample(x, y), pb = b.sample(x, y);
          d.at(x, y) = {std::fabs(pa.r - pb.r), std::fabs(pa.g - pb.g), std::fabs(pa.b - pb.b), std::fabs(pa.a - pb.a)};
        }
      kdswap::writeImage(std::string(argv[1]) + ".diff.exr", d);
    }
    return same ? 0 : 1;
  } catch (const kdswap::Error& e) {
    std::fprintf(stderr, "compare_images: %s\n", e.what());
    return 2;
  }
}
