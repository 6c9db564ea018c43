// The sensitivity study: how a direct shear test's peak and residual
// friction angles and its dilatancy respond to the contact coefficients,
// the specimen's initial density and the box' size (docs/sensitivity.md).
//
// The specimen: the paper's glass beads (6.35 mm, Table 2) poured at
// random into its shear box (4 layers' worth, 324 beads) and sheared under
// 160 kPa. Poured, not layered: the layered specimen's strength is that of
// its crystal, and a pour is where the initial density can be varied (by
// the friction while the beads settle, specimens.md).
//
// Five factors, each over a range around the paper's value (Factor):
// sliding friction μ_s, rolling friction μ_r, restitution ε, Young's
// modulus E (of the beads; the box keeps its steel) and the preparation
// friction, which sets the initial void ratio (reported with each test).
// Three designs, all independent shear tests run like a campaign's
// (resumable, one folder each, and on a cluster, cluster.h):
//   noise      the base point with other seeds: the spread a test has from
//              its packing alone (chaos), against which effects are judged
//   one-at-a-time (OAT)  each factor at the low and high ends of its range,
//              the others at the paper's values
//   Morris     r trajectories of elementary effects (Morris 1991): each
//              trajectory starts at a random point of a p-level grid over
//              the unit cube and moves one factor at a time by
//              Δ = p / (2 (p - 1)); a factor's effects give μ (mean), μ*
//              (mean of |effect|, Campolongo et al. 2007) and σ (spread:
//              interactions and non-linearity), in degrees per the whole
//              range of the factor
// plus the scale effect: the base point in boxes of other length / bead
// size ratios, the paper's box scaled whole (width and layers alike), as
// its programme's smaller beads fill the same box.
#pragma once

#include <array>
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "app/experiment/shear_box/campaign.h"
#include "app/experiment/shear_box/shear_run.h"
#include "solver/scene/scene.h"

namespace simsols {

// One factor: its range [low, high] and the paper's value, on a log or a
// linear scale. Unit levels u in [0, 1] map onto the range.
struct SensitivityFactor {
  std::string key;     // "mu_s": the CSV column's stem
  std::string symbol;  // "μ_s"
  std::string name;    // "sliding friction"
  std::string unit;    // "", "m", "Pa"
  double low = 0, base = 0, high = 0;
  bool log_scale = false;
  double value(double u) const;  // the factor's value at unit level u
  double level(double v) const;  // the unit level of value v
};
inline constexpr int kSensitivityFactors = 5;
using FactorLevels = std::array<double, kSensitivityFactors>;  // unit levels
const std::array<SensitivityFactor, kSensitivityFactors>& sensitivity_factors();

// The three responses, read from each test's summary (degrees).
inline constexpr int kSensitivityResponses = 3;
struct SensitivityResponse {
  const char* key;     // "peak_angle_deg"
  const char* symbol;  // "φ peak"
  const char* name;
};
const std::array<SensitivityResponse, kSensitivityResponses>& sensitivity_responses();

struct SensitivityPreset {
  std::string name;
  double diameter_mm = 6.35, stress_kpa = 160, displacement_mm = 4;
  int layers = 4;
  double settle_time = 0.3;   // s: the pour falls (~0.12 s) and comes to rest
  double consolidate_time = 0;  // s: the longest consolidation; 0: the scene's (0.1 s)
  int seeds = 5;              // the base point's seeds (noise: seeds 2..)
  int trajectories = 4;       // Morris r
  int grid_levels = 4;        // Morris p
  std::uint32_t design_seed = 1;
  std::vector<double> box_ratios{6, 14, 19};  // L / d besides the paper's box
  // The box, length x width (m); the paper's 60.23 x 60.07 mm by default.
  double box_length = 60.23e-3, box_width = 60.07e-3;
};
// "paper" (default) or "ci" (a small box and 0.2 mm of shear: checks that
// it runs, not figures); UsageError naming --preset otherwise.
SensitivityPreset sensitivity_preset(const std::string& name);

// The designs a test belongs to: the base point, its other seeds, one
// factor at a time, a Morris trajectory, the box scaled whole.
enum class Design { base, noise, oat, morris, scale };

// As sensitivity.csv and Python write it: "base", "noise", "oat", "morris", "scale".
const char* design_name(Design d);

// One test of the study: where it sits in which design.
struct SensitivityPoint {
  Design design = Design::base;
  FactorLevels levels{};
  int seed = 1;
  int trajectory = -1, step = -1;  // morris: which trajectory, which of its k + 1 points
  double box_ratio = 0;            // L / d; 0 = the preset's box
  std::string label;               // "oat mu_s low", "morris 2.3", ...
};

// The Morris design: `r` trajectories of k + 1 points each on a p-level
// grid (levels 0, 1/(p-1), ..., 1; p even, else std::invalid_argument),
// each next point differing from the one before in one factor by ±Δ.
// Deterministic for a given seed (a mersenne twister's raw output, so on
// every platform alike).
std::vector<std::vector<FactorLevels>> morris_design(int k, int r, int p, std::uint32_t seed);

struct SensitivityTest {
  SensitivityPoint point;
  Scene scene;
  std::filesystem::path dir;
  double cost = 0;  // particle-steps
  ShearRunResult result;
  double void_ratio = 0;        // after the pour has settled (packing.txt)
  double shear_void_ratio = 0;  // at the start of shearing, consolidated (from its height)
};

// Every test of the study, each scene built and checked before anything
// runs, in OUT/<label>/: the base, the noise seeds, OAT, Morris, scale.
std::vector<SensitivityTest> plan_sensitivity(const SensitivityPreset& preset,
                                              const std::string& out_dir);

// Runs what is left (or `run.only`, or collects) and, unless interrupted
// or running one test, writes the report (sensitivity_report.cpp).
CampaignOutcome run_sensitivity(std::vector<SensitivityTest>& tests,
                                const SensitivityPreset& preset, const std::string& out_dir,
                                const CampaignRun& run);

// ---- analysis (sensitivity_report.cpp): plain numbers, testable alone

struct FactorEffect {
  double oat_low = NAN, oat_high = NAN;  // response minus the base's (deg)
  double mu = NAN, mu_star = NAN, sigma = NAN;  // Morris, deg per the whole range
  int effects = 0;                              // elementary effects (= r)
};
struct SensitivityAnalysis {
  std::array<double, kSensitivityResponses> base{};        // the base (seed 1)
  std::array<double, kSensitivityResponses> noise_mean{};  // over the base's seeds
  std::array<double, kSensitivityResponses> noise_sd{};    // over the base's seeds
  // Where 95 % of tests at the base's values fall: noise_mean ± this, the
  // prediction interval t(0.975, n − 1) sd √(1 + 1/n) of the n seeds. A
  // test outside it moved beyond chaos.
  std::array<double, kSensitivityResponses> noise_band{};
  int noise_runs = 0;
  // [factor][response]
  std::array<std::array<FactorEffect, kSensitivityResponses>, kSensitivityFactors> effects{};
  double morris_delta = 0;
  // μ* that chaos alone would give: E|ε| of an effect whose two runs
  // differ by noise only, sqrt(2/π) sqrt(2) sd / Δ
  std::array<double, kSensitivityResponses> noise_mu_star{};
  // The μ* that chaos alone stays below in ~97.5 % of studies with
  // `effects` elementary effects per factor: the mean of |N(0, s)| plus two
  // standard deviations of that mean, s = √2 sd / Δ.
  double chaos_mu_star_limit(int response, int effects) const;
  // An OAT end outside the seeds' band, a μ* above chaos's limit (false
  // when either number is unknown).
  bool oat_beyond_chaos(int factor, int response, bool high) const;
  bool morris_beyond_chaos(int factor, int response) const;
};

// A test's responses in kSensitivityResponses order.
std::array<double, kSensitivityResponses> responses_of(const ShearSummary& s);
// From the tests' points and responses (any order; tests of a design that
// is missing leave its numbers NaN).
SensitivityAnalysis analyse_sensitivity(
    const std::vector<SensitivityPoint>& points,
    const std::vector<std::array<double, kSensitivityResponses>>& responses, int grid_levels);

// sensitivity.csv, effects.csv, scale.csv, summary.md and the charts
// (oat_<response>.png, morris_<response>.png, scale_effect.png) in `dir`.
void write_sensitivity_report(const std::filesystem::path& dir, const SensitivityPreset& preset,
                              const std::vector<SensitivityTest>& tests);

}  // namespace simsols
