#include "solver/apparatus/specimen/tamping_state.h"

#include <bit>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <string>

#include "solver/common/atomic_file.h"
#include "solver/common/errors.h"
#include "solver/common/number_text.h"

namespace simsols {
namespace {

constexpr const char* kMagic = "simsols tamping state 1";

// FNV-1a, 64 bits, over text and over numbers' bits.
struct Fnv {
  std::uint64_t h = 1469598103934665603ull;
  void text(std::string_view t) {
    for (const unsigned char c : t) h = (h ^ c) * 1099511628211ull;
  }
  void num(double v) {
    std::uint64_t b = std::bit_cast<std::uint64_t>(v);
    for (int k = 0; k < 8; ++k, b >>= 8) h = (h ^ (b & 0xff)) * 1099511628211ull;
  }
};

// Reads the tokens of one line, failing with the file and the line.
class Line {
 public:
  Line(const std::filesystem::path& file, int number, const std::string& text)
      : file_(file), number_(number), in_(text) {}
  std::string word() {
    std::string w;
    if (!(in_ >> w)) fail("a value is missing");
    return w;
  }
  double real() {
    const std::string w = word();
    char* end = nullptr;
    const double v = std::strtod(w.c_str(), &end);
    if (end == w.c_str() || *end != '\0') fail("'" + w + "' is not a number");
    return v;
  }
  int integer() { return static_cast<int>(real()); }
  Vec3 vec3() { return {real(), real(), real()}; }
  [[noreturn]] void fail(const std::string& what) const {
    throw ReadError(file_.string() + ":" + std::to_string(number_) +
                    ": not a tamping state SimSols wrote (" + what +
                    "); delete it to tamp the specimen afresh");
  }

 private:
  const std::filesystem::path& file_;
  int number_;
  std::istringstream in_;
};

std::string nums(std::initializer_list<double> values) {
  std::string s;
  for (const double v : values) s += " " + shortest_number(v);
  return s;
}

void read_record(Line& l, const std::string& kind, TampingState& s) {
  if (kind == "floor") {
    s.floor = l.real();
  } else if (kind == "solid_total") {
    s.solid_total = l.real();
  } else if (kind == "layer") {
    TampedLayer t;
    t.layer = l.integer();
    t.grains = l.integer();
    t.target_void_ratio = l.real();
    t.target_top = l.real();
    t.platen_stop = l.real();
    t.stress = l.real();
    t.void_ratio = l.real();
    s.layers.push_back(t);
    s.seconds.push_back(l.real());
  } else if (kind == "clump") {
    Clump c;
    c.grain = l.integer();
    c.scale = l.real();
    c.material = l.integer();
    c.position = l.vec3();
    for (double& q : c.orientation) q = l.real();
    s.clumps.push_back(c);
  } else if (kind == "sphere") {
    Particle p;
    p.material = l.integer();
    p.radius = l.real();
    p.position = l.vec3();
    s.spheres.push_back(p);
  } else {
    l.fail("unknown record '" + kind + "'");
  }
}

}  // namespace

std::uint64_t tamping_key(const Scene& scene, double void_ratio) {
  Fnv f;
  f.text(scene.name);
  f.text(scene.source_text);  // a file's every setting
  f.num(void_ratio);
  for (const Material& m : scene.materials)
    for (const double v : {m.young_modulus, m.poisson_ratio, m.density, m.restitution,
                           m.sliding_friction, m.rolling_friction})
      f.num(v);
  for (const Particle& p : scene.particles)  // the poured column: seed, grading, cell
    for (const double v : {double(p.material), p.radius, p.position[0], p.position[1], p.position[2]})
      f.num(v);
  for (const Clump& c : scene.clumps)
    for (const double v : {double(c.grain), c.scale, c.position[0], c.position[1], c.position[2],
                           c.orientation[0], c.orientation[1], c.orientation[2], c.orientation[3]})
      f.num(v);
  const Preparation& prep = scene.specimen()->preparation;
  f.num(prep.tamping_layers);
  f.num(prep.friction.value_or(-1));
  f.num(prep.rolling_friction.value_or(-1));
  f.num(prep.undercompaction);
  return f.h;
}

void save_tamping_state(const std::filesystem::path& file, const TampingState& s) {
  std::ostringstream o;
  o << kMagic << "\nkey " << s.key << "\nfloor " << shortest_number(s.floor)
    << "\nsolid_total " << shortest_number(s.solid_total) << '\n';
  for (size_t k = 0; k < s.layers.size(); ++k) {
    const TampedLayer& t = s.layers[k];
    o << "layer " << t.layer << ' ' << t.grains
      << nums({t.target_void_ratio, t.target_top, t.platen_stop, t.stress, t.void_ratio,
               s.seconds[k]})
      << '\n';
  }
  for (const Clump& c : s.clumps)
    o << "clump " << c.grain << nums({c.scale}) << ' ' << c.material
      << nums({c.position[0], c.position[1], c.position[2], c.orientation[0], c.orientation[1],
               c.orientation[2], c.orientation[3]})
      << '\n';
  for (const Particle& p : s.spheres)
    o << "sphere " << p.material << nums({p.radius, p.position[0], p.position[1], p.position[2]})
      << '\n';
  o << "end\n";
  write_file_atomic(file.string(), o.str());
}

std::optional<TampingState> load_tamping_state(const std::filesystem::path& file,
                                               std::uint64_t key) {
  std::ifstream in(file);
  if (!in) return std::nullopt;
  std::string text;
  if (!std::getline(in, text) || text != kMagic) Line(file, 1, text).fail("its first line");
  TampingState s;
  int number = 1;
  bool ended = false;
  while (!ended && std::getline(in, text)) {
    Line l(file, ++number, text);
    const std::string kind = l.word();
    if (kind == "key") {
      const std::string k = l.word();
      s.key = std::strtoull(k.c_str(), nullptr, 10);
      if (s.key != key) return std::nullopt;
    } else if (kind == "end") {
      ended = true;
    } else {
      read_record(l, kind, s);
    }
  }
  if (!ended || s.key != key) Line(file, number, "").fail("it ends early");
  return s;
}

}  // namespace simsols
