// simsols study accuracy: the accuracy study (study.h); simsols study
// shape: the shape study (shape_study.h).
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
#include <atomic>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <mutex>
#include <optional>
#include <thread>

#include "app/cli/cluster_flags.h"
#include "app/cli/commands.h"
#include "solver/common/errors.h"
#include "app/cli/interrupt.h"
#include "solver/io/output.h"
#include "app/experiment/run_cost.h"
#include "app/experiment/sensitivity.h"
#include "app/experiment/shape_study.h"
#include "app/experiment/study.h"
#include "app/experiment/study_ensemble.h"
#include "app/experiment/study_state.h"

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

void report_case(const StudyCase& c, bool shear) {
  if (c.contact.ok)
    std::fprintf(stderr, "    contact: worst error %.3g %%\n", c.contact.worst());
  else
    std::fprintf(stderr, "    contact: failed: %s\n", c.contact.failure.c_str());
  if (!shear) return;
  if (c.shear.ok)
    std::fprintf(stderr, "    shear: phi_peak %.2f, phi_res %.2f, psi_max %.2f deg in %.1f s\n",
                 c.shear.peak_angle, c.shear.residual_angle, c.shear.dilatancy_angle,
                 c.shear.wall_seconds);
  else
    std::fprintf(stderr, "    shear: failed: %s\n", c.shear.failure.c_str());
}

// The contact checks have no specimen and no shear speed or skin: a run
// whose time step, precision, stiffness and effects an earlier run had
// (another member, the round-off twin) reuses that run's results.
ContactErrors contact_checks_of(const StudySettings& s, const std::vector<StudyCase>& done,
                                const std::shared_ptr<Device>& device) {
  for (const StudyCase& c : done)
    if (c.settings.dt_fraction == s.dt_fraction && c.settings.precision == s.precision &&
        c.settings.stiffness_scale == s.stiffness_scale && c.settings.rolling == s.rolling &&
        c.settings.damping == s.damping)
      return c.contact;
  return run_contact_checks(s, device);
}

// The finished cases of an earlier invocation (--resume), or none.
std::vector<StudyCase> resumed_cases(const StudyOptions& opt, const StudyPreset& preset,
                                     const std::vector<StudySettings>& cases) {
  const fs::path state = fs::path(opt.out) / "study_state.txt";
  if (!opt.resume) return {};
  if (!fs::exists(state))
    throw SceneError("io", state.string(), 0, "--resume",
                     "no study to resume here (a study writes this file after its first case)");
  std::ifstream in(state, std::ios::binary);
  const std::string text((std::istreambuf_iterator<char>(in)), {});
  std::vector<StudyCase> done = parse_study_state(text, state.string(), preset, cases);
  compare_to_reference(done);
  std::fprintf(stderr, "[study] resumed after %zu of %zu cases%s\n", done.size(), cases.size(),
               fs::exists(fs::path(opt.out) / "case_checkpoint.bin")
                   ? " (the next one from its checkpoint)"  // --jobs 1's name
                   : "");
  return done;
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

int jobs_of(const StudyOptions& opt) { return std::max(1, opt.jobs); }

// Case i's checkpoint: case_checkpoint.bin when the cases run one at a
// time, case_checkpoint_<i+1>.bin with --jobs > 1 (several run at once).
fs::path checkpoint_path(const StudyOptions& opt, size_t i, int jobs) {
  return fs::path(opt.out) /
         (jobs > 1 ? "case_checkpoint_" + std::to_string(i + 1) + ".bin" : "case_checkpoint.bin");
}

// The study's runs and the workers that run them (--jobs: that many cases
// at once, each worker on its own OpenCL context and queue, so a device
// that a small specimen leaves idle between launches runs several). A
// case's result does not depend on which worker ran it. Results are
// written as each case finishes; study_state.txt keeps the finished
// prefix of the cases (what --resume continues after), so a case that
// finished after an unfinished one runs again on resume.
class StudyRun {
 public:
  StudyRun(const StudyOptions& opt, const StudyPreset& preset, std::vector<StudySettings> cases,
           std::vector<StudyCase> done)
      : opt_(opt), preset_(preset), cases_(std::move(cases)), results_(cases_.size()),
        first_(done.size()), next_(done.size()) {
    for (size_t i = 0; i < done.size(); ++i) results_[i] = std::move(done[i]);
  }

  int run(int jobs) {
    jobs_ = jobs;
    t0_ = std::chrono::steady_clock::now();
    // one context and queue per worker, opened here, one after the other
    std::vector<std::shared_ptr<Device>> devices(static_cast<size_t>(jobs));
    for (auto& d : devices) d = open_command_device();
    {
      std::vector<std::jthread> workers;  // joined when the scope ends, also on a throw
      for (int k = 1; k < jobs; ++k) workers.emplace_back([this, d = devices[k]] { work(d); });
      work(devices[0]);
    }
    if (error_) std::rethrow_exception(error_);
    const size_t finished = prefix().size();
    if (finished < cases_.size()) {
      std::printf("study interrupted: %zu of the %zu cases finished in order%s. Resume with: %s\n",
                  finished, cases_.size(),
                  interrupted_ ? ", the running cases' states are in case_checkpoint*.bin" : "",
                  resume_command(opt_).c_str());
      return interrupt_.exit_status();
    }
    std::printf("study %s (%s): %zu cases; results in %s (cases.csv, summary.md, pareto.png)\n",
                opt_.what.c_str(), preset_.name.c_str(), finished, opt_.out.c_str());
    return 0;
  }

 private:
  // The finished cases, in case order.
  std::vector<StudyCase> finished() const {
    std::vector<StudyCase> f;
    for (const auto& r : results_)
      if (r) f.push_back(*r);
    return f;
  }
  std::vector<StudyCase> prefix() const {
    std::vector<StudyCase> f;
    for (const auto& r : results_) {
      if (!r) break;
      f.push_back(*r);
    }
    return f;
  }

  // The next case to run, or nullopt when none is left or a stop was asked.
  std::optional<size_t> take() {
    std::lock_guard lock(mutex_);
    if (next_ >= cases_.size() || interrupt_.requested() || error_) return std::nullopt;
    const size_t i = next_++;
    if (!opt_.quiet) {
      const double elapsed =
          std::chrono::duration<double>(std::chrono::steady_clock::now() - t0_).count();
      const size_t ran = ran_;
      const std::string eta =
          ran > 0 ? ", ETA " + human_seconds(elapsed / double(ran) *
                                             double(cases_.size() - first_ - ran))
                  : "";
      std::fprintf(stderr, "[study %zu/%zu] %s specimen, %s: %s, seed %d (elapsed %s%s)\n", i + 1,
                   cases_.size(), specimen_name(cases_[i].specimen), cases_[i].knob.c_str(),
                   cases_[i].label.c_str(), cases_[i].seed, human_seconds(elapsed).c_str(),
                   eta.c_str());
    }
    return i;
  }

  void work(std::shared_ptr<Device> device) {
    try {
      while (const std::optional<size_t> i = take()) run_case(*i, device);
    } catch (...) {
      std::lock_guard lock(mutex_);
      if (!error_) error_ = std::current_exception();
      failed_ = true;
    }
  }

  void run_case(size_t i, const std::shared_ptr<Device>& device) {
    StudyCase c;
    c.settings = cases_[i];
    std::vector<StudyCase> known;
    {
      std::lock_guard lock(mutex_);
      known = finished();
    }
    c.contact = contact_checks_of(cases_[i], known, device);
    // a checkpoint of this case from an interrupted study, whichever --jobs wrote it
    fs::path checkpoint = checkpoint_path(opt_, i, 2);
    if (!fs::exists(checkpoint) && (jobs_ == 1 || i == first_)) checkpoint = checkpoint_path(opt_, i, 1);
    // stop on Ctrl-C, and when another worker failed (its error ends the study)
    const ShearCaseControl control{[this] { return interrupt_.requested() || failed_.load(); },
                                   checkpoint.string(), device};
    if (preset_.shear) c.shear = run_shear_case(preset_, cases_[i], control);
    std::lock_guard lock(mutex_);
    if (c.shear.interrupted) {
      if (failed_) return;  // stopped for another worker's error: the error is the news
      interrupted_ = true;
      std::printf("study interrupted in case %zu/%zu (%s); its state is in %s\n", i + 1,
                  cases_.size(), cases_[i].label.c_str(), checkpoint.string().c_str());
      return;
    }
    fs::remove(checkpoint);
    if (!opt_.quiet) report_case(c, preset_.shear);
    results_[i] = c;
    ++ran_;
    std::vector<StudyCase> all = finished(), ordered = prefix();
    compare_to_reference(all);
    write_study_outputs(opt_.out, preset_, all);
    write_file_atomic((fs::path(opt_.out) / "study_state.txt").string(),
                      study_state_text(preset_, cases_, ordered));
  }

  const StudyOptions& opt_;
  const StudyPreset& preset_;
  const std::vector<StudySettings> cases_;
  std::vector<std::optional<StudyCase>> results_;
  const size_t first_;  // finished before this invocation
  size_t next_;
  size_t ran_ = 0;  // finished by this invocation
  int jobs_ = 1;
  bool interrupted_ = false;
  std::exception_ptr error_;
  std::atomic<bool> failed_ = false;
  std::mutex mutex_;
  InterruptScope interrupt_;
  std::chrono::steady_clock::time_point t0_;
};

// `simsols study shape --out DIR [--preset quick|ci]`: the shape study
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

int study(const StudyOptions& opt) {
  if (opt.what == "table") return print_table(opt);
  if (opt.what != "sensitivity" &&
      (opt.cluster.emitting() || opt.cluster.task >= 0 || opt.cluster.collecting))
    throw UsageError("not_applicable", opt.cluster.emitting() ? "--emit" : "--task",
                     "the cluster flags are for the sensitivity study (and simsols campaign)");
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
                     "'" + opt.what + "' is not one of: accuracy, sensitivity, shape, table");
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
  std::vector<StudyCase> done = resumed_cases(opt, *preset, cases);
  if (!done.empty()) write_study_outputs(opt.out, *preset, done);  // today's tables and charts
  if (!opt.resume)  // another study's case states, whichever --jobs wrote them
    for (size_t i = 0; i < cases.size(); ++i)
      for (int jobs : {1, 2}) fs::remove(checkpoint_path(opt, i, jobs));
  return StudyRun(opt, *preset, cases, std::move(done)).run(jobs_of(opt));
}

}  // namespace

CommandRunner add_study_command(CLI::App& app) {
  auto opt = std::make_shared<StudyOptions>();
  CLI::App* cmd = app.add_subcommand("study", "Measured studies: what accuracy costs in time (accuracy), the strength's sensitivity to the model (sensitivity), the grains' shape (shape)");
  cmd->add_option("study", opt->what,
                  "accuracy (run the study), sensitivity (the strength's response to the "
                  "contact coefficients, density and box size), shape (angle of repose and "
                  "strength against the grains' shape), table (print a study's table)");
  cmd->add_option("--out,-o", opt->out, "Output folder (accuracy; table: its charts drawn again there)");
  cmd->add_option("--from", opt->from, "A finished study's ensemble.csv (table)");
  CLI::Option* preset =
      cmd->add_option("--preset", opt->preset,
                      "quick (3 mm of shear, default), full (6 mm), ci (reduced); shape: quick, "
                      "ci; sensitivity: paper (default), ci");
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
    opt->command_line = given_args(cmd, {"--out", "--from"});
    return study(*opt);
  };
}

}  // namespace simsols
