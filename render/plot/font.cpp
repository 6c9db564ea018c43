#include "render/plot/font.h"

#include "solver/common/errors.h"

#include <ft2build.h>
#include FT_FREETYPE_H
#include FT_BBOX_H
#include FT_OUTLINE_H
#include FT_TRUETYPE_TABLES_H

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <mutex>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

namespace simsols::plot {
namespace {

// Where distributions install DejaVu: Debian and Ubuntu (fonts-dejavu-core)
// first, then Fedora, Arch and others.
constexpr const char* kFontDirs[] = {"/usr/share/fonts/truetype/dejavu",
                                     "/usr/share/fonts/dejavu-sans-fonts",
                                     "/usr/share/fonts/dejavu", "/usr/share/fonts/TTF",
                                     "/usr/local/share/fonts"};
constexpr const char* kRegularFile = "DejaVuSans.ttf";
constexpr const char* kBoldFile = "DejaVuSans-Bold.ttf";

// Unhinted outlines: hinting would snap stems to whole pixels and change
// widths with the size, and text is placed at fractional positions anyway.
constexpr FT_Int32 kLoadFlags = FT_LOAD_NO_HINTING | FT_LOAD_NO_BITMAP;
constexpr double kMaxSize = 4096;
constexpr double kStemPerWeight = 0.085;  // em of stem width per unit of weight

std::string find_font(const char* name) {
  for (const char* dir : kFontDirs) {
    const std::filesystem::path p = std::filesystem::path(dir) / name;
    std::error_code ec;
    if (std::filesystem::is_regular_file(p, ec)) return p.string();
  }
  throw IoError(std::string("font file ") + kFontDirs[0] + "/" + name +
                           " not found (nor in the other standard font folders): install "
                           "Debian's package fonts-dejavu-core (apt-get install fonts-dejavu-core)");
}

// The FreeType library and the two faces, opened once. FreeType objects are
// not thread-safe, so every use holds `mutex`.
class Fonts {
 public:
  Fonts() {
    if (FT_Init_FreeType(&lib_) != 0) throw IoError("FreeType could not be initialised");
    try {
      regular_ = open(find_font(kRegularFile));
      try {
        bold_ = open(find_font(kBoldFile));
      } catch (const std::runtime_error&) {
        bold_ = nullptr;  // weights above 1.2 embolden the regular face instead
      }
    } catch (...) {
      FT_Done_FreeType(lib_);
      throw;
    }
    const double upem = regular_->units_per_EM;
    cap_em_ = cap_height_units(regular_) / upem;
    descent_em_ = -regular_->descender / upem;
  }
  ~Fonts() { FT_Done_FreeType(lib_); }  // closes the faces too
  Fonts(const Fonts&) = delete;
  Fonts& operator=(const Fonts&) = delete;

  std::mutex mutex;
  FT_Face regular() const { return regular_; }
  FT_Face bold() const { return bold_; }
  double cap_em() const { return cap_em_; }
  double descent_em() const { return descent_em_; }

  // Sets the face's em to size_px pixels (26.6 fixed point, 72 dpi: points
  // are pixels); call with `mutex` held.
  void set_size(FT_Face face, double size_px) {
    const auto size = static_cast<FT_F26Dot6>(std::lround(size_px * 64));
    FT_F26Dot6& current = face == bold_ ? bold_size_ : regular_size_;
    if (current == size) return;
    if (FT_Set_Char_Size(face, 0, size, 72, 72) != 0)
      throw IoError("FreeType cannot set the text size " + std::to_string(size_px));
    current = size;
  }

 private:
  FT_Face open(const std::string& path) {
    FT_Face face = nullptr;
    if (const FT_Error e = FT_New_Face(lib_, path.c_str(), 0, &face); e != 0)
      throw IoError("cannot read the font file " + path + " (FreeType error " +
                               std::to_string(e) + ")");
    return face;
  }

  // OS/2 sCapHeight where the table has it (version 2 and later), else the
  // height of "H" (DejaVu's table is version 1).
  static double cap_height_units(FT_Face face) {
    const auto* os2 = static_cast<const TT_OS2*>(FT_Get_Sfnt_Table(face, FT_SFNT_OS2));
    if (os2 && os2->version >= 2 && os2->sCapHeight > 0) return os2->sCapHeight;
    FT_BBox box{};
    if (FT_Load_Char(face, 'H', FT_LOAD_NO_SCALE | FT_LOAD_NO_HINTING) != 0 ||
        FT_Outline_Get_BBox(&face->glyph->outline, &box) != 0 || box.yMax <= 0)
      return 0.7 * face->units_per_EM;
    return static_cast<double>(box.yMax);
  }

  FT_Library lib_ = nullptr;
  FT_Face regular_ = nullptr, bold_ = nullptr;
  FT_F26Dot6 regular_size_ = -1, bold_size_ = -1;
  double cap_em_ = 0.7, descent_em_ = 0.2;
};

// Built on the first call (thread-safe); a failure throws and leaves it to
// the next call.
Fonts& fonts() {
  static Fonts f;
  return f;
}

// UTF-8 to code points; malformed sequences become U+FFFD.
std::u32string decode_utf8(std::string_view s) {
  std::u32string out;
  for (std::size_t i = 0; i < s.size();) {
    const auto b = static_cast<unsigned char>(s[i]);
    const int n = b < 0x80 ? 0 : (b >> 5) == 6 ? 1 : (b >> 4) == 14 ? 2 : (b >> 3) == 30 ? 3 : -1;
    char32_t c = n == 0 ? b : n == 1 ? (b & 0x1F) : n == 2 ? (b & 0x0F) : (b & 0x07);
    bool ok = n >= 0 && i + n < s.size();
    for (int k = 1; ok && k <= n; ++k) {
      if ((static_cast<unsigned char>(s[i + k]) & 0xC0) != 0x80)
        ok = false;
      else
        c = (c << 6) | (static_cast<unsigned char>(s[i + k]) & 0x3F);
    }
    out.push_back(ok ? c : 0xFFFD);
    i += ok ? n + 1 : 1;
  }
  return out;
}

// A string laid out along its baseline, in pixels from the first glyph's
// origin: where each glyph's origin goes and the extent of the ink.
struct PlacedGlyph {
  FT_UInt index;
  double pen;
};
struct Line {
  std::vector<PlacedGlyph> glyphs;
  double ink_lo = 0, ink_hi = 0;
  double width() const { return ink_hi - ink_lo; }
};

// Unhinted advances plus kerning; call with the mutex held and the size set.
Line lay_out(FT_Face face, const std::u32string& text) {
  Line line;
  double pen = 0;
  FT_UInt prev = 0;
  const bool kerning = FT_HAS_KERNING(face);
  for (char32_t c : text) {
    const FT_UInt index = FT_Get_Char_Index(face, c);  // 0: the missing-glyph box
    FT_Vector kern{0, 0};
    if (kerning && !line.glyphs.empty() &&
        FT_Get_Kerning(face, prev, index, FT_KERNING_UNFITTED, &kern) == 0)
      pen += kern.x / 64.0;
    prev = index;
    if (FT_Load_Glyph(face, index, kLoadFlags) != 0) continue;
    const FT_GlyphSlot g = face->glyph;
    const double advance = g->linearHoriAdvance / 65536.0;
    double lo = pen, hi = pen + advance;  // a space: its advance
    FT_BBox box{};
    if (g->outline.n_points > 0 && FT_Outline_Get_BBox(&g->outline, &box) == 0)
      lo = pen + box.xMin / 64.0, hi = pen + box.xMax / 64.0;
    line.ink_lo = line.glyphs.empty() ? lo : std::min(line.ink_lo, lo);
    line.ink_hi = line.glyphs.empty() ? hi : std::max(line.ink_hi, hi);
    line.glyphs.push_back({index, pen});
    pen += advance;
  }
  return line;
}

// One glyph's coverage: w x h bytes whose top-left pixel is (x, y).
struct Bitmap {
  int x = 0, y = 0, w = 0, h = 0;
  std::vector<std::uint8_t> cov;
};

// Renders the glyph in the face's slot with its origin at image point
// (gx, gy), turned a quarter turn counter-clockwise if asked.
std::optional<Bitmap> render_glyph(FT_Face face, double gx, double gy, bool rotate90,
                                   double embolden_px) {
  FT_Outline& o = face->glyph->outline;
  if (o.n_points == 0) return std::nullopt;
  if (embolden_px != 0) FT_Outline_Embolden(&o, static_cast<FT_Pos>(std::lround(embolden_px * 64)));
  if (rotate90) {
    FT_Matrix quarter{0, -0x10000, 0x10000, 0};  // (x, y) -> (-y, x), y up
    FT_Outline_Transform(&o, &quarter);
  }
  // FreeType's y runs up from the integer point (ix, iy); the fraction goes
  // into the outline, so glyphs sit at their exact positions.
  const double ix = std::floor(gx), iy = std::floor(gy);
  FT_Outline_Translate(&o, static_cast<FT_Pos>(std::lround((gx - ix) * 64)),
                       -static_cast<FT_Pos>(std::lround((gy - iy) * 64)));
  if (FT_Render_Glyph(face->glyph, FT_RENDER_MODE_NORMAL) != 0) return std::nullopt;
  const FT_Bitmap& b = face->glyph->bitmap;
  if (b.pixel_mode != FT_PIXEL_MODE_GRAY || b.width == 0 || b.rows == 0) return std::nullopt;
  Bitmap bm{static_cast<int>(ix) + face->glyph->bitmap_left,
            static_cast<int>(iy) - face->glyph->bitmap_top, static_cast<int>(b.width),
            static_cast<int>(b.rows), {}};
  bm.cov.resize(static_cast<std::size_t>(bm.w) * bm.h);
  const int pitch = std::abs(b.pitch);
  for (int r = 0; r < bm.h; ++r) {
    const int src = b.pitch > 0 ? r : bm.h - 1 - r;  // a negative pitch runs bottom-up
    std::copy_n(b.buffer + static_cast<std::size_t>(src) * pitch, bm.w, &bm.cov[r * bm.w]);
  }
  return bm;
}

// Sums the glyphs' coverage into one mask and blends it once.
void blend_coverage(Image& img, const std::vector<Bitmap>& maps, Color color) {
  if (maps.empty()) return;
  int x0 = img.width, y0 = img.height, x1 = 0, y1 = 0;
  for (const Bitmap& m : maps)
    x0 = std::min(x0, m.x), y0 = std::min(y0, m.y), x1 = std::max(x1, m.x + m.w),
    y1 = std::max(y1, m.y + m.h);
  x0 = std::max(x0, 0), y0 = std::max(y0, 0);
  x1 = std::min(x1, img.width), y1 = std::min(y1, img.height);
  if (x1 <= x0 || y1 <= y0) return;
  const int w = x1 - x0;
  std::vector<std::uint16_t> sum(static_cast<std::size_t>(w) * (y1 - y0), 0);
  for (const Bitmap& m : maps)
    for (int r = std::max(0, y0 - m.y); r < m.h && m.y + r < y1; ++r)
      for (int c = std::max(0, x0 - m.x); c < m.w && m.x + c < x1; ++c)
        sum[static_cast<std::size_t>(m.y + r - y0) * w + (m.x + c - x0)] += m.cov[r * m.w + c];
  for (int y = y0; y < y1; ++y)
    for (int x = x0; x < x1; ++x)
      if (const int s = sum[static_cast<std::size_t>(y - y0) * w + (x - x0)]; s > 0)
        blend_pixel(img, x, y, color, std::min(s, 255) / 255.0);
}

bool drawable_size(double size_px) { return size_px > 0 && size_px <= kMaxSize; }

}  // namespace

double text_width(std::string_view utf8, double size_px) {
  if (!drawable_size(size_px)) return 0;
  Fonts& f = fonts();
  const std::lock_guard lock(f.mutex);
  f.set_size(f.regular(), size_px);
  return lay_out(f.regular(), decode_utf8(utf8)).width();
}

double text_cap_height(double size_px) { return fonts().cap_em() * size_px; }
double text_descent(double size_px) { return fonts().descent_em() * size_px; }

std::string text_font_file(bool bold) { return find_font(bold ? kBoldFile : kRegularFile); }

double draw_text(Image& img, double x, double y, std::string_view utf8, double size_px, Color color,
                 Anchor anchor, bool rotate90, double weight) {
  if (!drawable_size(size_px) || !std::isfinite(x) || !std::isfinite(y)) return 0;
  Fonts& f = fonts();
  const std::lock_guard lock(f.mutex);
  weight = std::isfinite(weight) ? std::clamp(weight, 0.5, 3.0) : 1.0;
  FT_Face face = weight > 1.2 && f.bold() ? f.bold() : f.regular();
  const double embolden = face == f.bold() ? 0 : (weight - 1) * kStemPerWeight * size_px;
  f.set_size(face, size_px);
  const Line line = lay_out(face, decode_utf8(utf8));
  const double w = line.width();
  // The anchor: along the text from the pen origin, and above the baseline.
  const double along = line.ink_lo + (anchor.h == HAlign::left     ? 0
                                      : anchor.h == HAlign::center ? w / 2
                                                                   : w);
  const double cap = f.cap_em() * size_px, descent = f.descent_em() * size_px;
  const double up = anchor.v == VAlign::baseline ? 0
                    : anchor.v == VAlign::top    ? cap
                    : anchor.v == VAlign::middle ? cap / 2
                                                 : -descent;
  // Pen origin in the image; the text runs along +x, or up (-y) when rotated.
  const double ox = rotate90 ? x + up : x - along, oy = rotate90 ? y + along : y + up;
  constexpr double kFar = 1e7;  // keeps pixel coordinates in int range
  std::vector<Bitmap> maps;
  for (const PlacedGlyph& g : line.glyphs) {
    const double gx = rotate90 ? ox : ox + g.pen, gy = rotate90 ? oy - g.pen : oy;
    if (std::abs(gx) > kFar || std::abs(gy) > kFar) continue;
    if (FT_Load_Glyph(face, g.index, kLoadFlags) != 0) continue;
    if (auto bm = render_glyph(face, gx, gy, rotate90, embolden)) maps.push_back(std::move(*bm));
  }
  blend_coverage(img, maps, color);
  return w;
}

}  // namespace simsols::plot
