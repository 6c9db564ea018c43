#include "render/plot/font.h"

#include <array>
#include <charconv>
#include <cmath>
#include <numbers>
#include <string>
#include <unordered_map>
#include <vector>

namespace simsols::plot {
namespace {

// Glyph outlines: strokes separated by ';'. A stroke is a sequence of points
// "x,y" and elliptical arcs "(cx,cy,rx,ry,a0,a1)" (degrees, counter-clockwise
// from +x, y up; a1 < a0 runs clockwise), joined in order into one polyline.
// `width` is the ink width; glyphs start at x = 0.
struct GlyphDef {
  char32_t code;
  double width;
  const char* strokes;
};

constexpr GlyphDef kGlyphs[] = {
    {U' ', 1.2, ""},
    {U'!', 0, "0,10 0,3; 0,0 0,0.3"},
    {U'"', 2, "0,10 0,7.5; 2,10 2,7.5"},
    {U'#', 6.5, "1.5,0 2.5,10; 4,0 5,10; 0,3.3 6,3.3; 0.5,6.7 6.5,6.7"},
    {U'$', 6, "(3,7,2.8,2,20,270) (3,3,3,2,90,-160); 3,11 3,-1"},
    {U'%', 7, "0.5,0 6.5,10; (1.4,8.3,1.4,1.7,0,360); (5.6,1.7,1.4,1.7,0,360)"},
    {U'&', 7, "7,0 1.3,6.6 (2.6,8.4,1.4,1.6,230,-40) 0.6,3 (2.7,2.5,2.4,2.5,160,330) 6.5,4.5"},
    {U'\'', 0, "0,10 0,7.5"},
    {U'(', 2, "(3.5,4,3.5,7,120,240)"},
    {U')', 2, "(-1.5,4,3.5,7,60,-60)"},
    {U'*', 5, "2.5,10 2.5,5; 0.3,8.9 4.7,6.1; 0.3,6.1 4.7,8.9"},
    {U'+', 6, "0,4 6,4; 3,1 3,7"},
    {U',', 1, "1,0.6 1,0 0,-2"},
    {U'-', 4, "0,4 4,4"},
    {U'.', 0, "0,0 0,0.3"},
    {U'/', 4, "0,-1 4,10"},
    {U':', 0, "0,0 0,0.3; 0,6.7 0,7"},
    {U';', 1, "1,6.7 1,7; 1,0.6 1,0 0,-2"},
    {U'<', 6, "6,7 0,4 6,1"},
    {U'=', 6, "0,5.5 6,5.5; 0,2.5 6,2.5"},
    {U'>', 6, "0,7 6,4 0,1"},
    {U'?', 5.5, "(2.75,7.5,2.75,2.5,160,-70) 2.75,3; 2.75,0 2.75,0.3"},
    {U'@', 8,
     "6,6.5 6,3.2 (7,3.2,1,1.2,180,360) 8,4.5 (4,4.5,4,5.5,0,300); "
     "(4.2,4.8,1.8,2,0,360)"},
    {U'A', 7, "0,0 3.5,10 7,0; 1.4,3.5 5.6,3.5"},
    {U'B', 6.5, "0,0 0,10 3.5,10 (3.5,7.5,2.5,2.5,90,-90) 0,5; 3.8,5 (3.8,2.5,2.7,2.5,90,-90) 0,0"},
    {U'C', 6.5, "(3.5,5,3.5,5,45,315)"},
    {U'D', 6.5, "0,0 0,10 2.5,10 (2.5,5,4,5,90,-90) 0,0"},
    {U'E', 5.5, "5.5,10 0,10 0,0 5.5,0; 0,5 4.5,5"},
    {U'F', 5.5, "5.5,10 0,10 0,0; 0,5 4.5,5"},
    {U'G', 7, "(3.5,5,3.5,5,45,360) 4,5"},
    {U'H', 6, "0,0 0,10; 6,0 6,10; 0,5 6,5"},
    {U'I', 3, "1.5,0 1.5,10; 0,10 3,10; 0,0 3,0"},
    {U'J', 5, "5,10 5,3 (2.5,3,2.5,3,0,-180)"},
    {U'K', 6, "0,0 0,10; 6,10 0,3.5; 2,5.4 6,0"},
    {U'L', 5.5, "0,10 0,0 5.5,0"},
    {U'M', 7.5, "0,0 0,10 3.75,2.5 7.5,10 7.5,0"},
    {U'N', 6, "0,0 0,10 6,0 6,10"},
    {U'O', 7, "(3.5,5,3.5,5,0,360)"},
    {U'P', 6, "0,0 0,10 3.5,10 (3.5,7.25,2.5,2.75,90,-90) 0,4.5"},
    {U'Q', 7, "(3.5,5,3.5,5,0,360); 4.2,2.8 7.2,-0.5"},
    {U'R', 6, "0,0 0,10 3.5,10 (3.5,7.25,2.5,2.75,90,-90) 0,4.5; 3.5,4.5 6,0"},
    {U'S', 6, "(3,7.5,2.8,2.5,20,270) (3,2.5,3,2.5,90,-160)"},
    {U'T', 6, "0,10 6,10; 3,10 3,0"},
    {U'U', 6, "0,10 0,3 (3,3,3,3,180,360) 6,10"},
    {U'V', 6.5, "0,10 3.25,0 6.5,10"},
    {U'W', 9, "0,10 2,0 4.5,8 7,0 9,10"},
    {U'X', 6, "0,0 6,10; 0,10 6,0"},
    {U'Y', 6, "0,10 3,5 6,10; 3,5 3,0"},
    {U'Z', 6, "0,10 6,10 0,0 6,0"},
    {U'[', 2.5, "2.5,11 0,11 0,-2 2.5,-2"},
    {U'\\', 4, "0,10 4,-1"},
    {U']', 2.5, "0,11 2.5,11 2.5,-2 0,-2"},
    {U'^', 5, "0,6 2.5,10 5,6"},
    {U'_', 6, "0,-2 6,-2"},
    {U'`', 1.5, "0,10 1.5,8"},
    {U'a', 5.5, "(2.75,3.5,2.75,3.5,0,360); 5.5,7 5.5,0"},
    {U'b', 5.5, "0,10 0,0; (2.75,3.5,2.75,3.5,0,360)"},
    {U'c', 5.2, "(2.9,3.5,2.9,3.5,40,320)"},
    {U'd', 5.5, "(2.75,3.5,2.75,3.5,0,360); 5.5,10 5.5,0"},
    {U'e', 5.5, "0,3.5 5.5,3.5 (2.75,3.5,2.75,3.5,0,315)"},
    {U'f', 4, "(3.2,8.5,1.6,1.5,30,180) 1.6,0; 0,7 4,7"},
    {U'g', 5.5, "(2.75,3.5,2.75,3.5,0,360); 5.5,7 5.5,-1 (2.75,-1,2.75,2,0,-150)"},
    {U'h', 5.5, "0,10 0,0; (2.75,4.25,2.75,2.75,180,0) 5.5,0"},
    {U'i', 0, "0,0 0,7; 0,9.3 0,9.6"},
    {U'j', 2, "2,7 2,-1.5 (0.5,-1.5,1.5,1.5,0,-150); 2,9.3 2,9.6"},
    {U'k', 5, "0,0 0,10; 5,7 0,2.5; 1.8,4 5.2,0"},
    {U'l', 1.7, "0.5,10 0.5,1.2 (1.7,1.2,1.2,1.2,180,270)"},
    {U'm', 8, "0,0 0,7; (2,5,2,2,180,0) 4,0; (6,5,2,2,180,0) 8,0"},
    {U'n', 5.5, "0,0 0,7; (2.75,4.25,2.75,2.75,180,0) 5.5,0"},
    {U'o', 5.8, "(2.9,3.5,2.9,3.5,0,360)"},
    {U'p', 5.5, "0,7 0,-3; (2.75,3.5,2.75,3.5,0,360)"},
    {U'q', 5.5, "(2.75,3.5,2.75,3.5,0,360); 5.5,7 5.5,-3"},
    {U'r', 4.3, "0,0 0,7; (3.2,4.2,3.2,2.8,180,70)"},
    {U's', 5.2, "(2.6,5.25,2.4,1.75,20,270) (2.6,1.75,2.6,1.75,90,-160)"},
    {U't', 3.8, "1.5,9.5 1.5,1.2 (2.7,1.2,1.2,1.2,180,270) 3.8,0; 0,7 3.8,7"},
    {U'u', 5.5, "0,7 0,2.75 (2.75,2.75,2.75,2.75,180,360); 5.5,7 5.5,0"},
    {U'v', 5.5, "0,7 2.75,0 5.5,7"},
    {U'w', 8, "0,7 2,0 4,5.5 6,0 8,7"},
    {U'x', 5.5, "0,0 5.5,7; 0,7 5.5,0"},
    {U'y', 5.5, "0,7 2.75,0; 5.5,7 2.75,0 1.6,-2.6 0.5,-3"},
    {U'z', 5.5, "0,7 5.5,7 0,0 5.5,0"},
    {U'{', 3, "3,11 1.8,10.4 1.5,9 1.5,6 0,4.5 1.5,3 1.5,0 1.8,-1.4 3,-2"},
    {U'|', 0, "0,11 0,-2"},
    {U'}', 3, "0,11 1.2,10.4 1.5,9 1.5,6 3,4.5 1.5,3 1.5,0 1.2,-1.4 0,-2"},
    {U'~', 6, "(1.5,3.8,1.5,1,180,0) (4.5,3.8,1.5,1,180,360)"},
    {U'0', 5.5, "(2.75,5,2.75,5,0,360)"},
    {U'1', 5.5, "1.2,8 3,10 3,0"},
    {U'2', 5.5, "(2.75,7.25,2.75,2.75,160,-35) 0,0 5.5,0"},
    {U'3', 5.5, "(2.75,7.6,2.5,2.4,150,-90) (2.75,2.6,2.75,2.6,90,-150)"},
    {U'4', 5.5, "4,0 4,10 0,3 5.5,3"},
    {U'5', 5.5, "5.2,10 0.6,10 0.3,5.4 (2.75,3.2,2.75,3.2,140,-150)"},
    {U'6', 5.5, "(2.75,3,2.75,3,0,360); (5.5,3,5.5,7,180,105)"},
    {U'7', 5.5, "0,10 5.5,10 1.8,0"},
    {U'8', 5.5, "(2.75,7.6,2.4,2.4,0,360); (2.75,2.6,2.75,2.6,0,360)"},
    {U'9', 5.5, "(2.75,7,2.75,3,0,360); (0,7,5.5,7,0,-75)"},
    // Greek and symbols
    {U'σ', 7, "7,7 2.75,7 (2.75,3.5,2.75,3.5,90,450)"},
    {U'τ', 6, "0,7 6,7; 3,7 3,1.2 (4.2,1.2,1.2,1.2,180,270) 5,0"},
    {U'φ', 6, "(3,3.5,3,3.3,0,360); 3,10 3,-3"},
    {U'ψ', 6, "0,7 0,4 (3,4,3,3,180,360) 6,7; 3,9 3,-3"},
    {U'δ', 5.5, "(3,8.8,2.2,1.2,40,240) 3.91,5.72 (2.75,3,2.75,3,65,425)"},
    {U'ε', 5.6, "(3,5.3,2.6,1.7,30,270) (3.2,1.8,3,1.8,90,330)"},
    {U'μ', 5.5, "0,-3 0,7; (2.75,2.75,2.75,2.75,180,360) 5.5,7; 5.5,2.75 5.5,0"},
    {U'ρ', 5.5, "0,-3 0,3.5 (2.75,3.5,2.75,3.5,180,540)"},
    {U'Δ', 7, "0,0 3.5,10 7,0 0,0"},
    {U'θ', 5.8, "(2.9,5,2.9,5,0,360); 0,5 5.8,5"},
    {U'γ', 5.8, "0,7 2.9,1; 5.8,7 2.9,1 2.9,-3"},
    {U'ω', 8, "0,6.5 (2,3,2,3,180,360) 4,5; 4,3 (6,3,2,3,180,360) 8,6.5"},
    {U'π', 6.5, "0,7 6.5,7; 1.8,7 1.8,0; 4.8,7 4.8,0"},
    {U'–', 5, "0,4 5,4"},
    {U'—', 10, "0,4 10,4"},
    {U'′', 1, "1,10 0,7.5"},
    {U'‘', 1, "0,7.5 0,8.1 1,10"},
    {U'’', 1, "1,10 1,9.4 0,7.5"},
    {U'“', 3, "0,7.5 0,8.1 1,10; 2,7.5 2,8.1 3,10"},
    {U'”', 3, "1,10 1,9.4 0,7.5; 3,10 3,9.4 2,7.5"},
    {U'°', 3, "(1.5,8.5,1.5,1.5,0,360)"},
    {U'·', 0, "0,4 0,4.3"},
    {U'±', 6, "0,5 6,5; 3,8 3,2; 0,0 6,0"},
    {U'×', 5, "0.5,1.5 5.5,6.5; 0.5,6.5 5.5,1.5"},
    {U'−', 6, "0,4 6,4"},
    {0xFFFD, 5, "0,0 5,0 5,8 0,8 0,0"},  // replacement: a box
};

// Superscripts reuse a glyph, scaled and raised.
constexpr std::pair<char32_t, char32_t> kSuperscripts[] = {
    {U'⁰', U'0'}, {U'¹', U'1'}, {U'²', U'2'}, {U'³', U'3'}, {U'⁴', U'4'}, {U'⁵', U'5'},
    {U'⁶', U'6'}, {U'⁷', U'7'}, {U'⁸', U'8'}, {U'⁹', U'9'}, {U'⁺', U'+'}, {U'⁻', U'-'}};
constexpr double kSuperScale = 0.62, kSuperRaise = 5.0;

constexpr double kEm = 14.0;   // units per size_px
constexpr double kCap = 10.0;  // cap height
constexpr double kDescent = 3.0;
constexpr double kSpacing = 2.6;  // between the ink boxes of adjacent glyphs

struct Glyph {
  double width = 0;
  std::vector<std::vector<Point>> strokes;  // font units, y up
};

// The numbers of a token such as "(1,2.5,3,3,0,-90)" or "4,-1" (locale-free).
std::vector<double> numbers(std::string_view tok) {
  std::vector<double> v;
  const char *p = tok.data(), *end = p + tok.size();
  while (p < end) {
    if (*p == '(' || *p == ')' || *p == ',') {
      ++p;
      continue;
    }
    double d = 0;
    const auto r = std::from_chars(p, end, d);
    if (r.ec != std::errc{}) break;
    v.push_back(d);
    p = r.ptr;
  }
  return v;
}

Glyph parse_glyph(const GlyphDef& def) {
  Glyph g{def.width, {}};
  std::vector<Point> line;
  const std::string s = def.strokes;
  std::size_t i = 0;
  while (i <= s.size()) {
    if (i == s.size() || s[i] == ';') {
      if (!line.empty()) g.strokes.push_back(std::move(line));
      line.clear();
      ++i;
      continue;
    }
    if (s[i] == ' ') {
      ++i;
      continue;
    }
    const std::size_t end = s.find_first_of(" ;", i);
    const std::string tok = s.substr(i, end == std::string::npos ? std::string::npos : end - i);
    i = end == std::string::npos ? s.size() : end;
    const std::vector<double> v = numbers(tok);
    if (tok[0] == '(' && v.size() == 6) {
      const auto [cx, cy, rx, ry, a0, a1] = std::array{v[0], v[1], v[2], v[3], v[4], v[5]};
      const int n = std::max(4, static_cast<int>(std::ceil(std::abs(a1 - a0) / 12.0)));
      for (int k = 0; k <= n; ++k) {
        const double a = (a0 + (a1 - a0) * k / n) * std::numbers::pi / 180.0;
        line.push_back({cx + rx * std::cos(a), cy + ry * std::sin(a)});
      }
    } else if (v.size() == 2) {
      line.push_back({v[0], v[1]});
    }
  }
  return g;
}

// Parsed once, immutable afterwards.
const std::unordered_map<char32_t, Glyph>& glyphs() {
  static const std::unordered_map<char32_t, Glyph> table = [] {
    std::unordered_map<char32_t, Glyph> t;
    for (const GlyphDef& d : kGlyphs) t[d.code] = parse_glyph(d);
    for (auto [sup, base] : kSuperscripts) {
      Glyph g = t.at(base);
      g.width *= kSuperScale;
      for (auto& line : g.strokes)
        for (Point& p : line) p = {p.x * kSuperScale, p.y * kSuperScale + kSuperRaise};
      t[sup] = std::move(g);
    }
    return t;
  }();
  return table;
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

const Glyph& glyph_for(char32_t c) {
  const auto& t = glyphs();
  const auto it = t.find(c);
  return it != t.end() ? it->second : t.at(0xFFFD);
}

double width_units(const std::u32string& text) {
  double w = 0;
  for (char32_t c : text) w += glyph_for(c).width + kSpacing;
  return text.empty() ? 0 : w - kSpacing;
}

}  // namespace

double text_width(std::string_view utf8, double size_px) {
  return width_units(decode_utf8(utf8)) * size_px / kEm;
}

double text_cap_height(double size_px) { return kCap * size_px / kEm; }
double text_descent(double size_px) { return kDescent * size_px / kEm; }

double draw_text(Image& img, double x, double y, std::string_view utf8, double size_px, Color color,
                 Anchor anchor, bool rotate90, double weight) {
  const std::u32string text = decode_utf8(utf8);
  const double s = size_px / kEm;
  const double w = width_units(text);
  // Offset of the anchor from the text origin (left end of the baseline), units.
  const double du = anchor.h == HAlign::left ? 0 : anchor.h == HAlign::center ? w / 2 : w;
  const double dv = anchor.v == VAlign::baseline ? 0
                    : anchor.v == VAlign::top    ? kCap
                    : anchor.v == VAlign::middle ? kCap / 2
                                                 : -kDescent;
  std::vector<std::vector<Point>> lines;
  double pen = 0;
  for (char32_t c : text) {
    const Glyph& g = glyph_for(c);
    for (const auto& stroke : g.strokes) {
      std::vector<Point> line;
      for (const Point& p : stroke) {
        const double u = (pen + p.x - du) * s, v = (p.y - dv) * s;
        line.push_back(rotate90 ? Point{x - v, y - u} : Point{x + u, y - v});
      }
      lines.push_back(std::move(line));
    }
    pen += g.width + kSpacing;
  }
  const double thickness = std::max(1.0, size_px * 0.085) * weight;
  stroke_polylines(img, lines, thickness, color);
  return w * s;
}

}  // namespace simsols::plot
