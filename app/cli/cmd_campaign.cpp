// simsols campaign: the reference paper's programme of direct shear tests,
// 5 bead sizes (its Table 1) x 4 normal stresses (50, 160, 280, 400 kPa),
// or any subset, any sizes and stresses.
//
// Every test runs from a base scene (default: the built-in shear_box.toml)
// with specimen.diameter, specimen.layers (Table 1, or --layers) and
// normal_stress replaced, in OUT/d<size>mm_<stress>kPa/ (see shear_run.h).
// Resumable: a test whose summary.txt exists is not rerun, an interrupted
// one continues from its checkpoint. Afterwards, per bead size, the curves
// of its stresses on common axes (the paper's Figures 3-7), the
// Mohr-Coulomb envelopes of the peak and residual strengths, and
// OUT/summary.csv / .md (campaign_report.h).
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>

#include "app/experiment/campaign_report.h"
#include "app/cli/commands.h"
#include "app/experiment/paper_tests.h"
#include "solver/scene/contact_model.h"
#include "solver/common/errors.h"
#include "app/cli/interrupt.h"
#include "solver/io/output.h"
#include "app/experiment/run_cost.h"
#include "solver/io/scene_toml.h"
#include "solver/apparatus/shear_box.h"
#include "app/experiment/shear_plots.h"
#include "app/experiment/shear_run.h"

namespace simsols {
namespace {

constexpr auto fmt = format_number;  // printf conversion of one number (output.h)

namespace fs = std::filesystem;

struct CampaignOptions {
  std::string base;  // empty = the built-in shear_box.toml (kDefaultSceneName)
  std::string out_dir;
  std::vector<double> sizes_mm{2.38125, 3.175, 3.96875, 4.7625, 6.35};
  std::vector<double> stresses_kpa{50, 160, 280, 400};
  int layers = 0;  // 0 = Table 1
  std::string precision;
  double displacement_mm = 0;  // 0 = the base scene's
  bool quiet = false;
};

// A test finished earlier: its summary as today's analysis reads its rows
// (the apparatus' fields from its summary.txt), rewritten with its plots
// when that differs from the file.
ShearSummary reanalysed(const fs::path& dir, const std::string& name,
                        const std::vector<ShearRow>& rows) {
  const std::string text = read_text(dir / "summary.txt");
  ShearSummary s = parse_shear_summary(text);
  analyse_shear_rows(rows, s);
  if (const std::string now = shear_summary_text(s); now != text) {
    write_shear_plots(dir.string(), name, rows, s);
    write_file_atomic((dir / "summary.txt").string(), now);
  }
  return s;
}

struct Test {
  double d_mm = 0, s_kpa = 0;
  Scene scene;
  fs::path dir;
  double cost = 0;  // estimated particle-steps
  ShearRunResult result;
};

// Particle-steps the test will take: preparation (~60 ms simulated) and the
// shear at the speed the inertial number sets (height ~ layers x 0.8 d).
double estimated_cost(const Scene& s) {
  const ShearBox& b = *s.shear_box;
  const double dt = effective_time_step(s);
  const double d = 2 * s.particles[0].radius;
  const double rho = s.materials[s.particles[0].material].density;
  const double height = 0.8 * d * std::max(1, b.specimen.layers);
  const double v = b.shear_speed > 0 ? b.shear_speed
                                     : speed_for_inertial_number(b.inertial_number, height, d, rho,
                                                                 b.normal_stress);
  return s.particles.size() * (0.06 + b.shear_displacement / v) / dt;
}

int campaign(const CampaignOptions& opt) {
  // Everything is checked and every scene built before anything runs.
  const std::string base_name = opt.base.empty() ? kDefaultSceneName : opt.base;
  Scene base = opt.base.empty() ? parse_scene(default_shear_scene_text(), base_name)
                                : load_scene(opt.base);
  if (!base.shear_box)
    throw SceneError("missing_field", base_name, 0, "shear_box",
                     "the campaign's base scene must describe a shear box");
  for (double d : opt.sizes_mm)
    if (!(d > 0 && d < 60))
      throw SceneError("out_of_range", "command line", 0, "--sizes",
                       fmt("%g", d) + " mm is out of range, allowed (0, 60) mm");
  for (double s : opt.stresses_kpa)
    if (!(s > 0 && s <= 1e6))
      throw SceneError("out_of_range", "command line", 0, "--stresses",
                       fmt("%g", s) + " kPa is out of range, allowed (0, 1e6] kPa");
  if (opt.layers < 0 || opt.layers > 200)
    throw SceneError("out_of_range", "command line", 0, "--layers",
                     std::to_string(opt.layers) + " is out of range, allowed [1, 200] (0 = Table 1)");
  if (!opt.precision.empty() && opt.precision != "float" && opt.precision != "double")
    throw SceneError("bad_enum", "command line", 0, "--precision",
                     "'" + opt.precision + "' is not one of: float, double");
  if (opt.displacement_mm < 0)
    throw SceneError("out_of_range", "command line", 0, "--displacement", "must be > 0 mm");

  std::vector<Test> tests;
  for (double d : opt.sizes_mm) {
    const int layers = opt.layers > 0 ? opt.layers : table1_layers(d);
    if (layers == 0)
      throw SceneError("out_of_range", "command line", 0, "--sizes",
                       fmt("%g", d) +
                           " mm is not a Table 1 size (2.38125, 3.175, 3.96875, 4.7625, 6.35); "
                           "give --layers for other sizes");
    for (double s : opt.stresses_kpa) {
      Test t;
      t.d_mm = d;
      t.s_kpa = s;
      Scene sc = paper_test_scene(base, base_name, d, s, opt.layers, [&](Scene& x) {
        if (opt.displacement_mm > 0) x.shear_box->shear_displacement = opt.displacement_mm * 1e-3;
        if (!opt.precision.empty())
          x.numerics.precision = opt.precision == "float" ? Precision::Float : Precision::Double;
      });
      validate_scene(sc, base_name + " (" + sc.name + ")");
      t.scene = std::move(sc);
      t.dir = fs::path(opt.out_dir) / t.scene.name;
      t.cost = estimated_cost(t.scene);
      tests.push_back(std::move(t));
    }
  }
  fs::create_directories(opt.out_dir);

  InterruptScope interrupt;
  double total_cost = 0, done_cost = 0, spent = 0;
  for (const Test& t : tests)
    if (!shear_finished(t.dir.string())) total_cost += t.cost;
  if (!opt.quiet)
    std::fprintf(stderr, "[campaign] %zu tests, ~%.3g particle-steps to run, ~%s at %.0e "
                 "particle-steps/s\n", tests.size(), total_cost,
                 human_seconds(total_cost / kAssumedRate).c_str(), kAssumedRate);
  for (size_t k = 0; k < tests.size(); ++k) {
    Test& t = tests[k];
    const std::string label = "campaign " + std::to_string(k + 1) + "/" +
                              std::to_string(tests.size()) + " " + t.scene.name;
    if (shear_finished(t.dir.string())) {
      t.result.rows = parse_shear_rows_csv(read_text(t.dir / "shear.csv"));
      t.result.summary = reanalysed(t.dir, t.scene.name, t.result.rows);
      t.result.finished = true;
      if (!opt.quiet) std::fprintf(stderr, "[%s] finished earlier, kept\n", label.c_str());
      continue;
    }
    if (!opt.quiet && done_cost > 0) {
      const double rate = spent / done_cost;
      std::fprintf(stderr, "[campaign] %zu/%zu tests, %.0f s so far, ETA %.0f s\n", k,
                   tests.size(), spent, rate * (total_cost - done_cost));
    }
    ShearRunOptions o;
    o.out_dir = t.dir.string();
    o.label = label;
    o.quiet = opt.quiet;
    o.resume = fs::exists(t.dir / "checkpoint.bin") && fs::exists(t.dir / "shear.csv");
    o.stop_requested = interrupt.stop_function();
    o.later_particle_steps = total_cost - done_cost - t.cost;
    const auto t0 = std::chrono::steady_clock::now();
    t.result = run_shear(t.scene, o);
    if (t.result.interrupted) {
      std::printf("campaign interrupted in test %zu/%zu (%s): its checkpoint and rows are in %s; "
                  "%zu of %zu tests finished. Resume with the same command.\n",
                  k + 1, tests.size(), t.scene.name.c_str(), t.dir.string().c_str(), k,
                  tests.size());
      return interrupt.exit_status();
    }
    spent += std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    done_cost += t.cost;
    const ShearSummary& s = t.result.summary;
    std::printf("%-22s peak tau/sigma %.3f (phi %.2f deg), residual %.3f (phi %.2f deg), "
                "max dilatancy %.2f deg, %.0f s\n",
                t.scene.name.c_str(), s.peak_ratio, s.peak_angle, s.residual_ratio,
                s.residual_angle, s.max_dilatancy_angle, s.wall_seconds);
    std::fflush(stdout);
  }

  std::vector<CampaignEntry> entries;
  for (const Test& t : tests)
    entries.push_back({t.d_mm, t.s_kpa, t.scene.shear_box->specimen.layers,
                       static_cast<int>(t.scene.particles.size()), t.result.rows,
                       t.result.summary});
  write_campaign_report(opt.out_dir, base_name, opt.sizes_mm, entries, spent);
  std::printf("campaign done: %zu tests in %s (summary.md, summary.csv, *.png)\n", tests.size(),
              opt.out_dir.c_str());
  return 0;
}

}  // namespace

CommandRunner add_campaign_command(CLI::App& app) {
  auto opt = std::make_shared<CampaignOptions>();
  CLI::App* cmd = app.add_subcommand(
      "campaign", "Run the paper's direct shear programme (5 sizes x 4 stresses), resumable");
  cmd->add_option("base", opt->base, "Base shear-box scene (default: the built-in shear_box.toml)");
  cmd->add_option("--out,-o", opt->out_dir, "Output folder (rerun to resume)")->required();
  cmd->add_option("--sizes", opt->sizes_mm, "Bead diameters in mm (default: Table 1)")
      ->delimiter(',');
  cmd->add_option("--stresses", opt->stresses_kpa, "Normal stresses in kPa (default 50,160,280,400)")
      ->delimiter(',');
  cmd->add_option("--layers", opt->layers, "Layers for every size (default: Table 1)");
  cmd->add_option("--precision", opt->precision, "float or double (default: the base scene's)");
  cmd->add_option("--displacement", opt->displacement_mm,
                  "Horizontal displacement to shear, mm (default: the base scene's)");
  cmd->add_flag("--quiet,-q", opt->quiet, "No progress lines");
  return [opt] { return campaign(*opt); };
}

}  // namespace simsols
