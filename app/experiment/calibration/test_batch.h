// A batch of tests run one after another with the campaign loop
// (campaign_loop.h): each kept when it finished earlier, resumed from its
// checkpoint when it was stopped, else run, with progress and an ETA that
// also covers the work after the batch. The calibration's rounds and
// replicates and the prediction's specimens are such batches. A folder
// whose scene.toml differs from the test asked for now (the values
// changed since it ran) is refused (SceneError "stale_run") before
// anything runs: a kept result must be the result of the test it stands
// for.
#pragma once

#include <filesystem>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "solver/core/cl_device.h"
#include "solver/scene/scene.h"

namespace simsols {

struct BatchTest {
  Scene scene;  // as read (run_scene_test places it)
  std::filesystem::path dir;
  double cost = 0;  // particle-steps (expected_particle_steps)
  size_t target = 0;  // the caller's indices
  int design = 0;
};

struct BatchCluster {
  enum class Mode { here, emit, task, collect };
  Mode mode = Mode::here;
  size_t task = 0;
  // --task, --collect: the tests of the job the folder's manifest lists
  // (empty: none written yet).
  std::vector<std::string> job_tests;
  std::string manifest;  // that manifest's path, for messages
  // Writes the job array of a batch's tests (`batch`: "round0", ...).
  std::function<void(const std::vector<BatchTest>&, const std::string& batch)> write_job;
};

struct BatchOptions {
  std::shared_ptr<Device> device;
  bool quiet = false;
  std::function<bool()> stop_requested;
  std::string what = "tests";  // progress lines' noun
  std::string batch;           // its name in a cluster job ("round0", "replicates")
  const BatchCluster* cluster = nullptr;  // null: every test here
};

struct BatchOutcome {
  bool interrupted = false;
  std::string interrupted_dir;
  double seconds = 0;  // wall time of the tests run now
  bool ended = false;  // on a cluster: a job written or a task run; the command ends
};

BatchOutcome run_batch(std::vector<BatchTest>& tests, double later_cost, const BatchOptions& o);

}  // namespace simsols
