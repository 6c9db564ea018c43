#include "app/experiment/apparatus_run.h"

#include <unistd.h>

#include <cstdio>
#include <filesystem>

#include "app/experiment/apparatus_report.h"
#include "app/experiment/specimen_report.h"
#include "app/experiment/test_title.h"
#include "solver/io/output.h"
#include "solver/io/scene_toml.h"

namespace simsols {
namespace {

namespace fs = std::filesystem;

// What every apparatus' run writes: its rows file, its plots, summary.txt.
class TestOutputs : public ProgrammeOutputs {
 public:
  TestOutputs(const ApparatusKind& kind, ApparatusProgramme& test) : kind_(kind), test_(test) {}
  LoadingProgramme& programme() override { return test_; }
  void save_rows(const fs::path& dir) override {
    write_file_atomic((dir / test_.rows_file()).string(), test_.rows_csv());
  }
  std::string describe() override { return test_.describe(); }
  void on_measuring(const std::string& label) override {
    const std::string line = test_.measuring_line();
    if (!line.empty())
      std::fprintf(stderr, "%s[%s] %s\n", isatty(fileno(stderr)) ? "\r" : "", label.c_str(),
                   line.c_str());
  }
  void write_results(Simulation& sim, const fs::path& dir, double wall_seconds) override {
    write_test_plots(dir.string(), test_title(sim.scene()), kind_, test_);
    write_file_atomic((dir / "summary.txt").string(), test_.summary_text(wall_seconds));
  }

 private:
  const ApparatusKind& kind_;
  ApparatusProgramme& test_;
};

// --stop-at names one of the kind's stages.
void check_stop_at(const ApparatusKind& kind, const std::string& stop_at) {
  if (stop_at.empty() || has_stage(kind, stop_at)) return;
  throw UsageError("out_of_range", "--stop-at",
                   "'" + stop_at + "' is not a stage of " + kind.test_noun + "; allowed: " +
                       kPreparedStage + "," + kind.stages +
                       " (it stops at the end of that stage; prepared: before any loading)");
}

TestRun drive(std::unique_ptr<Simulation> sim, const ProgrammeRunOptions& opt,
              const std::string* resumed_state) {
  TestRun run;
  run.kind = apparatus_kind(sim->scene());
  run.programme = make_programme(*sim);
  run.sim = std::move(sim);
  ProgrammeRunOptions labelled = opt;
  if (labelled.label.empty()) labelled.label = run.kind->label;
  // a resumed test's series keeps its frames up to the checkpoint, however
  // the caller came to resume it
  labelled.resume = resumed_state != nullptr;
  double wall_before = 0;
  if (resumed_state) {
    restore_programme(*run.programme, *resumed_state, opt.out_dir);
    wall_before = driver_wall_seconds(*resumed_state);
    std::fprintf(stderr, "[%s] resumed at %s\n", labelled.label.c_str(),
                 where_programme_is(*run.sim, *run.programme).c_str());
  }
  TestOutputs outputs(*run.kind, *run.programme);
  run.state = drive_programme(*run.sim, outputs, labelled, wall_before);
  return run;
}

}  // namespace

TestRun resume_test(std::unique_ptr<Simulation> sim, const std::string& extra,
                    const ProgrammeRunOptions& opt) {
  if (!sim->scene().has_apparatus())
    throw SceneError("bad_checkpoint", (fs::path(opt.out_dir) / "checkpoint.bin").string(), 0,
                     "--resume", "the checkpoint is not a test of an apparatus (" +
                                     apparatus_names(", ") + ")");
  check_stop_at(*apparatus_kind(sim->scene()), opt.stop_at);
  if (opt.stop_at == kPreparedStage)
    throw UsageError("not_applicable", "--stop-at",
                     "a resumed test is past its preparation: name a stage of its own");
  return drive(std::move(sim), opt, &extra);
}

TestRun run_test(const Scene& scene, const ProgrammeRunOptions& opt) {
  if (opt.resume) {
    std::string state;
    auto sim = load_run_checkpoint(opt, &state);
    return resume_test(std::move(sim), state, opt);
  }
  check_stop_at(required_apparatus_kind(scene), opt.stop_at);  // before any device or folder work
  auto sim = std::make_unique<Simulation>(opt.device, scene);
  start_run_folder(scene, opt.out_dir);
  return drive(std::move(sim), opt, nullptr);
}

TestRun run_scene_test(Scene scene, const ProgrammeRunOptions& opt,
                       const std::function<void(const std::string&)>& log) {
  if (!opt.resume) {
    check_stop_at(required_apparatus_kind(scene), opt.stop_at);  // before a long preparation
    place_scene(scene);
    prepare_to_relative_density(scene, opt.device, opt.out_dir, PrepLog(log, opt.stop_requested));
  }
  return run_test(scene, opt);
}

}  // namespace simsols
