#include "app/experiment/size_study.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <sstream>

#include "app/experiment/apparatus_run.h"
#include "app/experiment/test_title.h"
#include "render/plot/chart.h"
#include "solver/apparatus/cell/cell_walls.h"
#include "solver/apparatus/shear_box/shear_analysis.h"
#include "solver/common/errors.h"
#include "solver/io/output.h"
#include "solver/io/scene_toml.h"
#include "solver/scene/contact_model.h"

namespace simsols {
namespace {

namespace fs = std::filesystem;
constexpr auto fmt = format_number;
constexpr double kDeg = 180 / M_PI;

void check_spec(const Scene& base, const std::string& base_name, const SizeStudySpec& spec) {
  const ApparatusKind& kind = required_apparatus_kind(base);
  if (!kind.resize)
    throw SceneError("not_applicable", base_name, 0, kind.name,
                     std::string(kind.test_noun) +
                         " has no walls to move apart: it is the bulk reference (--bulk)");
  if (base.cell()->specimen.method == Specimen::Method::Given)
    throw SceneError("not_applicable", base_name, 0, std::string(kind.name) + ".specimen.method",
                     "a given specimen cannot be resized: study the scene it was made from");
  if (!base.particles.empty())
    throw SceneError("not_applicable", base_name, 0, kind.name,
                     "the scene is placed already (its beads are given): resize the scene it was read from");
  if (spec.scales.empty()) throw UsageError("missing_field", "--scales", "give at least one scale");
  for (double s : spec.scales)
    if (!(s >= 0.5 && s <= 6))
      throw UsageError("out_of_range", "--scales", fmt("%g", s) + " is out of range, allowed [0.5, 6]");
  if (spec.seeds < 1 || spec.seeds > 100)
    throw UsageError("out_of_range", "--seeds", std::to_string(spec.seeds) + " is out of range, allowed [1, 100]");
}

std::string scale_text(double s) { return fmt("%g", s); }

SizeTest plan_test(const Scene& base, const std::string& base_name, const SizeStudySpec& spec, double scale,
                   int k, const std::string& out_dir) {
  const ApparatusKind& kind = required_apparatus_kind(base);
  SizeTest t;
  t.scale = scale;
  t.scene = base;
  kind.resize(t.scene, scale, spec.similar ? scale : 1.0);
  ApparatusCell& cell = *t.scene.cell();
  t.seed = cell.specimen.seed + k;
  cell.specimen.seed = t.seed;
  if (spec.precision) t.scene.numerics.precision = *spec.precision;
  t.scene.outputs.dump_csv = t.scene.outputs.dump_vtk = false;  // dozens of tests: no particle series
  t.scene.name = base.name + "_x" + scale_text(scale) + "_s" + std::to_string(t.seed);
  t.scene.source_text.clear();  // scene.toml is then the resolved scene
  t.ratio = cell_size_ratio(t.scene);
  place_scene(t.scene);
  validate_scene(t.scene, base_name + " (" + t.scene.name + ")");
  t.dir = fs::path(out_dir) / ("x" + scale_text(scale) + "_s" + std::to_string(t.seed));
  t.cost = expected_particle_steps(t.scene);
  return t;
}

// The headline keys (and wall_seconds) of a finished test's summary.txt.
std::map<std::string, double> read_results(const ApparatusKind& kind, const fs::path& dir) {
  const std::string path = (dir / "summary.txt").string();
  const auto keys = summary_keys(read_text(path));
  std::map<std::string, double> out;
  for (const HeadlineResult& h : kind.headlines) {
    const auto it = keys.find(h.key);
    out[h.key] = it == keys.end() ? NAN : std::strtod(it->second.c_str(), nullptr);
  }
  const auto w = keys.find("wall_seconds");
  out["wall_seconds"] = w == keys.end() ? NAN : std::strtod(w->second.c_str(), nullptr);
  return out;
}

void print_result(const ApparatusKind& kind, const SizeTest& t) {
  std::string line = t.scene.name + " (L/d " + fmt("%.1f", t.ratio) + ", " +
                     std::to_string(t.scene.particles.size()) + " beads):";
  for (const HeadlineResult& h : kind.headlines) line += " " + std::string(h.key) + " " + fmt("%.4g", t.results.at(h.key));
  std::printf("%s, %.0f s\n", line.c_str(), t.results.at("wall_seconds"));
  std::fflush(stdout);
}

std::string tests_csv(const ApparatusKind& kind, const std::vector<SizeTest>& tests) {
  std::ostringstream o;
  o.precision(8);
  o << "scale,size_ratio_L_over_d,seed,beads";
  for (const HeadlineResult& h : kind.headlines) o << ',' << h.key;
  o << ",wall_s\n";
  for (const SizeTest& t : tests) {
    o << t.scale << ',' << t.ratio << ',' << t.seed << ',' << t.scene.particles.size();
    for (const HeadlineResult& h : kind.headlines) o << ',' << t.results.at(h.key);
    o << ',' << t.results.at("wall_seconds") << '\n';
  }
  return o.str();
}

std::string summary_csv(const ApparatusKind& kind, const std::vector<SizePoint>& points) {
  std::ostringstream o;
  o.precision(6);
  o << "scale,size_ratio_L_over_d,specimens,beads";
  for (const HeadlineResult& h : kind.headlines) o << ',' << h.key << ',' << h.key << "_ci95";
  o << ",wall_s_per_test\n";
  for (const SizePoint& p : points) {
    o << p.scale << ',' << p.ratio << ',' << p.specimens << ',' << p.beads;
    for (const Interval& v : p.values) o << ',' << v.mean << ',' << v.half_width;
    o << ',' << p.wall_seconds << '\n';
  }
  return o.str();
}

std::string pm(const Interval& v, const char* f) { return fmt(f, v.mean) + " ± " + fmt(f, v.half_width); }

void write_plot(const ApparatusKind& kind, const std::string& what, size_t h, const std::vector<SizePoint>& points,
                const std::optional<BulkValue>& bulk, const std::string& path) {
  plot::Chart c;
  c.title = std::string(kind.title) + ", " + what + " (mean of specimens, 95 % interval)";
  c.x_label = "size ratio L / d";
  c.y_label = kind.headlines[h].symbol;
  plot::Series s;
  s.label = "apparatus";
  s.markers = true;
  for (const SizePoint& p : points) {
    s.x.push_back(p.ratio);
    s.y.push_back(p.values[h].mean);
    s.y_err.push_back(p.values[h].half_width);
  }
  c.series.push_back(s);
  const Interval* b = bulk ? bulk->for_match(kind.headlines[h].bulk) : nullptr;
  if (b && !points.empty()) {
    const double x0 = points.front().ratio, x1 = points.back().ratio;
    plot::Series line;
    line.label = "bulk (periodic cell)";
    line.x = {x0, x1};
    line.y = {b->mean, b->mean};
    line.color = plot::palette_color(1);
    c.series.push_back(line);
    for (double sign : {-1.0, 1.0}) {
      plot::Series band = line;
      band.label = sign < 0 ? "bulk 95 % interval" : "";
      band.y = {b->mean + sign * b->half_width, b->mean + sign * b->half_width};
      band.dashed = true;
      c.series.push_back(band);
    }
  }
  plot::write_chart_png(c, path);
}

}  // namespace

BulkValue read_bulk_value(const std::string& path) {
  std::istringstream in(read_text(path));
  std::string header, row;
  if (!std::getline(in, header) || !std::getline(in, row))
    throw SceneError("io", path, 0, "--bulk", "no table: give a periodic-cell campaign's summary.csv");
  const std::vector<std::string> names = split_csv_line(header), values = split_csv_line(row);
  auto column = [&](const std::string& name) {
    const auto it = std::find(names.begin(), names.end(), name);
    if (it == names.end() || size_t(it - names.begin()) >= values.size())
      throw SceneError("missing_field", path, 2, name, "a periodic-cell campaign's summary.csv has this column");
    const double v = std::strtod(values[it - names.begin()].c_str(), nullptr);
    if (!std::isfinite(v)) throw SceneError("out_of_range", path, 2, name, "not a finite number");
    return v;
  };
  BulkValue b;
  b.source = path;
  b.p_kpa = column("p_kPa");
  b.inertial = column("inertial_number");
  b.specimens = static_cast<int>(column("specimens"));
  const double mu = column("stress_ratio"), mu_ci = std::fabs(column("stress_ratio_ci95"));
  b.plane = {std::atan(mu) * kDeg, 0.5 * (std::atan(mu + mu_ci) - std::atan(mu - mu_ci)) * kDeg, b.specimens};
  b.mobilised = {column("friction_angle_deg"), std::fabs(column("friction_angle_ci95")), b.specimens};
  return b;
}

std::string size_study_title(const Scene& base, const SizeStudySpec& spec) {
  return base.name + (spec.similar ? ", height grows with the box" : ", fixed height");
}

std::vector<SizeTest> plan_size_study(const Scene& base, const std::string& base_name,
                                      const SizeStudySpec& spec, const std::string& out_dir) {
  check_spec(base, base_name, spec);
  std::vector<SizeTest> tests;
  for (double scale : spec.scales)
    for (int k = 0; k < spec.seeds; ++k) tests.push_back(plan_test(base, base_name, spec, scale, k, out_dir));
  return tests;
}

std::vector<SizePoint> size_points(const ApparatusKind& kind, const std::vector<SizeTest>& tests) {
  std::map<double, std::vector<const SizeTest*>> groups;
  for (const SizeTest& t : tests) groups[t.scale].push_back(&t);
  std::vector<SizePoint> out;
  for (const auto& [scale, group] : groups) {
    SizePoint p;
    p.scale = scale;
    p.ratio = group.front()->ratio;
    p.specimens = static_cast<int>(group.size());
    p.beads = static_cast<int>(group.front()->scene.particles.size());
    for (const HeadlineResult& h : kind.headlines) {
      std::vector<double> v;
      for (const SizeTest* t : group) v.push_back(t->results.at(h.key));
      p.values.push_back(mean_ci95(v));
    }
    for (const SizeTest* t : group) p.wall_seconds += t->results.at("wall_seconds") / double(group.size());
    out.push_back(std::move(p));
  }
  return out;
}

// Whether a size's mean headline is within `tolerance` of the bulk value.
static bool mean_within(const SizePoint& p, size_t headline, const Interval& bulk, double tolerance) {
  return std::fabs(p.values[headline].mean - bulk.mean) <= tolerance;
}

double ratio_within(const std::vector<SizePoint>& points, size_t headline, const Interval& bulk,
                    double tolerance) {
  double from = NAN;
  for (auto it = points.rbegin(); it != points.rend(); ++it) {
    if (!mean_within(*it, headline, bulk, tolerance)) break;
    from = it->ratio;
  }
  return from;
}

// Where no size and every larger one is within `tolerance`: the sizes that
// are, one by one ("at L/d = 14.2 only, not at the larger ones"), or none.
static std::string sizes_within(const std::vector<SizePoint>& points, size_t headline,
                                const Interval& bulk, double tolerance) {
  std::string at;
  for (const SizePoint& p : points)
    if (mean_within(p, headline, bulk, tolerance)) at += (at.empty() ? "" : ", ") + fmt("%.1f", p.ratio);
  return at.empty() ? "at none of these sizes" : "at L/d = " + at + " only, not at the larger ones";
}

std::string size_summary_markdown(const ApparatusKind& kind, const std::vector<SizePoint>& points,
                                  const std::optional<BulkValue>& bulk) {
  std::ostringstream o;
  o << "| scale | L/d | beads | specimens |";
  for (const HeadlineResult& h : kind.headlines) o << ' ' << h.symbol << " |";
  o << " wall per test (s) |\n|---|---|---|---|";
  for (size_t i = 0; i < kind.headlines.size(); ++i) o << "---|";
  o << "---|\n";
  for (const SizePoint& p : points) {
    o << "| " << fmt("%g", p.scale) << " | " << fmt("%.1f", p.ratio) << " | " << p.beads << " | " << p.specimens << " |";
    for (const Interval& v : p.values) o << ' ' << pm(v, "%.3g") << " |";
    o << ' ' << fmt("%.0f", p.wall_seconds) << " |\n";
  }
  if (!bulk) return o.str();
  o << "\nBulk value (periodic cell, " << fmt("%g", bulk->p_kpa) << " kPa, I = " << fmt("%g", bulk->inertial) << ", "
    << bulk->specimens << " specimens): atan(τ/σ) = " << pm(bulk->plane, "%.2f") << "°, φ_mob = "
    << pm(bulk->mobilised, "%.2f") << "°.\n\n";
  for (size_t h = 0; h < kind.headlines.size(); ++h) {
    const Interval* b = bulk->for_match(kind.headlines[h].bulk);
    if (!b) continue;
    o << "| L/d | " << kind.headlines[h].symbol << " − bulk (°) |\n|---|---|\n";
    for (const SizePoint& p : points) {
      const Interval& v = p.values[h];
      const double ci = std::hypot(v.half_width, b->half_width);
      o << "| " << fmt("%.1f", p.ratio) << " | " << fmt("%+.2f", v.mean - b->mean) << " ± " << fmt("%.2f", ci) << " |\n";
    }
    const double from = ratio_within(points, h, *b, 1.0);
    o << "\n" << kind.headlines[h].symbol << ": the mean within 1° of the bulk value "
      << (std::isnan(from) ? sizes_within(points, h, *b, 1.0) : "from L/d = " + fmt("%.1f", from) + " on");
    double widest = 0;  // of the differences' intervals from there on
    for (const SizePoint& p : points)
      if (p.ratio >= from) widest = std::max(widest, std::hypot(p.values[h].half_width, b->half_width));
    if (!std::isnan(from) && !(widest <= 1))
      o << " (but the difference's interval, up to ±" << fmt("%.2f", widest)
        << "°, is wider than 1°: more specimens would tell)";
    o << ".\n\n";
  }
  return o.str();
}

CampaignOutcome run_size_study(std::vector<SizeTest>& tests, const std::optional<BulkValue>& bulk,
                               const std::string& what, const std::string& out_dir, const CampaignRun& run) {
  fs::create_directories(out_dir);
  if (tests.empty()) return {};
  const ApparatusKind& kind = required_apparatus_kind(tests.front().scene);
  // scene.toml: written as a test starts, so its checkpoint resumes it
  CampaignLoop loop = campaign_loop(tests, std::string(kind.label) + " size tests", "scene.toml");
  loop.keep = [&](size_t k) { tests[k].results = read_results(kind, tests[k].dir); };
  loop.run = [&](size_t k, ProgrammeRunOptions& o) {
    const TestRun r = run_scene_test(tests[k].scene, o, [&](const std::string& line) {
      if (!run.quiet) std::fprintf(stderr, "%s\n", line.c_str());
    });
    if (r.state.interrupted) return true;
    tests[k].results = read_results(kind, tests[k].dir);
    return false;
  };
  loop.print = [&](size_t k) { print_result(kind, tests[k]); };
  const CampaignOutcome outcome = run_campaign_loop(loop, run);
  if (outcome.interrupted || !run.writes_report()) return outcome;
  const std::vector<SizePoint> points = size_points(kind, tests);
  write_file_atomic((fs::path(out_dir) / "tests.csv").string(), tests_csv(kind, tests));
  write_file_atomic((fs::path(out_dir) / "summary.csv").string(), summary_csv(kind, points));
  write_file_atomic((fs::path(out_dir) / "summary.md").string(), size_summary_markdown(kind, points, bulk));
  for (size_t h = 0; h < kind.headlines.size(); ++h)
    write_plot(kind, what, h, points, bulk, (fs::path(out_dir) / ("size_" + std::string(kind.headlines[h].key) + ".png")).string());
  return outcome;
}

}  // namespace simsols
