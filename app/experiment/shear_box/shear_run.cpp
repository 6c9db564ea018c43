#include "app/experiment/shear_box/shear_run.h"

#include <cstdio>

#include "app/experiment/apparatus_run.h"

namespace simsols {
namespace {

ShearRunResult shear_result(const TestRun& run) {
  const auto typed = typed_result<ShearProgramme>(run);
  ShearRunResult result;
  result.rows = typed.rows;
  result.summary = typed.summary;
  result.finished = run.state.finished;
  result.interrupted = run.state.interrupted;
  result.steps = run.state.steps;
  result.particles = run.state.particles;
  result.dt = run.state.dt;
  return result;
}

}  // namespace

std::string where_test_is(const Simulation& sim, const ShearProgramme& test) {
  const double dx = test.rows().empty() ? 0 : test.rows().back().displacement;
  char buf[160];
  std::snprintf(buf, sizeof buf, "step %lld, t = %.6g s, %s, dx = %.3f mm (%zu rows)",
                static_cast<long long>(sim.steps()), sim.time(), phase_name(test.phase()),
                dx * 1e3, test.rows().size());
  return buf;
}

ShearRunResult resume_shear(std::unique_ptr<Simulation> sim, const std::string& state,
                            const ShearRunOptions& opt) {
  if (!sim->scene().apparatus_as<ShearBox>())
    throw SceneError("bad_checkpoint", opt.out_dir + "/checkpoint.bin", 0, "--resume",
                     "the checkpoint is not a shear test");
  return shear_result(resume_test(std::move(sim), state, opt));
}

ShearRunResult run_shear(const Scene& scene, const ShearRunOptions& opt) {
  if (opt.resume) {
    std::string state;
    auto sim = load_run_checkpoint(opt, &state);
    return resume_shear(std::move(sim), state, opt);
  }
  if (!scene.apparatus_as<ShearBox>())
    throw SceneError("missing_field", scene.source_path, 0, "shear_box",
                     "the scene has no shear box");
  return shear_result(run_test(scene, opt));
}

}  // namespace simsols
