// PNG files for Image: charts of `simsols campaign`, renderer frames, and
// reading them back in tests. The codec is stb's (Debian libstb-dev:
// stb_image_write to encode, stb_image to decode); this file adapts it to
// Image and to the project's errors.
//
//   encode_png  8-bit RGBA, non-interlaced, zlib-compressed by stb.
//   decode_png  any PNG stb_image reads (8-bit grey, grey+alpha, RGB, RGBA,
//               palette, interlaced, 16-bit reduced to 8), as RGBA; anything
//               else is a std::runtime_error with stb's reason.
//   write_png   atomic (solver/common/atomic_file.h): the file appears whole
//               or not at all; IoError names the path.
#pragma once

#include <string>

#include "render/plot/image.h"

namespace simsols::plot {

std::string encode_png(const Image& img);
Image decode_png(const std::string& bytes);
void write_png(const Image& img, const std::string& path);
Image read_png(const std::string& path);

}  // namespace simsols::plot
