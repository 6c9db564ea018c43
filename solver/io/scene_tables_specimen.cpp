// [<apparatus>.specimen]: what every apparatus' specimen is, read the same
// way for each (docs/specimens.md): the placement (layers, pour, given),
// the grading curve, the grain template and the preparation (friction,
// relative density or void ratio, layered tamping, radius expansion).
#include <cmath>

#include "solver/apparatus/specimen/grading.h"
#include "solver/apparatus/specimen/specimen.h"
#include "solver/common/number_text.h"
#include "solver/io/scene_tables.h"
#include "solver/scene/clump.h"

namespace simsols::scene_toml {

namespace {

// [*.specimen.grading]: the law and its keys; the curve is built here so a
// bad one is refused with its field. Returns the curve's D50 (the
// specimen's reference diameter).
double read_grading(const Reader& sp, Specimen& s) {
  Reader gr = sp.sub("grading", {"law", "d_min", "d_max", "sigma", "exponent", "sizes", "passing"});
  Grading& g = s.grading;
  g.law = gr.choice("law", Grading::Law::Single);
  using Law = Grading::Law;
  const auto only = [&](std::vector<std::string> keys, const char* laws) {
    gr.forbid(keys, std::string("only allowed when law = ") + laws);
  };
  if (g.law != Law::Fuller) only({"exponent"}, "\"fuller\"");
  if (g.law != Law::Sieve) only({"sizes", "passing"}, "\"sieve\"");
  if (g.law == Law::Single || g.law == Law::Sieve)
    only({"d_min", "d_max"}, "\"uniform\", \"lognormal\" or \"fuller\"");
  if (g.law != Law::LogNormal) only({"sigma"}, "\"lognormal\"");
  g.d_min = gr.number("d_min", 0);
  g.d_max = gr.number("d_max", 0);
  g.sigma = gr.number("sigma", g.sigma);
  g.exponent = gr.number("exponent", g.exponent);
  g.sizes = gr.numbers("sizes", {});
  g.passing = gr.numbers("passing", {});
  if (g.law != Law::Single && s.method != Specimen::Method::Pour)
    gr.fail("conflicting_keys", "law", "a grading needs specimen.method = \"pour\"");
  const bool sets_d50 = g.law == Law::Uniform || g.law == Law::Fuller || g.law == Law::Sieve;
  if (sets_d50 && sp.has("diameter"))
    sp.fail("conflicting_keys", "diameter",
            std::string("the grading law \"") + choice_name(g.law) +
                "\" sets the sizes; leave diameter out (D50 is read from the curve)");
  if (g.law == Law::Single) return sp.number("diameter");
  const double d50 = sets_d50 ? 0 : sp.number("diameter");
  try {
    const GradingCurve curve = grading_curve(g, d50);  // a bad curve is refused here, by field
    return sets_d50 ? curve.size_at(0.5) : d50;
  } catch (const GradingError& e) {
    gr.fail("out_of_range", e.field, e.what());
  }
}

// Layered tamping (solver/apparatus/specimen/tamping.h): the layers, the target void
// ratio (or relative_density) and the under-compaction.
void read_tamping(const Reader& r, const Specimen& s, Preparation& p) {
  if (!r.has("tamping_layers")) {
    r.forbid({"undercompaction"}, "only allowed with tamping_layers");
    if (!p.expansion) r.forbid({"void_ratio"}, "only allowed with tamping_layers or expansion");
    return;
  }
  if (p.expansion)
    r.fail("conflicting_keys", "tamping_layers", "a specimen is tamped or grown by expansion, not both");
  if (s.method != Specimen::Method::Pour)
    r.fail("conflicting_keys", "tamping_layers", "tamping builds a poured specimen: use specimen.method = \"pour\"");
  const double layers = r.number("tamping_layers");
  r.check_range("tamping_layers", layers, layers >= 2 && layers <= 50 && layers == std::floor(layers),
                "a whole number in [2, 50]");
  p.tamping_layers = static_cast<int>(layers);
  p.void_ratio = r.optional_number("void_ratio");
  if (p.void_ratio) r.check_range("void_ratio", *p.void_ratio, *p.void_ratio > 0.01 && *p.void_ratio <= 10, "(0.01, 10]");
  p.undercompaction = r.number("undercompaction", p.undercompaction);
  r.check_range("undercompaction", p.undercompaction, p.undercompaction >= 0 && p.undercompaction <= 0.3, "[0, 0.3]");
  if (p.void_ratio && r.has("relative_density"))
    r.fail("conflicting_keys", "void_ratio", "give the target as void_ratio or relative_density, not both");
  if (!p.void_ratio && !r.has("relative_density"))
    r.fail("missing_field", "void_ratio", "tamping needs a target: void_ratio or relative_density");
}

// Radius expansion (solver/apparatus/specimen/expansion.h): spheres poured, grown in
// the closed cell to a target (void_ratio, relative_density) or with the
// friction given.
void read_expansion(const Reader& r, const Specimen& s, Preparation& p) {
  p.expansion = r.boolean("expansion", false);
  if (!p.expansion) return;
  if (s.method != Specimen::Method::Pour)
    r.fail("conflicting_keys", "expansion", "expansion grows a poured specimen: use specimen.method = \"pour\"");
  r.forbid({"drop_height", "intensity"}, "not allowed with expansion (the beads grow in place, no rain)");
  p.void_ratio = r.optional_number("void_ratio");
  if (p.void_ratio) r.check_range("void_ratio", *p.void_ratio, *p.void_ratio > 0.01 && *p.void_ratio <= 10, "(0.01, 10]");
  if (p.void_ratio && (r.has("relative_density") || r.has("friction")))
    r.fail("conflicting_keys", "void_ratio", "give one target: void_ratio, relative_density or friction");
}

// [*.specimen.preparation]: the settling friction, the pour's rain, a
// target relative density and the index void ratios (docs/specimens.md).
Preparation read_preparation(const Reader& sp, const Specimen& s) {
  Reader r = sp.sub("preparation", {"friction", "rolling_friction", "drop_height", "intensity",
                                     "relative_density", "e_min", "e_max", "tamping_layers",
                                     "void_ratio", "undercompaction", "expansion"});
  Preparation p;
  const auto opt = [&](const char* key, double lo, double hi, const char* range) {
    const std::optional<double> v = r.optional_number(key);
    if (v) r.check_range(key, *v, *v >= lo && *v <= hi, range);
    return v;
  };
  p.friction = opt("friction", 0, 10, "[0, 10]");
  p.rolling_friction = opt("rolling_friction", 0, 1, "[0, 1] m");
  p.relative_density = opt("relative_density", 0, 1, "[0, 1]");
  p.e_min = opt("e_min", 0.01, 10, "[0.01, 10]");
  p.e_max = opt("e_max", 0.01, 10, "[0.01, 10]");
  if (s.method != Specimen::Method::Pour)
    r.forbid({"drop_height", "intensity"}, "only allowed when specimen.method = \"pour\"");
  p.drop_height = opt("drop_height", 0, 10, "[0, 10] m").value_or(0);
  p.intensity = opt("intensity", 0, 0.35, "[0, 0.35]").value_or(0);
  read_expansion(r, s, p);
  read_tamping(r, s, p);
  if (p.relative_density && p.friction)
    r.fail("conflicting_keys", "relative_density",
           "a target relative density sets the friction; leave friction out");
  if (p.e_min.has_value() != p.e_max.has_value())
    r.fail("missing_field", p.e_min ? "e_max" : "e_min", "e_min and e_max go together");
  if (p.e_min && !(*p.e_min < *p.e_max))
    r.fail("out_of_range", "e_max",
           shortest_number(*p.e_max) + " is out of range, allowed (e_min = " +
               shortest_number(*p.e_min) + ", 10]");
  return p;
}

// specimen.grain: a pour of clumps of a [[grains]] shape, sized by
// volume-equivalent diameter (docs/specimens.md).
int read_grain(const Reader& sp, const Scene& scene, const Specimen& s) {
  const std::string name = sp.string("grain");
  if (s.method != Specimen::Method::Pour)
    sp.fail("conflicting_keys", "grain", "clumps are poured: use specimen.method = \"pour\"");
  for (size_t g = 0; g < scene.grains.size(); ++g)
    if (scene.grains[g].name == name) return static_cast<int>(g);
  sp.fail("unknown_grain", "grain", "no grain named '" + name + "' ([[grains]])");
}

}  // namespace

Specimen read_specimen(const Reader& apparatus, const Scene& scene) {
  Reader sp = apparatus.sub("specimen", {"method", "material", "diameter", "layers", "clearance",
                                         "seed", "grading", "grain", "preparation"});
  Specimen s;
  s.method = sp.choice("method", Specimen::Method::Layers);
  s.preparation = read_preparation(sp, s);
  if (s.method == Specimen::Method::Given) {
    sp.forbid({"material", "diameter", "layers", "clearance", "seed", "grading", "grain"},
              "only allowed when method = \"layers\" or \"pour\"");
    return s;
  }
  s.material = sp.material("material", scene);
  if (sp.has("grain")) {  // sizes are the grains' volume-equivalent diameters
    if (s.preparation.expansion)
      sp.fail("conflicting_keys", "grain", "expansion grows spheres; pour or tamp a specimen of clumps");
    s.grain = read_grain(sp, scene, s);
    s.diameter = sp.has("diameter") || sp.has("grading")
                     ? read_grading(sp, s)
                     : volume_equivalent_diameter(grain_body(scene.grains[s.grain]));
  } else {
    s.diameter = read_grading(sp, s);
  }
  const std::int64_t layers = sp.integer("layers");
  if (layers < 1 || layers > 200)
    sp.fail("out_of_range", "layers", std::to_string(layers) + " is out of range, allowed [1, 200]");
  s.layers = static_cast<int>(layers);
  if (s.method == Specimen::Method::Pour)
    sp.forbid({"clearance"}, "only allowed when method = \"layers\"");
  s.clearance = sp.choice("clearance", Specimen::Clearance::Shift);
  const std::int64_t seed = sp.optional_integer("seed").value_or(1);
  if (seed < 0)
    sp.fail("out_of_range", "seed", std::to_string(seed) + " is out of range, allowed [0, 2^63)");
  s.seed = seed;
  return s;
}

}  // namespace simsols::scene_toml
