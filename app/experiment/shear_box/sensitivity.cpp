// The sensitivity study's factors, presets, designs and runs
// (sensitivity.h); its analysis and report are in sensitivity_report.cpp.
#include "app/experiment/shear_box/sensitivity.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <random>
#include <stdexcept>

#include "app/experiment/shear_box/paper_tests.h"
#include "app/experiment/test_title.h"
#include "solver/apparatus/registry.h"
#include "solver/apparatus/shear_box/shear_analysis.h"
#include "solver/common/errors.h"
#include "solver/io/output.h"
#include "solver/io/scene_toml.h"

namespace simsols {
namespace {

namespace fs = std::filesystem;

// The paper's glass (Table 2) and the ranges around it: friction and
// rolling resistance over a factor of 4 either side (log), restitution
// from a dull to a lively impact, E down to a tenth (how far a softened
// material may go), the preparation friction from a frictionless pour
// (densest) to a rough one (loosest).
const std::array<SensitivityFactor, kSensitivityFactors> kFactors{{
    {"mu_s", "μ_s", "sliding friction", "", 0.005, 0.02, 0.08, true},
    {"mu_r", "μ_r", "rolling friction", "m", 1.25e-5, 5e-5, 2e-4, true},
    {"restitution", "ε", "restitution", "", 0.5, 0.87, 0.95, false},
    {"young_modulus", "E", "Young's modulus of the beads", "Pa", 6.2784e9, 62.784e9, 62.784e9,
     true},
    {"preparation_friction", "μ_prep", "preparation friction: initial density", "",
     0, 0.1, 0.5, false},
}};

const std::array<SensitivityResponse, kSensitivityResponses> kResponses{{
    {"peak_angle_deg", "φ peak", "peak friction angle"},
    {"residual_angle_deg", "φ residual", "residual friction angle"},
    {"max_dilatancy_deg", "ψ max", "maximum dilatancy angle"},
}};

// Raw mersenne-twister draws: the same sequence on every platform (the
// standard library's distributions are not).
int draw(std::mt19937& g, int n) { return static_cast<int>(g() % static_cast<std::uint32_t>(n)); }

// The glass and the box' steel take μ_s, μ_r and ε (every contact has
// them); E changes the beads only. The pour settles with the preparation
// friction and the paper's μ_r whatever the test's, so that the packing is
// the density factor's (ε and E still shape the rain a little: each test
// reports its e0).
void apply_levels(Scene& sc, const FactorLevels& u) {
  const auto& f = kFactors;
  for (Material& m : sc.materials) {
    m.sliding_friction = f[0].value(u[0]);
    m.rolling_friction = f[1].value(u[1]);
    m.restitution = f[2].value(u[2]);
  }
  ShearBox& b = *sc.apparatus_as<ShearBox>();
  sc.materials[b.specimen.material].young_modulus = f[3].value(u[3]);
  b.specimen.preparation.friction = f[4].value(u[4]);
  b.specimen.preparation.rolling_friction = f[1].base;
}

FactorLevels base_levels() {
  FactorLevels u{};
  for (int i = 0; i < kSensitivityFactors; ++i) u[i] = kFactors[i].level(kFactors[i].base);
  return u;
}

std::string level_name(double u) { return u == 0 ? "low" : u == 1 ? "high" : format_number("%.3g", u); }

std::vector<SensitivityPoint> study_points(const SensitivityPreset& p) {
  std::vector<SensitivityPoint> pts;
  const FactorLevels base = base_levels();
  pts.push_back({Design::base, base, 1, -1, -1, 0, "base"});
  for (int s = 2; s <= p.seeds; ++s)
    pts.push_back({Design::noise, base, s, -1, -1, 0, "noise_seed" + std::to_string(s)});
  for (int i = 0; i < kSensitivityFactors; ++i)
    for (double u : {0.0, 1.0}) {
      if (u == base[i]) continue;  // the base already is this end (E)
      FactorLevels l = base;
      l[i] = u;
      pts.push_back({Design::oat, l, 1, -1, -1, 0, "oat_" + kFactors[i].key + "_" + level_name(u)});
    }
  const auto design =
      morris_design(kSensitivityFactors, p.trajectories, p.grid_levels, p.design_seed);
  for (size_t t = 0; t < design.size(); ++t)
    for (size_t j = 0; j < design[t].size(); ++j)
      pts.push_back({Design::morris, design[t][j], 1, int(t), int(j), 0,
                     "morris_" + std::to_string(t + 1) + "_" + std::to_string(j)});
  for (double ratio : p.box_ratios)
    pts.push_back({Design::scale, base, 1, -1, -1, ratio, "scale_" + format_number("%g", ratio)});
  return pts;
}

// The study's base scene: the default experiment's glass and box, poured.
Scene base_scene(const SensitivityPreset& p) {
  Scene sc = default_shear_base();
  ShearBox& b = *sc.apparatus_as<ShearBox>();
  b.specimen.method = Specimen::Method::Pour;
  b.settle_time = p.settle_time;
  if (p.consolidate_time > 0) b.consolidate_time = p.consolidate_time;
  b.shear_displacement = p.displacement_mm * 1e-3;
  b.length = p.box_length;
  b.width = p.box_width;
  sc.outputs.dump_vtk = false;
  sc.outputs.dump_csv = false;
  return sc;
}

}  // namespace

double SensitivityFactor::value(double u) const {
  return log_scale ? low * std::pow(high / low, u) : low + (high - low) * u;
}
double SensitivityFactor::level(double v) const {
  return log_scale ? std::log(v / low) / std::log(high / low) : (v - low) / (high - low);
}

const std::array<SensitivityFactor, kSensitivityFactors>& sensitivity_factors() { return kFactors; }
const std::array<SensitivityResponse, kSensitivityResponses>& sensitivity_responses() {
  return kResponses;
}

const char* design_name(Design d) {
  switch (d) {
    case Design::base: return "base";
    case Design::noise: return "noise";
    case Design::oat: return "oat";
    case Design::morris: return "morris";
    case Design::scale: return "scale";
  }
  return "?";
}

SensitivityPreset sensitivity_preset(const std::string& name) {
  SensitivityPreset p;
  p.name = name;
  if (name == "paper") return p;
  if (name == "ci") {
    p.box_length = 33.46e-3;  // 5 x 5 beads a layer (assets/tests/shear_small.toml)
    p.box_width = 33.40e-3;
    p.layers = 2;
    p.displacement_mm = 0.2;
    p.settle_time = 0.07;
    p.consolidate_time = 0.04;  // its 50 beads do not reach the equilibrium criterion
    p.seeds = 2;
    p.trajectories = 1;
    p.box_ratios = {7};
    return p;
  }
  throw UsageError("bad_enum", "--preset",
                   "'" + name + "' is not a sensitivity preset: paper, ci");
}

std::vector<std::vector<FactorLevels>> morris_design(int k, int r, int p, std::uint32_t seed) {
  // an even p: every level is a start equally often (an odd one draws the
  // middle level twice as often)
  if (p < 2 || p % 2 != 0 || k < 1 || k > kSensitivityFactors)
    throw std::invalid_argument("morris_design: p must be even and >= 2, k in [1, 5]");
  std::mt19937 g(seed);
  const double step = 1.0 / (p - 1);
  const int jump = p / 2;  // Δ = p / (2 (p - 1)) = jump steps
  const double delta = jump * step;
  std::vector<std::vector<FactorLevels>> design;
  for (int t = 0; t < r; ++t) {
    FactorLevels x{};
    for (int i = 0; i < k; ++i) x[i] = draw(g, p - jump) * step + (draw(g, 2) ? delta : 0);
    std::vector<int> order(k);
    for (int i = 0; i < k; ++i) order[i] = i;
    for (int i = k - 1; i > 0; --i) std::swap(order[i], order[draw(g, i + 1)]);
    std::vector<FactorLevels> traj{x};
    for (int i : order) {
      x[i] = x[i] + delta <= 1 + 1e-12 ? x[i] + delta : x[i] - delta;
      traj.push_back(x);
    }
    design.push_back(std::move(traj));
  }
  return design;
}

std::vector<SensitivityTest> plan_sensitivity(const SensitivityPreset& preset,
                                              const std::string& out_dir) {
  const Scene base = base_scene(preset);
  std::vector<SensitivityTest> tests;
  for (const SensitivityPoint& pt : study_points(preset)) {
    // a box of another L/d is the paper's scaled: its height too (the layers)
    const double d = preset.diameter_mm * 1e-3;
    const double scale = pt.box_ratio > 0 ? pt.box_ratio * d / preset.box_length : 1;
    const int layers = std::max(2, static_cast<int>(std::lround(preset.layers * scale)));
    Scene sc = paper_test_scene(base, kDefaultSceneName, preset.diameter_mm, preset.stress_kpa,
                                layers, [&](Scene& x) {
                                  apply_levels(x, pt.levels);
                                  ShearBox& box = *x.apparatus_as<ShearBox>();
                                  box.specimen.seed = pt.seed;
                                  box.length = scale * preset.box_length;
                                  box.width = scale * preset.box_width;
                                });
    sc.name = pt.label;
    validate_scene(sc, "sensitivity study (" + pt.label + ")");
    SensitivityTest t;
    t.point = pt;
    t.cost = expected_particle_steps(sc);
    t.scene = std::move(sc);
    t.dir = fs::path(out_dir) / pt.label;
    tests.push_back(std::move(t));
  }
  return tests;
}

namespace {

double settled_void_ratio(const fs::path& dir) {
  if (!fs::exists(dir / "packing.txt")) return NAN;
  const auto keys = summary_keys(read_text(dir / "packing.txt"));
  const auto it = keys.find("void_ratio");
  return it == keys.end() ? NAN : std::strtod(it->second.c_str(), nullptr);
}

// e = V / V_s - 1 of the box up to the platen as shearing starts.
double consolidated_void_ratio(const SensitivityTest& t) {
  double solids = 0;
  for (const Particle& p : t.scene.particles) solids += 4.0 / 3.0 * M_PI * std::pow(p.radius, 3);
  const ShearBox& b = *t.scene.apparatus_as<ShearBox>();
  return b.length * b.width * t.result.summary.specimen_height / solids - 1;
}

void measured(SensitivityTest& t) {
  t.void_ratio = settled_void_ratio(t.dir);
  t.shear_void_ratio = consolidated_void_ratio(t);
}

void print_test(const SensitivityTest& t) {
  const ShearSummary& s = t.result.summary;
  std::printf("%-30s e pour %.3f, sheared %.3f  phi_peak %.2f  phi_res %.2f  psi_max %.2f deg  %.0f s\n",
              t.point.label.c_str(), t.void_ratio, t.shear_void_ratio, s.peak_angle, s.residual_angle,
              s.max_dilatancy_angle, s.wall_seconds);
  std::fflush(stdout);
}

}  // namespace

CampaignOutcome run_sensitivity(std::vector<SensitivityTest>& tests,
                                const SensitivityPreset& preset, const std::string& out_dir,
                                const CampaignRun& run) {
  fs::create_directories(out_dir);
  CampaignLoop loop = campaign_loop(tests, "sensitivity tests", "shear.csv");
  loop.keep = [&](size_t k) {
    tests[k].result = finished_shear_test(tests[k].dir, test_title(tests[k].scene));
    measured(tests[k]);
  };
  loop.run = [&](size_t k, ProgrammeRunOptions& o) {
    tests[k].result = run_shear_test(tests[k].scene, o, test_title(tests[k].scene));
    measured(tests[k]);
    return tests[k].result.interrupted;
  };
  loop.print = [&](size_t k) { print_test(tests[k]); };
  const CampaignOutcome outcome = run_campaign_loop(loop, run);
  if (!outcome.interrupted && run.writes_report())
    write_sensitivity_report(out_dir, preset, tests);
  return outcome;
}

}  // namespace simsols
