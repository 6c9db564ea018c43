// simsols study accuracy: the accuracy study (study.h).
//
//   simsols study accuracy --out DIR [--preset quick|full|ci] [--ensemble N] [--knob NAME ...]
//                                    [--no-shear] [--resume] [-q]
//
// Outputs in DIR, rewritten after every run (an interrupted study keeps the
// runs it finished): cases.csv (one row per run), ensemble.csv (one row per
// setting: means, 95 % intervals, errors and their significance),
// summary.md (tables, chaos, the recommendation), error_vs_time_<knob>.png
// per knob and pareto.png.
//
//   simsols study table --from DIR/ensemble.csv
//
// prints that study's settings table (markdown), as docs/accuracy.md holds it.
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>

#include "commands.h"
#include "errors.h"
#include "interrupt.h"
#include "output.h"
#include "run_cost.h"
#include "study.h"
#include "study_ensemble.h"
#include "study_state.h"

namespace simsols {
namespace {

namespace fs = std::filesystem;

struct StudyOptions {
  std::string what;
  std::string out;
  std::string from;  // study table: the ensemble.csv to print
  std::string preset = "quick";
  std::vector<std::string> knobs;
  int ensemble = 0;  // 0 = the preset's
  bool no_shear = false;
  bool quiet = false;
  bool resume = false;
};

std::vector<StudySettings> selected_cases(const StudyPreset& preset, const StudyOptions& opt) {
  std::vector<StudySettings> cases;
  for (size_t i = 0; i < preset.cases.size(); ++i) {
    const StudySettings& s = preset.cases[i];
    if (i == 0 || opt.knobs.empty() ||
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
ContactErrors contact_checks_of(const StudySettings& s, const std::vector<StudyCase>& done) {
  for (const StudyCase& c : done)
    if (c.settings.dt_fraction == s.dt_fraction && c.settings.precision == s.precision &&
        c.settings.stiffness_scale == s.stiffness_scale && c.settings.rolling == s.rolling &&
        c.settings.damping == s.damping)
      return c.contact;
  return run_contact_checks(s);
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
                   ? " (the next one from its checkpoint)"
                   : "");
  return done;
}

std::string resume_command(const StudyOptions& opt) {
  std::string c = "simsols study " + opt.what + " --out " + opt.out + " --preset " + opt.preset;
  if (opt.ensemble > 0) c += " --ensemble " + std::to_string(opt.ensemble);
  for (const std::string& k : opt.knobs) c += " --knob '" + k + "'";
  return c + (opt.no_shear ? " --no-shear" : "") + " --resume";
}

// `simsols study table --from ENSEMBLE_CSV`: the settings' table of a
// finished study, as markdown (docs/accuracy.md holds the shipped one's).
int print_table(const StudyOptions& opt) {
  if (opt.from.empty())
    throw SceneError("missing_field", "command line", 0, "--from", "give the study's ensemble.csv");
  if (!fs::exists(opt.from)) throw SceneError("io", opt.from, 0, "--from", "no such file");
  try {
    std::fputs(ensemble_table_md(parse_ensemble_csv(read_text(opt.from))).c_str(), stdout);
  } catch (const std::runtime_error& e) {
    throw SceneError("bad_file", opt.from, 0, "--from", e.what());
  }
  return 0;
}

int study(const StudyOptions& opt) {
  if (opt.what == "table") return print_table(opt);
  if (opt.what != "accuracy")
    throw SceneError("bad_enum", "command line", 0, "STUDY",
                     "'" + opt.what + "' is not one of: accuracy, table");
  if (opt.out.empty()) throw SceneError("missing_field", "command line", 0, "--out", "give an output folder");
  if (opt.ensemble < 0 || opt.ensemble > 50)
    throw SceneError("out_of_range", "command line", 0, "--ensemble",
                     std::to_string(opt.ensemble) +
                         " is out of range, allowed [1, 50] members per setting (0 = the preset's)");
  auto preset = study_preset(opt.preset, opt.ensemble);
  if (!preset)
    throw SceneError("bad_enum", "command line", 0, "--preset",
                     "'" + opt.preset + "' is not one of: quick, full, ci");
  if (opt.no_shear) preset->shear = false;
  const std::vector<StudySettings> cases = study_runs(*preset, selected_cases(*preset, opt));
  std::vector<StudyCase> done = resumed_cases(opt, *preset, cases);
  if (!done.empty()) write_study_outputs(opt.out, *preset, done);  // today's tables and charts
  if (!opt.resume) fs::remove(fs::path(opt.out) / "case_checkpoint.bin");
  InterruptScope interrupt;
  ShearCaseControl control{interrupt.stop_function(),
                           (fs::path(opt.out) / "case_checkpoint.bin").string()};
  const auto t0 = std::chrono::steady_clock::now();
  const size_t first = done.size();
  for (size_t i = first; i < cases.size(); ++i) {
    const double elapsed =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    const std::string eta =
        i > first ? ", ETA " + human_seconds(elapsed / double(i - first) * double(cases.size() - i))
                  : "";
    if (!opt.quiet)
      std::fprintf(stderr, "[study %zu/%zu] %s: %s (elapsed %s%s)\n", i + 1, cases.size(),
                   cases[i].knob.c_str(), cases[i].label.c_str(), human_seconds(elapsed).c_str(),
                   eta.c_str());
    StudyCase c;
    c.settings = cases[i];
    c.contact = contact_checks_of(cases[i], done);
    if (preset->shear) c.shear = run_shear_case(*preset, cases[i], control);
    if (c.shear.interrupted) {
      std::printf("study interrupted in case %zu/%zu (%s): %zu of the cases finished, the case's "
                  "state is in %s. Resume with: %s\n",
                  i + 1, cases.size(), cases[i].label.c_str(), done.size(),
                  control.checkpoint.c_str(), resume_command(opt).c_str());
      return interrupt.exit_status();
    }
    fs::remove(control.checkpoint);
    if (!opt.quiet) report_case(c, preset->shear);
    done.push_back(c);
    compare_to_reference(done);
    write_study_outputs(opt.out, *preset, done);
    write_file_atomic((fs::path(opt.out) / "study_state.txt").string(),
                      study_state_text(*preset, cases, done));
    if (interrupt.requested() && i + 1 < cases.size()) {
      std::printf("study interrupted after case %zu/%zu. Resume with: %s\n", i + 1, cases.size(),
                  resume_command(opt).c_str());
      return interrupt.exit_status();
    }
  }
  std::printf("study %s (%s): %zu cases; results in %s (cases.csv, summary.md, pareto.png)\n",
              opt.what.c_str(), preset->name.c_str(), done.size(), opt.out.c_str());
  return 0;
}

}  // namespace

CommandRunner add_study_command(CLI::App& app) {
  auto opt = std::make_shared<StudyOptions>();
  CLI::App* cmd = app.add_subcommand("study", "Measured studies: what accuracy costs in time");
  cmd->add_option("study", opt->what, "accuracy (run the study), table (print a study's table)")
      ->required();
  cmd->add_option("--out,-o", opt->out, "Output folder (accuracy)");
  cmd->add_option("--from", opt->from, "A finished study's ensemble.csv (table)");
  cmd->add_option("--preset", opt->preset, "quick (3 mm of shear, default), full (6 mm), ci (reduced)")
      ->capture_default_str();
  cmd->add_option("--knob", opt->knobs,
                  "Only these knobs (with the reference): time step, precision, stiffness, "
                  "inertial number, skin, effects, combination, baseline");
  cmd->add_option("--ensemble", opt->ensemble,
                  "Members per setting, specimens differing only in their seed (default: quick 3, "
                  "full 5, ci 2)");
  cmd->add_flag("--no-shear", opt->no_shear, "Contact checks only");
  cmd->add_flag("--resume", opt->resume,
                "Continue the study in --out after its finished cases (same --preset and --knob)");
  cmd->add_flag("--quiet,-q", opt->quiet, "No progress lines");
  return [opt] { return study(*opt); };
}

}  // namespace simsols
