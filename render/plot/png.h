// PNG files for Image: charts of `simsols campaign`, renderer frames, and
// reading them back in tests. Written from the PNG specification (ISO/IEC
// 15948) on top of zlib for deflate and CRC-32; nothing else.
//
//   encode_png  8-bit RGBA, non-interlaced: IHDR, one IDAT, IEND. Each row
//               gets the filter that minimises the sum of |bytes| (the
//               specification's heuristic) unless one filter is forced.
//   decode_png  8-bit greyscale, grey+alpha, RGB or RGBA, non-interlaced, all
//               five filter types; anything else is a std::runtime_error.
//   write_png   atomic: writes `path.tmp`, then renames it over `path`; on
//               failure removes the temporary file and throws
//               std::runtime_error naming the path.
#pragma once

#include <string>

#include "render/plot/image.h"

namespace simsols::plot {

enum class PngFilter { none = 0, sub = 1, up = 2, average = 3, paeth = 4, adaptive = 5 };

std::string encode_png(const Image& img, PngFilter filter = PngFilter::adaptive);
Image decode_png(const std::string& bytes);
void write_png(const Image& img, const std::string& path);
Image read_png(const std::string& path);

}  // namespace simsols::plot
