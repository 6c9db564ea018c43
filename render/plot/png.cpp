#include "render/plot/png.h"

#include <stb_image.h>
#include <stb_image_write.h>

#include <fstream>
#include <iterator>
#include <limits>
#include <memory>
#include <stdexcept>

#include "solver/common/atomic_file.h"
#include "solver/common/errors.h"

namespace simsols::plot {
namespace {

// stb_image_write hands the encoded file over in pieces.
void append(void* context, void* data, int size) {
  static_cast<std::string*>(context)->append(static_cast<const char*>(data), static_cast<size_t>(size));
}

}  // namespace

std::string encode_png(const Image& img) {
  if (img.width <= 0 || img.height <= 0 ||
      img.rgba.size() != 4 * static_cast<size_t>(img.width) * static_cast<size_t>(img.height))
    throw std::logic_error("PNG: the image is empty or its pixels do not match its size");
  std::string out;
  if (!stbi_write_png_to_func(append, &out, img.width, img.height, 4, img.rgba.data(), 4 * img.width))
    throw IoError("PNG: encoding failed");
  return out;
}

Image decode_png(const std::string& bytes) {
  if (bytes.size() > static_cast<size_t>(std::numeric_limits<int>::max()))
    throw ReadError("PNG: file too large");
  int w = 0, h = 0, channels = 0;
  const std::unique_ptr<stbi_uc, void (*)(void*)> pixels(
      stbi_load_from_memory(reinterpret_cast<const stbi_uc*>(bytes.data()), static_cast<int>(bytes.size()),
                            &w, &h, &channels, 4),
      stbi_image_free);
  if (!pixels) throw ReadError(std::string("PNG: ") + stbi_failure_reason());
  Image img;
  img.width = w;
  img.height = h;
  img.rgba.assign(pixels.get(), pixels.get() + 4 * static_cast<size_t>(w) * static_cast<size_t>(h));
  return img;
}

void write_png(const Image& img, const std::string& path) {
  try {
    write_file_atomic(path, encode_png(img));
  } catch (const std::exception& e) {
    throw IoError("cannot write PNG '" + path + "': " + e.what());
  }
}

Image read_png(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw ReadError("cannot read PNG '" + path + "'");
  const std::string bytes{std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
  try {
    return decode_png(bytes);
  } catch (const std::runtime_error& e) {
    throw ReadError(std::string(e.what()) + " in '" + path + "'");
  }
}

}  // namespace simsols::plot
