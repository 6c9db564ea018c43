#include "render/plot/png.h"

#include "solver/common/errors.h"

#include <zlib.h>

#include <array>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <stdexcept>

namespace simsols::plot {
namespace {

constexpr std::array<unsigned char, 8> kSignature = {137, 80, 78, 71, 13, 10, 26, 10};

void put_u32(std::string& out, std::uint32_t v) {
  for (int s = 24; s >= 0; s -= 8) out.push_back(static_cast<char>((v >> s) & 0xFF));
}

std::uint32_t get_u32(const std::string& in, std::size_t at) {
  std::uint32_t v = 0;
  for (int i = 0; i < 4; ++i) v = (v << 8) | static_cast<unsigned char>(in[at + i]);
  return v;
}

// length, type, data, CRC-32 of type + data
void put_chunk(std::string& out, const char* type, const std::string& data) {
  put_u32(out, static_cast<std::uint32_t>(data.size()));
  const std::size_t start = out.size();
  out.append(type, 4);
  out += data;
  const auto* p = reinterpret_cast<const Bytef*>(out.data() + start);
  put_u32(out, static_cast<std::uint32_t>(crc32(0L, p, static_cast<uInt>(4 + data.size()))));
}

int paeth(int a, int b, int c) {
  const int p = a + b - c, pa = std::abs(p - a), pb = std::abs(p - b), pc = std::abs(p - c);
  if (pa <= pb && pa <= pc) return a;
  return pb <= pc ? b : c;
}

// Predictor of filter type `f` for byte i of a row (bpp bytes per pixel);
// `prev` is the previous unfiltered row (zeros for the first).
int predict(int f, const unsigned char* row, const unsigned char* prev, std::size_t i,
            std::size_t bpp) {
  const int a = i >= bpp ? row[i - bpp] : 0, b = prev[i], c = i >= bpp ? prev[i - bpp] : 0;
  switch (f) {
    case 1:
      return a;
    case 2:
      return b;
    case 3:
      return (a + b) / 2;
    case 4:
      return paeth(a, b, c);
    default:
      return 0;
  }
}

[[noreturn]] void bad(const std::string& why) { throw std::runtime_error("PNG: " + why); }

}  // namespace

std::string encode_png(const Image& img, PngFilter filter) {
  if (img.width <= 0 || img.height <= 0 ||
      img.rgba.size() != static_cast<std::size_t>(img.width) * img.height * 4)
    throw std::invalid_argument("encode_png: image size and pixel buffer disagree");
  const std::size_t stride = static_cast<std::size_t>(img.width) * 4;
  std::string raw;
  raw.reserve((stride + 1) * img.height);
  const std::vector<unsigned char> zeros(stride, 0);
  std::string best, trial(stride, '\0');
  for (int y = 0; y < img.height; ++y) {
    const unsigned char* row = img.rgba.data() + y * stride;
    const unsigned char* prev = y > 0 ? row - stride : zeros.data();
    long best_cost = -1;
    int best_f = 0;
    const int f0 = filter == PngFilter::adaptive ? 0 : static_cast<int>(filter);
    const int f1 = filter == PngFilter::adaptive ? 4 : f0;
    for (int f = f0; f <= f1; ++f) {
      long cost = 0;
      for (std::size_t i = 0; i < stride; ++i) {
        const auto v = static_cast<unsigned char>(row[i] - predict(f, row, prev, i, 4));
        trial[i] = static_cast<char>(v);
        cost += v < 128 ? v : 256 - v;  // bytes as signed magnitudes
      }
      if (best_cost < 0 || cost < best_cost) best_cost = cost, best_f = f, best = trial;
    }
    raw.push_back(static_cast<char>(best_f));
    raw += best;
  }
  uLongf zlen = compressBound(static_cast<uLong>(raw.size()));
  std::string z(zlen, '\0');
  if (compress2(reinterpret_cast<Bytef*>(z.data()), &zlen,
                reinterpret_cast<const Bytef*>(raw.data()), static_cast<uLong>(raw.size()),
                6) != Z_OK)
    throw std::runtime_error("encode_png: zlib compression failed");
  z.resize(zlen);

  std::string ihdr;
  put_u32(ihdr, static_cast<std::uint32_t>(img.width));
  put_u32(ihdr, static_cast<std::uint32_t>(img.height));
  ihdr += std::string{8, 6, 0, 0, 0};  // depth 8, RGBA, deflate, filter set 0, no interlace
  std::string out(kSignature.begin(), kSignature.end());
  put_chunk(out, "IHDR", ihdr);
  put_chunk(out, "IDAT", z);
  put_chunk(out, "IEND", "");
  return out;
}

namespace {

struct PngHeader {
  std::uint32_t width = 0, height = 0;
  int channels = 0;  // 1 grey, 2 grey + alpha, 3 RGB, 4 RGBA
};

// The IHDR chunk's fields at `data` (8-bit, not interlaced, no palette).
PngHeader read_header(const std::string& in, std::size_t data, std::uint32_t len) {
  if (len != 13) bad("bad IHDR");
  PngHeader h;
  h.width = get_u32(in, data);
  h.height = get_u32(in, data + 4);
  const int depth = static_cast<unsigned char>(in[data + 8]);
  const int color = static_cast<unsigned char>(in[data + 9]);
  if (depth != 8) bad("only 8-bit samples are supported");
  switch (color) {
    case 0: h.channels = 1; break;
    case 2: h.channels = 3; break;
    case 4: h.channels = 2; break;
    case 6: h.channels = 4; break;
    default: bad("palette images are not supported");
  }
  if (in[data + 10] != 0 || in[data + 11] != 0) bad("unknown compression or filter method");
  if (in[data + 12] != 0) bad("interlaced images are not supported");
  if (h.width == 0 || h.height == 0 || h.width > 32768 || h.height > 32768 ||
      std::uint64_t{h.width} * h.height > (1u << 28))
    bad("bad image size");
  return h;
}

// Undoes the row filters of the inflated data and expands to RGBA.
Image unfilter(std::vector<unsigned char>& raw, const PngHeader& h) {
  const std::size_t width = h.width, height = h.height, bpp = h.channels, stride = width * bpp;
  Image img{static_cast<int>(width), static_cast<int>(height),
            std::vector<std::uint8_t>(width * height * 4)};
  const std::vector<unsigned char> zeros(stride, 0);
  for (std::size_t y = 0; y < height; ++y) {
    unsigned char* row = raw.data() + y * (stride + 1) + 1;
    const unsigned char* prev = y > 0 ? row - stride - 1 : zeros.data();
    const int f = row[-1];
    if (f > 4) bad("unknown filter type");
    for (std::size_t i = 0; i < stride; ++i)
      row[i] = static_cast<unsigned char>(row[i] + predict(f, row, prev, i, bpp));
    for (std::size_t x = 0; x < width; ++x) {
      const unsigned char* s = row + x * bpp;
      std::uint8_t* d = &img.rgba[(y * width + x) * 4];
      const bool grey = h.channels < 3;
      d[0] = s[0];
      d[1] = grey ? s[0] : s[1];
      d[2] = grey ? s[0] : s[2];
      d[3] = h.channels == 4 ? s[3] : h.channels == 2 ? s[1] : 255;
    }
  }
  return img;
}

}  // namespace

Image decode_png(const std::string& in) {
  if (in.size() < 8 || !std::equal(kSignature.begin(), kSignature.end(),
                                   reinterpret_cast<const unsigned char*>(in.data())))
    bad("not a PNG file (bad signature)");
  std::size_t at = 8;
  PngHeader header;
  std::string idat;
  bool have_header = false, ended = false;
  while (!ended) {
    if (at + 12 > in.size()) bad("truncated chunk");
    const std::uint32_t len = get_u32(in, at);
    if (len > in.size() - at - 12) bad("truncated chunk");
    const std::string type = in.substr(at + 4, 4);
    const auto* p = reinterpret_cast<const Bytef*>(in.data() + at + 4);
    if (crc32(0L, p, len + 4) != get_u32(in, at + 8 + len)) bad("CRC mismatch in " + type);
    const std::size_t data = at + 8;
    if (type == "IHDR") {
      header = read_header(in, data, len);
      have_header = true;
    } else if (type == "IDAT") {
      idat.append(in, data, len);
    } else if (type == "IEND") {
      ended = true;
    } else if (!(type[0] & 0x20)) {
      bad("unknown critical chunk " + type);
    }
    at += 12 + len;
  }
  if (!have_header) bad("missing IHDR");
  std::vector<unsigned char> raw((std::size_t{header.width} * header.channels + 1) * header.height);
  uLongf rawlen = static_cast<uLongf>(raw.size());
  if (uncompress(raw.data(), &rawlen, reinterpret_cast<const Bytef*>(idat.data()),
                 static_cast<uLong>(idat.size())) != Z_OK ||
      rawlen != raw.size())
    bad("corrupt or short image data");
  return unfilter(raw, header);
}

void write_png(const Image& img, const std::string& path) {
  const std::string bytes = encode_png(img);
  const std::string tmp = path + ".tmp";
  std::string why;
  {
    std::ofstream out(tmp, std::ios::binary | std::ios::trunc);
    if (!out) {
      why = "cannot create " + tmp;
    } else {
      out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
      out.close();
      if (!out) why = "write failed";
    }
  }
  std::error_code ec;
  if (why.empty()) {
    std::filesystem::rename(tmp, path, ec);
    if (ec) why = "rename failed: " + ec.message();
  }
  if (!why.empty()) {
    std::filesystem::remove(tmp, ec);
    throw IoError("cannot write PNG '" + path + "': " + why);
  }
}

Image read_png(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw std::runtime_error("cannot read PNG '" + path + "'");
  const std::string bytes{std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
  try {
    return decode_png(bytes);
  } catch (const std::runtime_error& e) {
    throw std::runtime_error(std::string(e.what()) + " in '" + path + "'");
  }
}

}  // namespace simsols::plot
