// `simsols calibrate`: a material's parameters fitted to measured curves,
// with their uncertainty (docs/calibration.md).
//
// The calibration runs rounds of simulations. A design is one set of the
// parameters; each design runs every target's test (its scene with the
// parameters and the target's own keys set, scene_keys.h) into
//   OUT/runs/round<r>_<i>/<target>/
// Round 0 spreads its designs over the ranges (a Sobol sequence); after
// each round a surrogate (surrogate.h) is fitted to every design so far
// and the posterior (posterior.h) is computed; the next round draws its
// designs from it. At the end, the specimens' own scatter is measured:
// the most likely set runs every target again on `replicates` other seeds
// (the kind's seed key, registry.h; seeds 1001, 1002, ...), one batch, into
//   OUT/runs/replicate<k>/<target>/
// and the posterior is computed once more with that scatter in the
// likelihood. What it writes is in calibration_report.h.
//
// Every run keeps what finished: the same command continues an
// interrupted calibration (finished tests are read back, an interrupted
// one resumes from its checkpoint), with progress and an ETA over all the
// rounds (campaign_loop.h). On a Slurm cluster each batch (a round, the
// replicates) is a job array, and the job collecting one writes and
// submits the next (test_batch.h, docs/cluster.md).
#pragma once

#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "app/experiment/calibration/calibration_spec.h"
#include "app/experiment/calibration/curves.h"
#include "app/experiment/calibration/posterior.h"
#include "app/experiment/calibration/test_batch.h"
#include "solver/core/cl_device.h"

namespace simsols {

struct CalibrationOptions {
  std::shared_ptr<Device> device;
  std::string out_dir;
  bool quiet = false;
  std::function<bool()> stop_requested;  // Ctrl-C (interrupt.h)
  const BatchCluster* cluster = nullptr;  // the cluster flags; null: all here
};

// One measured curve against the calibrated material, in the measured
// column's unit.
struct CurveFit {
  std::string target, quantity, unit;
  int points = 0;
  double rms_misfit = 0;    // of the replicates' mean curve from the measured one
  double seed_scatter = 0;  // one specimen's standard deviation, r.m.s. over the points
  double measured_scatter = 0;  // the user's; NaN when not given
  double misfit = 0;        // D (posterior.h) of the replicates' mean
};

// A simulation of the design: its round ("0", "1", ..., "replicate"),
// design, parameters and each curve's r.m.s. misfit (measured units).
struct DesignRow {
  std::string round;
  int design = 0;
  std::string target;
  std::vector<double> parameters;
  std::vector<double> rms;  // per y of the target
};

struct CalibrationResult {
  bool interrupted = false;
  std::string interrupted_dir;  // the test that was stopped
  bool ended = false;  // on a cluster: a batch's job written or a task run, no result
  Posterior posterior;          // the last one, with the specimens' scatter
  std::vector<double> calibrated;  // the replicates' parameters (the mode before them)
  std::vector<CurveFit> curves;
  std::vector<DesignRow> design;
  std::vector<Curve> measured;                 // per target
  std::vector<std::vector<Curve>> replicates;  // per target, per seed
  int simulations = 0;
  double seconds = 0;  // wall time of the tests run now
};

CalibrationResult run_calibration(const CalibrationSpec& spec, const CalibrationOptions& options);

}  // namespace simsols
