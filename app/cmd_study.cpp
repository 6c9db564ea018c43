// simsols study accuracy: the accuracy study (study.h).
//
//   simsols study accuracy --out DIR [--preset quick|full|ci] [--knob NAME ...] [--no-shear] [-q]
//
// Outputs in DIR, rewritten after every case (an interrupted study keeps the
// cases it finished): cases.csv, summary.md (tables and the recommendation),
// error_vs_time_<knob>.png per knob and pareto.png.
#include <chrono>
#include <cstdio>

#include "commands.h"
#include "errors.h"
#include "study.h"

namespace simsols {
namespace {

struct StudyOptions {
  std::string what;
  std::string out;
  std::string preset = "quick";
  std::vector<std::string> knobs;
  bool no_shear = false;
  bool quiet = false;
};

int study(const StudyOptions& opt) {
  if (opt.what != "accuracy")
    throw SceneError("bad_enum", "command line", 0, "STUDY", "'" + opt.what + "' is not one of: accuracy");
  auto preset = study_preset(opt.preset);
  if (!preset)
    throw SceneError("bad_enum", "command line", 0, "--preset",
                     "'" + opt.preset + "' is not one of: quick, full, ci");
  if (opt.no_shear) preset->shear = false;
  std::vector<StudySettings> cases;
  for (size_t i = 0; i < preset->cases.size(); ++i) {
    const StudySettings& s = preset->cases[i];
    if (i == 0 || opt.knobs.empty() ||
        std::find(opt.knobs.begin(), opt.knobs.end(), s.knob) != opt.knobs.end())
      cases.push_back(s);
  }
  std::vector<StudyCase> done;
  const auto t0 = std::chrono::steady_clock::now();
  for (size_t i = 0; i < cases.size(); ++i) {
    const double elapsed =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    if (!opt.quiet)
      std::fprintf(stderr, "[study %zu/%zu] %s: %s (elapsed %.0f s%s)\n", i + 1, cases.size(),
                   cases[i].knob.c_str(), cases[i].label.c_str(), elapsed,
                   i > 0 ? (", ETA " + std::to_string(int(elapsed / i * (cases.size() - i))) + " s").c_str() : "");
    StudyCase c;
    c.settings = cases[i];
    c.contact = run_contact_checks(cases[i]);
    if (preset->shear) c.shear = run_shear_case(*preset, cases[i]);
    if (!opt.quiet) {
      if (c.contact.ok)
        std::fprintf(stderr, "    contact: worst error %.3g %%\n", c.contact.worst());
      else
        std::fprintf(stderr, "    contact: failed: %s\n", c.contact.failure.c_str());
      if (preset->shear) {
        if (c.shear.ok)
          std::fprintf(stderr, "    shear: phi_peak %.2f, phi_res %.2f, psi_max %.2f deg in %.1f s\n",
                       c.shear.peak_angle, c.shear.residual_angle, c.shear.dilatancy_angle,
                       c.shear.wall_seconds);
        else
          std::fprintf(stderr, "    shear: failed: %s\n", c.shear.failure.c_str());
      }
    }
    done.push_back(c);
    compare_to_reference(done);
    write_study_outputs(opt.out, *preset, done);
  }
  std::printf("study %s (%s): %zu cases; results in %s (cases.csv, summary.md, pareto.png)\n",
              opt.what.c_str(), preset->name.c_str(), done.size(), opt.out.c_str());
  return 0;
}

}  // namespace

CommandRunner add_study_command(CLI::App& app) {
  auto opt = std::make_shared<StudyOptions>();
  CLI::App* cmd = app.add_subcommand("study", "Measured studies: what accuracy costs in time");
  cmd->add_option("study", opt->what, "accuracy")->required();
  cmd->add_option("--out,-o", opt->out, "Output folder")->required();
  cmd->add_option("--preset", opt->preset, "quick (3 mm of shear, default), full (6 mm), ci (reduced)")
      ->capture_default_str();
  cmd->add_option("--knob", opt->knobs,
                  "Only these knobs (with the reference): time step, precision, stiffness, "
                  "inertial number, skin, effects, combination, baseline");
  cmd->add_flag("--no-shear", opt->no_shear, "Contact checks only");
  cmd->add_flag("--quiet,-q", opt->quiet, "No progress lines");
  return [opt] { return study(*opt); };
}

}  // namespace simsols
