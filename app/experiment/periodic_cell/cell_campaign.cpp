#include "app/experiment/periodic_cell/cell_campaign.h"

#include <cmath>
#include <cstdio>
#include <map>
#include <sstream>

#include "app/experiment/periodic_cell/cell_plots.h"
#include "app/experiment/shear_box/study_stats.h"
#include "app/experiment/test_title.h"
#include "render/plot/chart.h"
#include "solver/apparatus/periodic_cell/periodic_cell.h"
#include "solver/apparatus/shear_box/shear_analysis.h"
#include "solver/common/errors.h"
#include "solver/io/output.h"
#include "solver/scene/contact_model.h"

namespace simsols {
namespace {

namespace fs = std::filesystem;
constexpr auto fmt = format_number;

const PeriodicCell& cell_of(const Scene& s) { return *s.apparatus_as<PeriodicCell>(); }

double end_strain(const PeriodicCell& c) {
  return c.test == PeriodicCell::Test::SimpleShear ? c.shear_strain : c.axial_strain;
}

void check_spec(const Scene& base, const std::string& base_name, const CellCampaignSpec& spec) {
  if (!base.apparatus_as<PeriodicCell>())
    throw SceneError("missing_field", base_name, 0, "periodic_cell",
                     "the periodic-cell campaign's base scene must describe a periodic cell");
  for (double p : spec.pressures_kpa)
    if (!(p > 0 && p <= 1e6))
      throw UsageError("out_of_range", "--stresses", fmt("%g", p) + " kPa is out of range, allowed (0, 1e6] kPa");
  for (double i : spec.inertial_numbers)
    if (!(i > 0 && i <= 1))
      throw UsageError("out_of_range", "--inertial-numbers", fmt("%g", i) + " is out of range, allowed (0, 1]");
  if (spec.seeds < 1 || spec.seeds > 100)
    throw UsageError("out_of_range", "--seeds", std::to_string(spec.seeds) + " is out of range, allowed [1, 100]");
  if (spec.seeds > 1 && cell_of(base).given)
    throw SceneError("not_applicable", base_name, 0, "periodic_cell.given",
                     "a given specimen has no seed to vary: campaign over the scene it was made from");
}

// The base with its pressure, inertial number and seed replaced: a new gas.
Scene test_scene(const Scene& base, double p_kpa, double inertial, std::int64_t seed,
                 const std::string& base_name) {
  Scene s = base;
  PeriodicCell& c = *s.apparatus_as<PeriodicCell>();
  c.pressure = p_kpa * 1e3;
  c.inertial_number = inertial;
  if (!c.given && seed != c.seed) {
    c.seed = seed;
    s.particles.clear();
    s.periodic.reset();
    if (std::optional<SceneIssue> bad = build_periodic_cell(s))
      throw SceneError(bad->code, base_name, 0, bad->field, bad->message);
  }
  s.name = base.name + "_p" + fmt("%g", p_kpa) + "kPa_I" + fmt("%g", inertial) + "_s" + std::to_string(seed);
  s.source_text.clear();  // scene.toml is then the resolved scene
  return s;
}

CellRunResult finished_cell_test(const fs::path& dir, const PeriodicCell& c) {
  CellRunResult r;
  r.rows = parse_cell_rows_csv(read_text((dir / "cell.csv").string()));
  r.summary = cell_summary(r.rows, 0.5 * end_strain(c));
  const auto keys = summary_keys(read_text((dir / "summary.txt").string()));
  if (const auto it = keys.find("wall_seconds"); it != keys.end()) r.summary.wall_seconds = std::stod(it->second);
  r.state.finished = true;
  return r;
}

void print_result(const CellCampaignTest& t) {
  const CellSummary& s = t.result.summary;
  std::printf("%-34s ratio %.4f +- %.4f, phi %.4f +- %.4f, Z %.3f, eps_v %.4f, %.0f s\n", t.scene.name.c_str(),
              s.ratio.mean, s.ratio.half_width, s.phi.mean, s.phi.half_width, s.z.mean, s.volumetric.mean,
              s.wall_seconds);
  std::fflush(stdout);
}

std::string tests_csv(const std::vector<CellCampaignTest>& tests) {
  std::ostringstream o;
  o.precision(8);
  o << "p_kPa,inertial_number,seed,particles,stress_ratio,stress_ratio_ci95,solid_fraction,"
       "solid_fraction_ci95,coordination,coordination_ci95,volumetric_strain,solid_fraction_compressed,"
       "coordination_compressed,friction_angle_deg,friction_angle_ci95,wall_s\n";
  for (const CellCampaignTest& t : tests) {
    const CellSummary& s = t.result.summary;
    o << t.p_kpa << ',' << t.inertial << ',' << t.seed << ',' << t.scene.particles.size() << ','
      << s.ratio.mean << ',' << s.ratio.half_width << ',' << s.phi.mean << ',' << s.phi.half_width << ','
      << s.z.mean << ',' << s.z.half_width << ',' << s.volumetric.mean << ',' << s.phi_compressed << ','
      << s.z_compressed << ',' << s.angle.mean << ',' << s.angle.half_width << ',' << s.wall_seconds << '\n';
  }
  return o.str();
}

void write_point_plot(const std::vector<CellPoint>& points, const std::string& path, const std::string& y_label,
                      double CellPoint::*value, double CellPoint::*ci) {
  plot::Chart c;
  c.title = "Periodic cell, steady simple shear (mean of specimens, 95 % interval)";
  c.x_label = "inertial number I";
  c.y_label = y_label;
  c.x_log = true;
  std::map<double, plot::Series> by_pressure;
  for (const CellPoint& p : points) {
    plot::Series& s = by_pressure[p.p_kpa];
    s.label = "p = " + fmt("%g", p.p_kpa) + " kPa";
    s.markers = true;
    s.x.push_back(p.inertial);
    s.y.push_back(p.*value);
    s.y_err.push_back(p.*ci);
  }
  for (auto& [p, s] : by_pressure) c.series.push_back(s);
  plot::write_chart_png(c, path);
}

}  // namespace

std::vector<CellPoint> cell_points(const std::vector<CellCampaignTest>& tests) {
  std::map<std::pair<double, double>, std::vector<const CellCampaignTest*>> groups;
  for (const CellCampaignTest& t : tests) groups[{t.p_kpa, t.inertial}].push_back(&t);
  std::vector<CellPoint> out;
  for (const auto& [key, group] : groups) {
    CellPoint p;
    p.p_kpa = key.first;
    p.inertial = key.second;
    p.specimens = static_cast<int>(group.size());
    std::vector<double> mu, phi, z, ev, angle;
    for (const CellCampaignTest* t : group) {
      mu.push_back(t->result.summary.ratio.mean);
      phi.push_back(t->result.summary.phi.mean);
      z.push_back(t->result.summary.z.mean);
      ev.push_back(t->result.summary.volumetric.mean);
      angle.push_back(t->result.summary.angle.mean);
    }
    const Interval a = mean_ci95(mu), b = mean_ci95(phi), c = mean_ci95(z), d = mean_ci95(ev);
    p.mu = a.mean, p.mu_ci = a.half_width, p.phi = b.mean, p.phi_ci = b.half_width;
    p.z = c.mean, p.z_ci = c.half_width, p.ev = d.mean, p.ev_ci = d.half_width;
    const Interval f = mean_ci95(angle);
    p.angle = f.mean, p.angle_ci = f.half_width;
    out.push_back(p);
  }
  return out;
}

std::string cell_points_csv(const std::vector<CellPoint>& points) {
  std::ostringstream o;
  o.precision(6);
  o << "p_kPa,inertial_number,specimens,stress_ratio,stress_ratio_ci95,solid_fraction,solid_fraction_ci95,"
       "coordination,coordination_ci95,volumetric_strain,volumetric_strain_ci95,friction_angle_deg,"
       "friction_angle_ci95\n";
  for (const CellPoint& p : points)
    o << p.p_kpa << ',' << p.inertial << ',' << p.specimens << ',' << p.mu << ',' << p.mu_ci << ',' << p.phi
      << ',' << p.phi_ci << ',' << p.z << ',' << p.z_ci << ',' << p.ev << ',' << p.ev_ci << ',' << p.angle << ','
      << p.angle_ci << '\n';
  return o.str();
}

std::string cell_points_markdown(const std::vector<CellPoint>& points) {
  std::ostringstream o;
  o << "| p (kPa) | I | specimens | τ/σ_zz | φ_mob (°) | Φ | Z | ε_v |\n|---|---|---|---|---|---|---|---|\n";
  for (const CellPoint& p : points)
    o << "| " << fmt("%g", p.p_kpa) << " | " << fmt("%g", p.inertial) << " | " << p.specimens << " | "
      << fmt("%.4f", p.mu) << " ± " << fmt("%.4f", p.mu_ci) << " | " << fmt("%.2f", p.angle) << " ± "
      << fmt("%.2f", p.angle_ci) << " | " << fmt("%.4f", p.phi) << " ± "
      << fmt("%.4f", p.phi_ci) << " | " << fmt("%.3f", p.z) << " ± " << fmt("%.3f", p.z_ci) << " | "
      << fmt("%.4f", p.ev) << " ± " << fmt("%.4f", p.ev_ci) << " |\n";
  return o.str();
}

std::vector<CellCampaignTest> plan_cell_campaign(const Scene& base, const std::string& base_name,
                                                 const CellCampaignSpec& spec, const std::string& out_dir) {
  check_spec(base, base_name, spec);
  const PeriodicCell& c = cell_of(base);
  const std::vector<double> pressures = spec.pressures_kpa.empty() ? std::vector{c.pressure * 1e-3} : spec.pressures_kpa;
  const std::vector<double> numbers = spec.inertial_numbers.empty() ? std::vector{c.inertial_number} : spec.inertial_numbers;
  std::vector<CellCampaignTest> tests;
  for (double p : pressures)
    for (double i : numbers)
      for (int k = 0; k < spec.seeds; ++k) {
        CellCampaignTest t;
        t.p_kpa = p;
        t.inertial = i;
        t.seed = c.seed + k;
        t.scene = test_scene(base, p, i, t.seed, base_name);
        if (spec.precision) t.scene.numerics.precision = *spec.precision;
        validate_scene(t.scene, base_name + " (" + t.scene.name + ")");
        t.dir = fs::path(out_dir) / ("p" + fmt("%g", p) + "kPa_I" + fmt("%g", i) + "_s" + std::to_string(t.seed));
        t.cost = expected_particle_steps(t.scene);
        tests.push_back(std::move(t));
      }
  return tests;
}

CampaignOutcome run_cell_campaign(std::vector<CellCampaignTest>& tests, const std::string& out_dir,
                                  const CampaignRun& run) {
  fs::create_directories(out_dir);
  CampaignLoop loop = campaign_loop(tests, "periodic-cell tests", "cell.csv");
  loop.keep = [&](size_t k) { tests[k].result = finished_cell_test(tests[k].dir, cell_of(tests[k].scene)); };
  loop.run = [&](size_t k, ProgrammeRunOptions& o) {
    tests[k].result = typed_result<CellProgramme>(run_test(tests[k].scene, o));
    return tests[k].result.state.interrupted;
  };
  loop.print = [&](size_t k) { print_result(tests[k]); };
  const CampaignOutcome outcome = run_campaign_loop(loop, run);
  if (outcome.interrupted || !run.writes_report()) return outcome;
  const std::vector<CellPoint> points = cell_points(tests);
  write_file_atomic((fs::path(out_dir) / "tests.csv").string(), tests_csv(tests));
  write_file_atomic((fs::path(out_dir) / "summary.csv").string(), cell_points_csv(points));
  write_file_atomic((fs::path(out_dir) / "summary.md").string(), cell_points_markdown(points));
  write_point_plot(points, (fs::path(out_dir) / "mu_I.png").string(), "stress ratio τ / σ_zz", &CellPoint::mu,
                   &CellPoint::mu_ci);
  write_point_plot(points, (fs::path(out_dir) / "phi_I.png").string(), "solid fraction Φ", &CellPoint::phi,
                   &CellPoint::phi_ci);
  return outcome;
}

}  // namespace simsols
