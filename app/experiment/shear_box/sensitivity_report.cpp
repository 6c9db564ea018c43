// The sensitivity study's analysis and what it writes (sensitivity.h):
// one-at-a-time differences, Morris elementary effects, the noise a test
// has from its packing alone, and the scale effect; CSV with units,
// summary.md and the charts.
#include <cmath>
#include <map>
#include <sstream>

#include "app/experiment/shear_box/sensitivity.h"
#include "app/experiment/shear_box/study_stats.h"
#include "render/plot/chart.h"
#include "solver/io/output.h"

namespace simsols {
namespace {

namespace fs = std::filesystem;
using Responses = std::array<double, kSensitivityResponses>;

double mean_of(const std::vector<double>& v) {
  double s = 0;
  for (double x : v) s += x;
  return v.empty() ? NAN : s / double(v.size());
}
double sd_of(const std::vector<double>& v) {
  if (v.size() < 2) return NAN;
  const double m = mean_of(v);
  double s = 0;
  for (double x : v) s += (x - m) * (x - m);
  return std::sqrt(s / double(v.size() - 1));
}

// The factor in which two successive points of a trajectory differ, and by
// how much (-1 when they differ in none or several).
int moved_factor(const FactorLevels& a, const FactorLevels& b, double& by) {
  int moved = -1;
  for (int i = 0; i < kSensitivityFactors; ++i)
    if (std::abs(a[i] - b[i]) > 1e-9) {
      if (moved >= 0) return -1;
      moved = i;
      by = b[i] - a[i];
    }
  return moved;
}

void morris_effects(const std::vector<SensitivityPoint>& pts, const std::vector<Responses>& ys,
                    SensitivityAnalysis& a) {
  // each trajectory's points in order
  std::map<int, std::map<int, size_t>> traj;
  for (size_t n = 0; n < pts.size(); ++n)
    if (pts[n].design == Design::morris) traj[pts[n].trajectory][pts[n].step] = n;
  std::array<std::array<std::vector<double>, kSensitivityResponses>, kSensitivityFactors> ee;
  for (const auto& [t, steps] : traj)
    for (auto it = steps.begin(); std::next(it) != steps.end(); ++it) {
      const size_t from = it->second, to = std::next(it)->second;
      double by = 0;
      const int i = moved_factor(pts[from].levels, pts[to].levels, by);
      if (i < 0 || std::next(it)->first != it->first + 1) continue;
      for (int r = 0; r < kSensitivityResponses; ++r) ee[i][r].push_back((ys[to][r] - ys[from][r]) / by);
    }
  for (int i = 0; i < kSensitivityFactors; ++i)
    for (int r = 0; r < kSensitivityResponses; ++r) {
      const std::vector<double>& e = ee[i][r];
      FactorEffect& f = a.effects[i][r];
      f.effects = int(e.size());
      if (e.empty()) continue;
      std::vector<double> abs_e;
      for (double x : e) abs_e.push_back(std::abs(x));
      f.mu = mean_of(e);
      f.mu_star = mean_of(abs_e);
      f.sigma = sd_of(e);
    }
}

}  // namespace

std::array<double, kSensitivityResponses> responses_of(const ShearSummary& s) {
  return {s.peak_angle, s.residual_angle, s.max_dilatancy_angle};
}

SensitivityAnalysis analyse_sensitivity(const std::vector<SensitivityPoint>& pts,
                                        const std::vector<Responses>& ys, int grid_levels) {
  SensitivityAnalysis a;
  a.morris_delta = (grid_levels / 2) / double(grid_levels - 1);
  std::array<std::vector<double>, kSensitivityResponses> seeds;
  a.base.fill(NAN);
  for (size_t n = 0; n < pts.size(); ++n) {
    if (pts[n].design != Design::base && pts[n].design != Design::noise) continue;
    if (pts[n].design == Design::base) a.base = ys[n];
    for (int r = 0; r < kSensitivityResponses; ++r) seeds[r].push_back(ys[n][r]);
  }
  a.noise_runs = int(seeds[0].size());
  for (int r = 0; r < kSensitivityResponses; ++r) {
    a.noise_mean[r] = mean_of(seeds[r]);
    a.noise_sd[r] = sd_of(seeds[r]);
    const double n = a.noise_runs;
    a.noise_band[r] = n >= 2 ? student_t_quantile(0.975, n - 1) * a.noise_sd[r] * std::sqrt(1 + 1 / n)
                             : NAN;
    a.noise_mu_star[r] = std::sqrt(2 / M_PI) * std::sqrt(2.0) * a.noise_sd[r] / a.morris_delta;
  }
  FactorLevels base{};
  for (const SensitivityPoint& p : pts)
    if (p.design == Design::base) base = p.levels;
  for (size_t n = 0; n < pts.size(); ++n) {
    if (pts[n].design != Design::oat) continue;
    double by = 0;
    const int i = moved_factor(base, pts[n].levels, by);
    if (i < 0) continue;
    for (int r = 0; r < kSensitivityResponses; ++r)
      (pts[n].levels[i] == 0 ? a.effects[i][r].oat_low : a.effects[i][r].oat_high) =
          ys[n][r] - a.base[r];
  }
  morris_effects(pts, ys, a);
  return a;
}

bool SensitivityAnalysis::oat_beyond_chaos(int i, int r, bool high) const {
  const double d = high ? effects[i][r].oat_high : effects[i][r].oat_low;
  return std::abs(base[r] + d - noise_mean[r]) > noise_band[r];  // false for NaN
}

double SensitivityAnalysis::chaos_mu_star_limit(int r, int n) const {
  const double s = std::sqrt(2.0) * noise_sd[r] / morris_delta;
  return n > 0 ? s * (std::sqrt(2 / M_PI) + 2 * std::sqrt(1 - 2 / M_PI) / std::sqrt(double(n))) : NAN;
}

bool SensitivityAnalysis::morris_beyond_chaos(int i, int r) const {
  const FactorEffect& e = effects[i][r];
  return e.mu_star > chaos_mu_star_limit(r, e.effects);
}

namespace {

std::string num(double v, const char* f = "%.2f") {
  return std::isfinite(v) ? format_number(f, v) : std::string("–");
}

std::string tests_csv(const std::vector<SensitivityTest>& tests) {
  std::ostringstream o;
  o << "test,design,trajectory,step,seed,box_ratio,";
  for (const SensitivityFactor& f : sensitivity_factors())
    o << f.key << (f.unit.empty() ? "" : "_" + f.unit) << ',';
  o << "particles,void_ratio_poured,void_ratio_sheared,peak_angle_deg,residual_angle_deg,max_dilatancy_deg,"
       "peak_displacement_mm,wall_s\n";
  for (const SensitivityTest& t : tests) {
    const SensitivityPoint& p = t.point;
    const ShearSummary& s = t.result.summary;
    o << p.label << ',' << design_name(p.design) << ',' << p.trajectory << ',' << p.step << ',' << p.seed << ','
      << t.scene.apparatus_as<ShearBox>()->length / (2 * t.scene.particles[0].radius) << ',';
    for (int i = 0; i < kSensitivityFactors; ++i)
      o << format_number("%.6g", sensitivity_factors()[i].value(p.levels[i])) << ',';
    o << t.scene.particles.size() << ',' << format_number("%.5g", t.void_ratio) << ','
      << format_number("%.5g", t.shear_void_ratio) << ','
      << format_number("%.4f", s.peak_angle) << ',' << format_number("%.4f", s.residual_angle) << ','
      << format_number("%.4f", s.max_dilatancy_angle) << ','
      << format_number("%.4f", s.peak_displacement * 1e3) << ','
      << format_number("%.1f", s.wall_seconds) << '\n';
  }
  return o.str();
}

// CSV: NaN (a design not run) as an empty field
std::string csv_num(double v) { return std::isfinite(v) ? format_number("%.4f", v) : std::string(); }

std::string effects_csv(const SensitivityAnalysis& a) {
  std::ostringstream o;
  o << "factor,response,oat_low_deg,oat_high_deg,morris_mu_deg,morris_mu_star_deg,"
       "morris_sigma_deg,effects,noise_sd_deg,noise_mu_star_deg,chaos_mu_star_limit_deg\n";
  for (int i = 0; i < kSensitivityFactors; ++i)
    for (int r = 0; r < kSensitivityResponses; ++r) {
      const FactorEffect& f = a.effects[i][r];
      o << sensitivity_factors()[i].key << ',' << sensitivity_responses()[r].key << ','
        << csv_num(f.oat_low) << ',' << csv_num(f.oat_high) << ',' << csv_num(f.mu) << ','
        << csv_num(f.mu_star) << ',' << csv_num(f.sigma) << ',' << f.effects << ','
        << csv_num(a.noise_sd[r]) << ',' << csv_num(a.noise_mu_star[r]) << ','
        << csv_num(a.chaos_mu_star_limit(r, f.effects)) << '\n';
    }
  return o.str();
}

// One line per factor: its response at the low end, the base and the high
// end against its unit level (a spider plot), and the band where 95 % of
// tests at the base's values fall (the seeds' mean ± noise_band).
void oat_chart(const SensitivityAnalysis& a, int r, const fs::path& path) {
  const SensitivityResponse& resp = sensitivity_responses()[r];
  plot::Chart c;
  c.title = std::string("One at a time: ") + resp.symbol;
  c.x_label = "Factor level within its range (0 = low, 1 = high)";
  c.y_label = std::string(resp.symbol) + " (°)";
  c.x_min = 0;
  c.x_max = 1;
  for (int i = 0; i < kSensitivityFactors; ++i) {
    const SensitivityFactor& f = sensitivity_factors()[i];
    const FactorEffect& e = a.effects[i][r];
    plot::Series s;
    s.label = f.symbol + " (" + f.name + ")";
    s.markers = true;
    auto add = [&](double u, double y) {
      if (std::isfinite(y)) s.x.push_back(u), s.y.push_back(y);
    };
    add(0, a.base[r] + e.oat_low);
    add(f.level(f.base), a.base[r]);
    add(1, a.base[r] + e.oat_high);
    c.series.push_back(s);
  }
  for (double sign : {-1.0, 1.0}) {
    plot::Series band;
    band.label = sign < 0 ? "95 % of tests at the paper's values (" +
                                std::to_string(a.noise_runs) + " seeds)"
                          : "";
    const double y = a.noise_mean[r] + sign * a.noise_band[r];
    band.x = {0, 1};
    band.y = {y, y};
    band.dashed = true;
    band.color = plot::Color{120, 120, 120};
    if (std::isfinite(y)) c.series.push_back(band);
  }
  plot::write_chart_png(c, path.string());
}

// μ* against σ, one point per factor, and the μ* chaos alone would give.
void morris_chart(const SensitivityAnalysis& a, int r, int trajectories, const fs::path& path) {
  const SensitivityResponse& resp = sensitivity_responses()[r];
  plot::Chart c;
  c.title = std::string("Morris elementary effects on ") + resp.symbol + " (r = " +
            std::to_string(trajectories) + ")";
  c.x_label = "μ*: mean |effect| (° over the factor's range)";
  c.y_label = "σ: spread of the effects (°)";
  c.x_min = 0;
  c.y_min = 0;
  double top = 0;
  for (int i = 0; i < kSensitivityFactors; ++i) {
    const FactorEffect& e = a.effects[i][r];
    if (!std::isfinite(e.mu_star)) continue;
    plot::Series s;
    s.label = sensitivity_factors()[i].symbol + " (" + sensitivity_factors()[i].name + ")";
    s.x = {e.mu_star};
    s.y = {std::isfinite(e.sigma) ? e.sigma : 0};
    s.line = false;
    s.markers = true;
    top = std::max(top, s.y[0]);
    c.markers.push_back({s.x[0], s.y[0], sensitivity_factors()[i].symbol});
    c.series.push_back(s);
  }
  const double limit = a.chaos_mu_star_limit(r, trajectories);
  if (std::isfinite(limit)) {
    plot::Series n;
    n.label = "chaos alone stays left of this (97.5 %)";
    n.x = {limit, limit};
    n.y = {0, std::max(top, limit)};
    n.dashed = true;
    n.color = plot::Color{120, 120, 120};
    c.series.push_back(n);
  }
  plot::write_chart_png(c, path.string());
}

// The angles against L/d: single tests (seed 1), and at the paper's box
// the seeds' mean with the band where 95 % of single tests fall.
void scale_chart(const SensitivityAnalysis& a, const std::vector<SensitivityTest>& tests,
                 const fs::path& path) {
  plot::Chart c;
  c.title = "Scale effect: the paper's glass beads, 160 kPa, box scaled whole";
  c.x_label = "Box length / bead diameter L/d";
  c.y_label = "Angle (°)";
  c.y_min = 0;
  for (int r = 0; r < kSensitivityResponses; ++r) {
    plot::Series s;
    s.label = sensitivity_responses()[r].symbol;
    s.markers = true;
    std::map<double, std::pair<double, double>> by_ratio;  // L/d -> value, bar
    for (const SensitivityTest& t : tests) {
      const double ratio = t.scene.apparatus_as<ShearBox>()->length / (2 * t.scene.particles[0].radius);
      if (t.point.design == Design::scale) by_ratio[ratio] = {responses_of(t.result.summary)[r], NAN};
      if (t.point.design == Design::base) by_ratio[ratio] = {a.noise_mean[r], a.noise_band[r]};
    }
    for (const auto& [x, v] : by_ratio) {
      s.x.push_back(x);
      s.y.push_back(v.first);
      s.y_err.push_back(v.second);
    }
    c.series.push_back(s);
  }
  plot::write_chart_png(c, path.string());
}

double total_wall(const std::vector<SensitivityTest>& tests) {
  double s = 0;
  for (const SensitivityTest& t : tests) s += t.result.summary.wall_seconds;
  return s;
}

std::string summary_md(const SensitivityPreset& p, const SensitivityAnalysis& a,
                       const std::vector<SensitivityTest>& tests) {
  std::ostringstream o;
  o << "# Sensitivity study (" << p.name << ")\n\n" << tests.size() << " shear tests, "
    << format_number("%g", p.diameter_mm) << " mm beads poured, " << format_number("%g", p.stress_kpa)
    << " kPa, sheared " << format_number("%g", p.displacement_mm) << " mm; " << a.noise_runs
    << " seeds of the base, Morris r = " << p.trajectories << ", p = " << p.grid_levels
    << " (Δ = " << num(a.morris_delta, "%.3f") << "); " << num(total_wall(tests) / 60, "%.0f")
    << " min of tests in all (their summaries' wall times).\n\n";
  o << "| | " << sensitivity_responses()[0].symbol << " | " << sensitivity_responses()[1].symbol
    << " | " << sensitivity_responses()[2].symbol << " |\n|---|---|---|---|\n| base (°) ";
  for (double v : a.base) o << "| " << num(v) << " ";
  o << "|\n| mean over seeds (°) ";
  for (double v : a.noise_mean) o << "| " << num(v) << " ";
  o << "|\n| sd over seeds (°) ";
  for (double v : a.noise_sd) o << "| " << num(v) << " ";
  o << "|\n| 95 % of tests within ± (°) ";
  for (double v : a.noise_band) o << "| " << num(v) << " ";
  o << "|\n\nEffects in degrees: OAT = response at the factor's low / high end minus the base "
       "(seed 1), * where the test falls outside the seeds' 95 % band; Morris μ*, σ, μ over the "
       "factor's whole range, * where μ* exceeds what chaos alone gives in 97.5 % of studies.\n\n| factor | range | response | OAT low | "
       "OAT high | μ* | σ | μ |\n|---|---|---|---|---|---|---|---|\n";
  for (int i = 0; i < kSensitivityFactors; ++i) {
    const SensitivityFactor& f = sensitivity_factors()[i];
    for (int r = 0; r < kSensitivityResponses; ++r) {
      const FactorEffect& e = a.effects[i][r];
      o << "| " << (r == 0 ? f.symbol : "") << " | "
        << (r == 0 ? format_number("%g", f.low) + " – " + format_number("%g", f.high) + " " + f.unit : "")
        << " | " << sensitivity_responses()[r].symbol << " | " << num(e.oat_low)
        << (a.oat_beyond_chaos(i, r, false) ? " *" : "") << " | " << num(e.oat_high)
        << (a.oat_beyond_chaos(i, r, true) ? " *" : "") << " | " << num(e.mu_star)
        << (a.morris_beyond_chaos(i, r) ? " *" : "") << " | " << num(e.sigma) << " | "
        << num(e.mu) << " |\n";
    }
  }
  o << "\nμ* that chaos alone gives on average (√(2/π)·√2·sd/Δ), and stays below in 97.5 % "
       "of studies with r = " << p.trajectories << ": ";
  for (int r = 0; r < kSensitivityResponses; ++r)
    o << (r ? ", " : "") << sensitivity_responses()[r].symbol << " " << num(a.noise_mu_star[r])
      << "° and " << num(a.chaos_mu_star_limit(r, p.trajectories)) << "°";
  o << ".\n\ne poured: the void ratio of the settled pour (packing.txt); e sheared: as "
       "shearing starts, consolidated (box × the platen's height).\n\n| test | L/d | beads | "
       "e poured | e sheared | φ peak | φ residual | ψ max |\n|---|---|---|---|---|---|---|---|\n";
  for (const SensitivityTest& t : tests) {
    if (t.point.design == Design::noise || t.point.design == Design::morris) continue;
    const Responses y = responses_of(t.result.summary);
    o << "| " << t.point.label << " | "
      << num(t.scene.apparatus_as<ShearBox>()->length / (2 * t.scene.particles[0].radius), "%.1f") << " | "
      << t.scene.particles.size() << " | " << num(t.void_ratio, "%.3f") << " | "
      << num(t.shear_void_ratio, "%.3f") << " | " << num(y[0])
      << " | " << num(y[1]) << " | " << num(y[2]) << " |\n";
  }
  return o.str();
}

}  // namespace

void write_sensitivity_report(const fs::path& dir, const SensitivityPreset& preset,
                              const std::vector<SensitivityTest>& tests) {
  std::vector<SensitivityPoint> pts;
  std::vector<Responses> ys;
  for (const SensitivityTest& t : tests) {
    pts.push_back(t.point);
    ys.push_back(responses_of(t.result.summary));
  }
  const SensitivityAnalysis a = analyse_sensitivity(pts, ys, preset.grid_levels);
  write_file_atomic((dir / "sensitivity.csv").string(), tests_csv(tests));
  write_file_atomic((dir / "effects.csv").string(), effects_csv(a));
  write_file_atomic((dir / "summary.md").string(), summary_md(preset, a, tests));
  for (int r = 0; r < kSensitivityResponses; ++r) {
    const std::string stem = sensitivity_responses()[r].key;
    oat_chart(a, r, dir / ("oat_" + stem + ".png"));
    morris_chart(a, r, preset.trajectories, dir / ("morris_" + stem + ".png"));
  }
  scale_chart(a, tests, dir / "scale_effect.png");
}

}  // namespace simsols
