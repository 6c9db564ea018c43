#include "app/experiment/shear_box/campaign.h"
#include "app/experiment/test_title.h"

#include <algorithm>
#include <chrono>
#include <cstdio>

#include "app/experiment/shear_box/campaign_report.h"
#include "app/experiment/shear_box/paper_tests.h"
#include "app/experiment/run_cost.h"
#include "app/experiment/shear_box/shear_plots.h"
#include "solver/apparatus/shear_box/shear_box.h"
#include "solver/apparatus/registry.h"
#include "solver/common/errors.h"
#include "solver/io/output.h"
#include "solver/io/scene_toml.h"
#include "solver/scene/contact_model.h"

namespace simsols {
namespace {

constexpr auto fmt = format_number;  // printf conversion of one number (output.h)

namespace fs = std::filesystem;

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

}  // namespace

ShearRunResult finished_shear_test(const fs::path& dir, const std::string& title) {
  ShearRunResult r;
  r.rows = parse_shear_rows_csv(read_text(dir / "shear.csv"));
  r.summary = reanalysed(dir, title, r.rows);
  r.finished = true;
  return r;
}

namespace {

void check_spec(const Scene& base, const std::string& base_name, const CampaignSpec& spec) {
  if (!base.apparatus_as<ShearBox>())
    throw SceneError("missing_field", base_name, 0, "shear_box",
                     "the paper's programme runs in a shear box: the base scene has none");
  for (double d : spec.sizes_mm)
    if (!(d > 0 && d < 60))
      throw UsageError("out_of_range", "--sizes",
                       fmt("%g", d) + " mm is out of range, allowed (0, 60) mm");
  for (double s : spec.stresses_kpa)
    if (!(s > 0 && s <= 1e6))
      throw UsageError("out_of_range", "--stresses",
                       fmt("%g", s) + " kPa is out of range, allowed (0, 1e6] kPa");
  if (spec.layers < 0 || spec.layers > 200)
    throw UsageError("out_of_range", "--layers",
                     std::to_string(spec.layers) + " is out of range, allowed [1, 200] (0 = Table 1)");
  if (spec.displacement_mm < 0)
    throw UsageError("out_of_range", "--displacement", "must be > 0 mm");
  if (spec.seeds < 1 || spec.seeds > 100)
    throw UsageError("out_of_range", "--seeds",
                     std::to_string(spec.seeds) + " is out of range, allowed [1, 100]");
}

// A test finished earlier, read back.
void keep_finished(CampaignTest& t) { t.result = finished_shear_test(t.dir, test_title(t.scene)); }

void print_result(const CampaignTest& t) {
  const ShearSummary& s = t.result.summary;
  std::printf("%-22s peak tau/sigma %.3f (phi %.2f deg), residual %.3f (phi %.2f deg), "
              "max dilatancy %.2f deg, %.0f s\n",
              t.scene.name.c_str(), s.peak_ratio, s.peak_angle, s.residual_ratio,
              s.residual_angle, s.max_dilatancy_angle, s.wall_seconds);
  std::fflush(stdout);
}

void write_report(const std::vector<CampaignTest>& tests, const std::string& base_name,
                  const CampaignSpec& spec, const std::string& out_dir, double seconds) {
  std::vector<CampaignEntry> entries;
  for (const CampaignTest& t : tests)
    entries.push_back({t.d_mm, t.s_kpa, t.seed, t.scene.apparatus_as<ShearBox>()->specimen.layers,
                       static_cast<int>(t.scene.particles.size()), t.result.rows,
                       t.result.summary});
  write_campaign_report(out_dir, base_name, spec.sizes_mm, entries, seconds);
}

}  // namespace

std::vector<CampaignTest> plan_campaign(const Scene& base, const std::string& base_name,
                                        const CampaignSpec& spec, const std::string& out_dir) {
  check_spec(base, base_name, spec);
  std::vector<CampaignTest> tests;
  for (double d : spec.sizes_mm) {
    const int layers = spec.layers > 0 ? spec.layers : table1_layers(d);
    if (layers == 0)
      throw UsageError("out_of_range", "--sizes",
                       fmt("%g", d) +
                           " mm is not a Table 1 size (2.38125, 3.175, 3.96875, 4.7625, 6.35); "
                           "give --layers for other sizes");
    for (int k = 0; k < spec.seeds; ++k)  // one specimen's envelope after another
      for (double s : spec.stresses_kpa) {
        CampaignTest t;
        t.d_mm = d;
        t.s_kpa = s;
        Scene sc = paper_test_scene(base, base_name, d, s, spec.layers, [&](Scene& x) {
          ShearBox& box = *x.apparatus_as<ShearBox>();
          if (spec.displacement_mm > 0) box.shear_displacement = spec.displacement_mm * 1e-3;
          if (spec.precision) x.numerics.precision = *spec.precision;
          box.specimen.seed += k;
          t.seed = box.specimen.seed;
        });
        if (k > 0) sc.name += "_s" + std::to_string(t.seed);
        if (spec.profile) apply_profile(sc, *spec.profile, base_name);
        validate_scene(sc, base_name + " (" + sc.name + ")");
        t.scene = std::move(sc);
        t.dir = fs::path(out_dir) / t.scene.name;
        t.cost = expected_particle_steps(t.scene);
        tests.push_back(std::move(t));
      }
  }
  return tests;
}

ShearRunResult run_shear_test(const Scene& scene, const ProgrammeRunOptions& options,
                              const std::string& title) {
  ShearRunResult r = run_shear(scene, options);
  if (!r.finished) return r;
  ShearRunResult back = finished_shear_test(options.out_dir, title);
  r.rows = std::move(back.rows);
  r.summary = std::move(back.summary);
  return r;
}

CampaignOutcome run_campaign(std::vector<CampaignTest>& tests, const std::string& base_name,
                             const CampaignSpec& spec, const std::string& out_dir,
                             const CampaignRun& run) {
  fs::create_directories(out_dir);
  CampaignLoop loop = campaign_loop(tests, "tests", "shear.csv");
  loop.keep = [&](size_t k) { keep_finished(tests[k]); };
  loop.run = [&](size_t k, ProgrammeRunOptions& o) {
    tests[k].result = run_shear_test(tests[k].scene, o, test_title(tests[k].scene));
    return tests[k].result.interrupted;
  };
  loop.print = [&](size_t k) { print_result(tests[k]); };
  const CampaignOutcome outcome = run_campaign_loop(loop, run);
  if (!outcome.interrupted && run.writes_report()) {
    double seconds = outcome.seconds;  // collected: the tests' own wall times
    if (run.collect)
      for (const CampaignTest& t : tests) seconds += t.result.summary.wall_seconds;
    write_report(tests, base_name, spec, out_dir, seconds);
  }
  return outcome;
}

}  // namespace simsols
