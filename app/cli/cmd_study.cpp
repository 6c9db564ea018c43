// simsols study accuracy: the accuracy study (study.h); simsols study
// shape: the shape study (shape_study.h); simsols study size: an apparatus
// at growing size against the bulk (size_study.h):
//
//   simsols study size --scene FILE --out DIR [--scales 1,1.5,2] [--fixed-height]
//                      [--seeds N] [--bulk CELL_CAMPAIGN/summary.csv] [--precision P]
//
//   simsols study accuracy --out DIR [--preset quick|full|ci] [--ensemble N] [--knob NAME ...]
//                                    [--specimen layered|poured] [--box-scale S]
//                                    [--no-shear] [--resume] [-q]
//
// Outputs in DIR, rewritten after every run (an interrupted study keeps the
// runs it finished): cases.csv (one row per run), ensemble.csv (one row per
// setting: means, 95 % intervals, errors and their significance),
// summary.md (tables, chaos, the recommendation), error_vs_time_<knob>.png
// per knob and pareto.png.
//
//   simsols study table --from DIR/ensemble.csv [--specimen layered|poured] [--out DIR2]
//
// prints that study's settings table of each specimen (markdown), as
// docs/accuracy.md holds them; with --out, also draws its charts there again.
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <optional>
#include <utility>

#include "app/cli/cluster_flags.h"
#include "app/cli/commands.h"
#include "solver/common/errors.h"
#include "app/cli/interrupt.h"
#include "solver/io/output.h"
#include "app/experiment/run_cost.h"
#include "app/experiment/shear_box/sensitivity.h"
#include "app/experiment/shape_study.h"
#include "app/experiment/size_study.h"
#include "solver/io/scene_toml.h"
#include "app/experiment/shear_box/study.h"
#include "app/experiment/shear_box/study_ensemble.h"
#include "app/experiment/shear_box/study_run.h"

namespace simsols {
namespace {

namespace fs = std::filesystem;

struct StudyOptions {
  std::string what;
  std::string out;
  std::string from;  // study table: the ensemble.csv to print
  std::string preset = "quick";
  std::vector<std::string> knobs;
  std::string specimen;  // "" = both
  double box_scale = 0;  // 0 = the preset's
  int jobs = 1;          // cases at once
  int ensemble = 0;  // 0 = the preset's
  bool no_shear = false;
  bool quiet = false;
  bool resume = false;
  bool preset_given = false;
  // study size
  std::string scene;
  std::vector<double> scales{1, 1.5, 2};
  bool fixed_height = false;
  int seeds = 3;
  std::string bulk;
  std::string precision;
  ClusterFlags cluster;
  std::vector<std::string> command_line;  // plans the same tests again (given_args)
};

// --specimen: nullopt for both; throws for another name.
std::optional<StudySpecimen> selected_specimen(const StudyOptions& opt) {
  if (opt.specimen.empty()) return std::nullopt;
  const std::optional<StudySpecimen> s = parse_specimen(opt.specimen);
  if (!s)
    throw UsageError("bad_enum", "--specimen",
                     "'" + opt.specimen + "' is not one of: layered, poured");
  return s;
}

std::vector<StudySettings> selected_cases(const StudyPreset& preset, const StudyOptions& opt) {
  const std::optional<StudySpecimen> specimen = selected_specimen(opt);
  std::vector<StudySettings> cases;
  for (const StudySettings& s : preset.cases) {
    if (specimen && s.specimen != *specimen) continue;
    if (s.knob == "reference" || opt.knobs.empty() ||
        std::find(opt.knobs.begin(), opt.knobs.end(), s.knob) != opt.knobs.end())
      cases.push_back(s);
  }
  return cases;
}

std::string resume_command(const StudyOptions& opt) {
  std::string c = "simsols study " + opt.what + " --out " + opt.out + " --preset " + opt.preset;
  if (opt.ensemble > 0) c += " --ensemble " + std::to_string(opt.ensemble);
  for (const std::string& k : opt.knobs) c += " --knob '" + k + "'";
  if (!opt.specimen.empty()) c += " --specimen " + opt.specimen;
  if (opt.box_scale > 0) c += " --box-scale " + format_number("%.17g", opt.box_scale);
  return c + (opt.no_shear ? " --no-shear" : "") + " --resume";
}

// `simsols study table --from ENSEMBLE_CSV`: the settings' table of a
// finished study, as markdown (docs/accuracy.md holds the shipped one's).
int print_table(const StudyOptions& opt) {
  if (opt.from.empty())
    throw UsageError("missing_field", "--from", "give the study's ensemble.csv");
  if (!fs::exists(opt.from)) throw SceneError("io", opt.from, 0, "--from", "no such file");
  const std::optional<StudySpecimen> only = selected_specimen(opt);
  try {
    const std::vector<SettingSummary> settings = parse_ensemble_csv(read_text(opt.from));
    bool first = true;
    for (StudySpecimen s : kStudySpecimens) {
      if ((only && s != *only) || settings_of(settings, s).empty()) continue;
      if (!only) std::printf("%s%s specimen:\n\n", first ? "" : "\n", specimen_name(s));
      std::fputs(ensemble_table_md(settings, s).c_str(), stdout);
      first = false;
    }
    if (!opt.out.empty()) write_study_charts(opt.out, settings);
  } catch (const std::runtime_error& e) {
    throw SceneError("bad_file", opt.from, 0, "--from", e.what());
  }
  return 0;
}

// The accuracy study's cases on the pool of study_run.h (--jobs workers),
// Ctrl-C caught; the status: 0, or the interrupt's.
int run_accuracy_study(const StudyOptions& opt, const StudyPreset& preset,
                       const std::vector<StudySettings>& cases, std::vector<StudyCase> done) {
  InterruptScope interrupt;
  StudyRunOptions run;
  run.out = opt.out;
  run.quiet = opt.quiet;
  run.jobs = std::max(1, opt.jobs);
  run.open_device = [] { return open_command_device(); };
  run.stop_requested = interrupt.stop_function();
  const StudyRunOutcome o = run_study(preset, cases, std::move(done), run);
  if (!o.complete()) {
    std::printf("study interrupted: %zu of the %zu cases finished in order%s. Resume with: %s\n",
                o.finished, o.total,
                o.interrupted ? ", the running cases' states are in case_checkpoint*.bin" : "",
                resume_command(opt).c_str());
    return interrupt.exit_status();
  }
  std::printf("study %s (%s): %zu cases; results in %s (cases.csv, summary.md, pareto.png)\n",
              opt.what.c_str(), preset.name.c_str(), o.finished, opt.out.c_str());
  return 0;
}

// `simsols study shape --out DIR [--preset quick|rolling|ci]`: the shape study
// (shape_study.h), its results rewritten after each case; a stop (Ctrl-C)
// ends it after the running case's stage, keeping the finished cases.
int shape_study(const StudyOptions& opt) {
  const ShapePreset preset = shape_preset(opt.preset);
  const std::shared_ptr<Device> device = open_command_device();
  InterruptScope interrupt;
  std::vector<ShapeResult> results;
  const auto t0 = std::chrono::steady_clock::now();
  for (size_t i = 0; i < preset.cases.size() && !interrupt.requested(); ++i) {
    const double elapsed = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    const std::string eta =
        i > 0 ? ", ETA " + human_seconds(elapsed / double(i) * double(preset.cases.size() - i)) : "";
    if (!opt.quiet)
      std::fprintf(stderr, "[shape %zu/%zu] %s (elapsed %s%s)\n", i + 1, preset.cases.size(),
                   preset.cases[i].label.c_str(), human_seconds(elapsed).c_str(), eta.c_str());
    results.push_back(run_shape_case(preset, preset.cases[i], device, [&](const std::string& m) {
      if (!opt.quiet) std::fprintf(stderr, "[shape %zu/%zu] %s\n", i + 1, preset.cases.size(), m.c_str());
    }));
    write_shape_results(results, preset, opt.out);
  }
  std::fputs(shape_table(results).c_str(), stdout);
  std::printf("shape study (%s): %zu of %zu cases; results in %s (shapes.csv, summary.md, "
              "repose_profiles.png, shear_curves.png)\n",
              preset.name.c_str(), results.size(), preset.cases.size(), opt.out.c_str());
  return results.size() < preset.cases.size() ? interrupt.exit_status() : 0;
}

// `simsols study sensitivity --out DIR [--preset paper|ci]` (sensitivity.h):
// its tests run like a campaign's (resumable; on a cluster with the
// cluster flags), then the report.
int sensitivity_study(const StudyOptions& opt) {
  const SensitivityPreset preset = sensitivity_preset(opt.preset_given ? opt.preset : "paper");
  std::vector<SensitivityTest> tests = plan_sensitivity(preset, opt.out);
  InterruptScope interrupt;
  CampaignRun run = campaign_run(opt.cluster, opt.out, interrupt.stop_function(), opt.quiet);
  if (emit_or_check_plan(opt.cluster, "study", opt.command_line, opt.out, cluster_tests(tests)))
    return 0;
  if (!run.collect) run.device = open_command_device();
  const CampaignOutcome outcome = run_sensitivity(tests, preset, opt.out, run);
  if (outcome.interrupted) {
    std::printf("sensitivity study interrupted in test %zu/%zu (%s); resume with the same "
                "command\n", outcome.interrupted_test + 1, tests.size(),
                tests[outcome.interrupted_test].point.label.c_str());
    return interrupt.exit_status();
  }
  if (run.only)
    std::printf("sensitivity task %zu of %zu done: %s\n", *run.only, tests.size(),
                tests[*run.only].point.label.c_str());
  else
    std::printf("sensitivity study (%s): %zu tests; results in %s (summary.md, effects.csv, "
                "sensitivity.csv, oat_*.png, morris_*.png, scale_effect.png)\n",
                preset.name.c_str(), tests.size(), opt.out.c_str());
  return 0;
}

// `simsols study size --scene FILE --out DIR` (size_study.h): its tests run
// like a campaign's (resumable; on a cluster with the cluster flags), then
// the report against the bulk value of --bulk.
int size_study(const StudyOptions& opt) {
  if (opt.scene.empty()) throw UsageError("missing_field", "--scene", "give the apparatus' scene to resize");
  std::optional<BulkValue> bulk;
  if (!opt.bulk.empty()) bulk = read_bulk_value(opt.bulk);
  SizeStudySpec spec;
  spec.scales = opt.scales;
  spec.similar = !opt.fixed_height;
  spec.seeds = opt.seeds;
  spec.precision = precision_flag(opt.precision);
  const Scene base = read_scene(opt.scene);
  std::vector<SizeTest> tests = plan_size_study(base, opt.scene, spec, opt.out);
  InterruptScope interrupt;
  CampaignRun run = campaign_run(opt.cluster, opt.out, interrupt.stop_function(), opt.quiet);
  if (emit_or_check_plan(opt.cluster, "study", opt.command_line, opt.out, cluster_tests(tests)))
    return 0;
  if (!run.collect) run.device = open_command_device();
  const CampaignOutcome outcome = run_size_study(tests, bulk, size_study_title(base, spec), opt.out, run);
  if (outcome.interrupted) {
    std::printf("size study interrupted in test %zu/%zu (%s); resume with the same command\n",
                outcome.interrupted_test + 1, tests.size(), tests[outcome.interrupted_test].scene.name.c_str());
    return interrupt.exit_status();
  }
  if (run.only)
    std::printf("size study task %zu of %zu done: %s\n", *run.only, tests.size(),
                tests[*run.only].scene.name.c_str());
  else
    std::printf("size study: %zu tests; results in %s (summary.md, summary.csv, tests.csv, size_*.png)\n",
                tests.size(), opt.out.c_str());
  return 0;
}

int study(const StudyOptions& opt) {
  if (opt.what == "table") return print_table(opt);
  if (opt.what != "sensitivity" && opt.what != "size" &&
      (opt.cluster.emitting() || opt.cluster.task >= 0 || opt.cluster.collecting))
    throw UsageError("not_applicable", opt.cluster.emitting() ? "--emit" : "--task",
                     "the cluster flags are for the sensitivity and size studies (and simsols campaign)");
  if (opt.what == "size") {
    if (opt.out.empty()) throw UsageError("missing_field", "--out", "give an output folder");
    return size_study(opt);
  }
  for (const auto& [given, flag] : {std::pair{!opt.scene.empty(), "--scene"}, {!opt.bulk.empty(), "--bulk"},
                                    {opt.fixed_height, "--fixed-height"}})
    if (given) throw UsageError("not_applicable", flag, "is a flag of the size study (simsols study size)");
  if (opt.what == "sensitivity") {
    if (opt.out.empty()) throw UsageError("missing_field", "--out", "give an output folder");
    return sensitivity_study(opt);
  }
  if (opt.what == "shape") {
    if (opt.out.empty()) throw UsageError("missing_field", "--out", "give an output folder");
    return shape_study(opt);
  }
  if (opt.what != "accuracy")
    throw UsageError("bad_enum", "STUDY",
                     "'" + opt.what + "' is not one of: accuracy, sensitivity, shape, size, table");
  if (opt.out.empty()) throw UsageError("missing_field", "--out", "give an output folder");
  if (opt.ensemble < 0 || opt.ensemble > 50)
    throw UsageError("out_of_range", "--ensemble",
                     std::to_string(opt.ensemble) +
                         " is out of range, allowed [1, 50] members per setting (0 = the preset's)");
  auto preset = study_preset(opt.preset, opt.ensemble);
  if (!preset)
    throw UsageError("bad_enum", "--preset",
                     "'" + opt.preset + "' is not one of: quick, full, ci");
  if (opt.box_scale != 0 && !(opt.box_scale >= 1 && opt.box_scale <= 4))
    throw UsageError("out_of_range", "--box-scale",
                     format_number("%g", opt.box_scale) +
                         " is out of range, allowed [1, 4] (the poured specimen's box against the "
                         "paper's; 0 = the preset's)");
  if (opt.box_scale > 0) preset->poured_box_scale = opt.box_scale;
  if (opt.jobs < 1 || opt.jobs > 16)
    throw UsageError("out_of_range", "--jobs",
                     std::to_string(opt.jobs) + " is out of range, allowed [1, 16] cases at once");
  if (opt.no_shear) preset->shear = false;
  const std::vector<StudySettings> cases = study_runs(*preset, selected_cases(*preset, opt));
  std::vector<StudyCase> done;
  if (opt.resume) done = resumed_study_cases(opt.out, *preset, cases);
  if (!done.empty()) write_study_outputs(opt.out, *preset, done);  // today's tables and charts
  if (!opt.resume)  // another study's case states, whichever --jobs wrote them
    for (size_t i = 0; i < cases.size(); ++i)
      for (int jobs : {1, 2}) fs::remove(study_case_checkpoint(opt.out, i, jobs));
  return run_accuracy_study(opt, *preset, cases, std::move(done));
}

}  // namespace

CommandRunner add_study_command(CLI::App& app) {
  auto opt = std::make_shared<StudyOptions>();
  CLI::App* cmd = app.add_subcommand("study", "Measured studies: what accuracy costs in time (accuracy), the strength's sensitivity to the model (sensitivity), the grains' shape (shape), the apparatus' size against the bulk (size)");
  cmd->add_option("study", opt->what,
                  "accuracy (run the study), sensitivity (the strength's response to the "
                  "contact coefficients, density and box size), shape (angle of repose and "
                  "strength against the grains' shape), size (an apparatus at growing size "
                  "against the periodic cell's bulk value), table (print a study's table)");
  cmd->add_option("--out,-o", opt->out, "Output folder (accuracy; table: its charts drawn again there)");
  cmd->add_option("--from", opt->from, "A finished study's ensemble.csv (table)");
  CLI::Option* preset =
      cmd->add_option("--preset", opt->preset,
                      "quick (3 mm of shear, default), full (6 mm), ci (reduced); shape: quick, "
                      "rolling, ci; sensitivity: paper (default), ci");
  cmd->add_option("--knob", opt->knobs,
                  "Only these knobs (with the reference): time step, precision, stiffness, "
                  "inertial number, skin, effects, combination, baseline");
  cmd->add_option("--ensemble", opt->ensemble,
                  "Members per setting, specimens differing only in their seed (default: quick 3, "
                  "full 5, ci 2)");
  cmd->add_option("--specimen", opt->specimen,
                  "Only this specimen: layered (the paper's) or poured (random); default both "
                  "(with table: print only its table)");
  cmd->add_option("--box-scale", opt->box_scale,
                  "The poured specimen's box against the paper's, length and width, [1, 4] "
                  "(default: quick and full 2, ci 1)");
  cmd->add_option("--jobs,-j", opt->jobs,
                  "Cases at once, each on its own OpenCL context and queue (default 1; see "
                  "docs/accuracy.md for when more is faster)");
  cmd->add_flag("--no-shear", opt->no_shear, "Contact checks only");
  cmd->add_option("--scene", opt->scene, "size: the apparatus' scene (shear box, oedometer or triaxial cell)");
  cmd->add_option("--scales", opt->scales,
                  "size: the apparatus' widths against the scene's, [0.5, 6] (default 1 1.5 2)")
      ->delimiter(',');
  cmd->add_flag("--fixed-height", opt->fixed_height,
                "size: the specimen keeps its layers (default: its height grows with the box)");
  cmd->add_option("--seeds", opt->seeds, "size: specimens per size, [1, 100] (default 3)");
  cmd->add_option("--bulk", opt->bulk,
                  "size: a periodic-cell campaign's summary.csv, the material's bulk value");
  cmd->add_option("--precision", opt->precision, "size: float or double (default: the scene's)");
  cmd->add_flag("--resume", opt->resume,
                "Continue the study in --out after its finished cases (same --preset, --knob, "
                "--specimen, --box-scale)");
  cmd->add_flag("--quiet,-q", opt->quiet, "No progress lines");
  add_cluster_flags(cmd, opt->cluster);
  return [opt, preset, cmd] {
    if (!opt->cluster.collect.empty())
      return collect_from_manifest(opt->cluster, "study", add_study_command);
    if (opt->what.empty()) throw UsageError("missing_field", "STUDY", "name the study to run");
    opt->preset_given = preset->count() > 0;
    opt->command_line = given_args(cmd, {"--out", "--from", "--scene", "--bulk"});
    return study(*opt);
  };
}

}  // namespace simsols
