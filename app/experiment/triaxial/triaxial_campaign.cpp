#include "app/experiment/triaxial/triaxial_campaign.h"
#include "app/experiment/test_title.h"

#include <cstdio>

#include "app/experiment/triaxial/triaxial_campaign_report.h"
#include "app/experiment/triaxial/triaxial_plots.h"
#include "solver/apparatus/cell/platen_servo.h"
#include "solver/apparatus/triaxial/triaxial.h"
#include "solver/common/errors.h"
#include "solver/io/output.h"
#include "solver/io/scene_toml.h"
#include "solver/scene/contact_model.h"

namespace simsols {
namespace {

namespace fs = std::filesystem;
constexpr auto fmt = format_number;  // printf conversion of one number (output.h)


void check_spec(const Scene& base, const std::string& base_name, const TriaxialCampaignSpec& spec) {
  if (!base.apparatus_as<Triaxial>())
    throw SceneError("missing_field", base_name, 0, "triaxial",
                     "the triaxial campaign's base scene must describe a triaxial cell");
  if (spec.stresses_kpa.empty())
    throw UsageError("missing_value", "--stresses", "give one or more confining stresses in kPa");
  for (double s : spec.stresses_kpa)
    if (!(s > 0 && s <= 1e6))
      throw UsageError("out_of_range", "--stresses",
                       fmt("%g", s) + " kPa is out of range, allowed (0, 1e6] kPa");
  if (spec.seeds < 1 || spec.seeds > 100)
    throw UsageError("out_of_range", "--seeds",
                     std::to_string(spec.seeds) + " is out of range, allowed [1, 100]");
}

// Specimen k of the campaign: the base itself (k = 0), else the base's
// scene text read again with its specimen seed k further on and placed.
Scene specimen_scene(const Scene& base, const std::string& base_name, int k) {
  if (k == 0) return base;
  if (base.source_text.empty())
    throw UsageError("not_applicable", "--seeds",
                     "needs the base scene's text to place further specimens; give a scene file");
  Scene sc = read_scene_text(base.source_text, base.source_path.empty() ? base_name : base.source_path);
  sc.cell()->specimen.seed += k;
  place_scene(sc);
  return sc;
}

}  // namespace

TriaxialRunResult finished_triaxial_test(const fs::path& dir, const std::string& title,
                                         double confining_stress) {
  TriaxialRunResult r;
  r.rows = parse_triaxial_rows_csv(read_text(dir / "triaxial.csv"));
  const std::string text = read_text(dir / "summary.txt");
  const auto keys = summary_keys(text);
  TriaxialSummary& s = r.summary;
  s.confining_stress = confining_stress;
  for (const auto& [key, field] : {std::pair{"strain_rate_per_s", &s.strain_rate},
                                   {"bead_diameter_mm", &s.bead_diameter},
                                   {"settle_time_s", &s.settle_time},
                                   {"consolidate_time_s", &s.consolidate_time},
                                   {"wall_seconds", &s.wall_seconds}})
    if (const auto it = keys.find(key); it != keys.end()) *field = std::stod(it->second);
  s.bead_diameter *= 1e-3;
  if (const auto it = keys.find("cell"); it != keys.end()) s.membrane = it->second == "membrane";
  if (const auto it = keys.find("max_membrane_stress_kPa"); it != keys.end())
    s.max_membrane_stress = std::stod(it->second) * 1e3;
  analyse_triaxial_rows(r.rows, s);
  // Today's analysis of the rows, written back when it reads them otherwise.
  if (const std::string now = triaxial_summary_text(s); now != text) {
    write_triaxial_plots(dir.string(), title, r.rows, s);
    write_file_atomic((dir / "summary.txt").string(), now);
  }
  r.state.finished = true;
  return r;
}

TriaxialRunResult run_triaxial_test(const Scene& scene, const ProgrammeRunOptions& options,
                                    const std::string& title) {
  TriaxialRunResult r = typed_result<TriaxialProgramme>(run_test(scene, options));
  if (!r.state.finished) return r;
  TriaxialRunResult back =
      finished_triaxial_test(options.out_dir, title, scene.apparatus_as<Triaxial>()->confining_stress);
  r.rows = std::move(back.rows);
  r.summary = std::move(back.summary);
  return r;
}

namespace {

// A test finished earlier, read back.
void keep_finished(TriaxialCampaignTest& t) {
  t.result = finished_triaxial_test(t.dir, test_title(t.scene), t.s_kpa * 1e3);
}

void print_result(const TriaxialCampaignTest& t) {
  const TriaxialSummary& s = t.result.summary;
  std::printf("%-26s peak phi %.2f deg (q/p' %.3f at %.1f %%), critical phi %.2f deg, "
              "e_cs %.3f, max dilatancy %.2f deg, %.0f s\n",
              t.scene.name.c_str(), s.peak_angle, s.peak_q_over_p, 100 * s.peak_axial_strain,
              s.critical_angle, s.critical_void_ratio, s.max_dilatancy_angle, s.wall_seconds);
  std::fflush(stdout);
}

}  // namespace

std::vector<TriaxialCampaignTest> plan_triaxial_campaign(const Scene& base,
                                                         const std::string& base_name,
                                                         const TriaxialCampaignSpec& spec,
                                                         const std::string& out_dir) {
  check_spec(base, base_name, spec);
  std::vector<TriaxialCampaignTest> tests;
  for (int k = 0; k < spec.seeds; ++k) {  // one specimen's tests after another
    const Scene specimen = specimen_scene(base, base_name, k);
    for (double s : spec.stresses_kpa) {
      TriaxialCampaignTest t;
      t.s_kpa = s;
      t.scene = specimen;
      Triaxial& tri = *t.scene.apparatus_as<Triaxial>();
      tri.confining_stress = s * 1e3;
      t.seed = tri.specimen.seed;
      if (spec.precision) t.scene.numerics.precision = *spec.precision;
      const std::string folder =
          "s3_" + fmt("%g", s) + "kPa" + (k > 0 ? "_s" + std::to_string(t.seed) : "");
      t.scene.name = base.name + "_" + folder;
      t.scene.source_text.clear();  // scene.toml is then the resolved scene
      validate_scene(t.scene, base_name + " (" + t.scene.name + ")");
      t.dir = fs::path(out_dir) / folder;
      t.cost = expected_particle_steps(t.scene);
      tests.push_back(std::move(t));
    }
  }
  return tests;
}

CampaignOutcome run_triaxial_campaign(std::vector<TriaxialCampaignTest>& tests,
                                      const std::string& base_name, const std::string& out_dir,
                                      const CampaignRun& run) {
  fs::create_directories(out_dir);
  CampaignLoop loop = campaign_loop(tests, "triaxial tests", "triaxial.csv");
  loop.keep = [&](size_t k) { keep_finished(tests[k]); };
  loop.run = [&](size_t k, ProgrammeRunOptions& o) {
    tests[k].result = run_triaxial_test(tests[k].scene, o, test_title(tests[k].scene));
    return tests[k].result.state.interrupted;
  };
  loop.print = [&](size_t k) { print_result(tests[k]); };
  const CampaignOutcome outcome = run_campaign_loop(loop, run);
  if (outcome.interrupted || !run.writes_report()) return outcome;
  std::vector<TriaxialCampaignEntry> entries;
  for (const TriaxialCampaignTest& t : tests)
    entries.push_back({t.s_kpa, t.seed, static_cast<int>(t.scene.particles.size()),
                       t.result.rows, t.result.summary});
  write_triaxial_campaign_report(out_dir, base_name, entries, outcome.seconds);
  return outcome;
}

}  // namespace simsols
