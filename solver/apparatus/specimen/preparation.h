// A specimen prepared to a target relative density, and what a prepared
// specimen is like (docs/specimens.md).
//
// A laboratory finds a sand's index void ratios by its densest and its
// loosest preparations, then prepares each specimen by a method whose
// density it has calibrated. Here the method is the scene's pour, and the
// calibrated knob is the friction the beads settle with (Preparation::
// friction): settled frictionless they reach their densest random packing
// (e_min); settled with kLooseFriction they lock up loose (e_max); in
// between, e rises with the friction. A target D_r is met by a regula falsi
// search on that friction, each trial the scene's own pour settled in its own cell,
// so the test then pours the very specimen the search found.
#pragma once

#include <filesystem>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "solver/apparatus/specimen/prep_log.h"
#include "solver/apparatus/apparatus.h"
#include "solver/apparatus/specimen/packing.h"
#include "solver/core/cl_device.h"

namespace simsols {

// The friction of the loosest preparation; the search's most trials and
// the D_r it is content with (a few hundred beads scatter D_r by ~0.05
// from one friction to a nearby one: docs/specimens.md).
inline constexpr double kLooseFriction = 1.0;
inline constexpr int kSearchTrials = 5;
inline constexpr double kSearchTolerance = 0.05;

// The packing of the simulation's specimen now.
Packing measure_specimen(Simulation& sim);

// The scene's apparatus test run until its specimen has settled; the
// packing then, and the simulated seconds it took.
struct Settled {
  Packing packing;
  double seconds = 0;
  long long steps = 0;
};
// `progress`, when given, hears a line about every 10 s of wall time:
// the simulated time settled so far and the steps.
Settled settle_specimen(const Scene& scene, const std::shared_ptr<Device>& device,
                        const PrepLog& progress = {});

// One preparation of the search: its friction and what it gave.
struct DensityTrial {
  std::string role;  // "densest", "loosest", "trial"
  double friction = 0;
  Settled result;
  std::shared_ptr<const Scene> grown;  // radius expansion: the specimen this trial grew
};
struct DensitySearch {
  double e_min = 0, e_max = 0, target = 0;
  double friction = 0;  // chosen
  double achieved = 0;  // D_r of the chosen trial
  std::vector<DensityTrial> trials;
};

// The specimen prepared as the scene asks, the one step between a scene
// and its test (app/experiment/apparatus_run.h):
// - a relative density or void ratio: finds e_min and e_max (unless
//   given), then the friction that gives the target, and writes it into
//   the scene's preparation (the target itself is then cleared: the scene
//   holds what the test runs); density.csv in `out_dir`, and the search in
//   `*searched` when given (app/experiment/specimen_report.h draws it);
// - layered tamping (tamping.h) and radius expansion (expansion.h) build
//   the specimen instead and leave it in the scene, `given`; an expansion
//   to a void ratio or relative density searches the friction the same
//   way, each trial grown.
// `log` receives one line per preparation and is asked between chunks of
// steps whether to stop (PreparationStopped, prep_log.h). Returns nothing
// to do as false.
bool prepare_specimen(Scene& scene, const std::shared_ptr<Device>& device,
                      const std::filesystem::path& out_dir, const PrepLog& log,
                      DensitySearch* searched = nullptr);

// packing.txt: the packing, with D_r when the scene knows e_min and e_max.
std::string packing_text(const Packing& p, const Preparation& prep);

}  // namespace simsols
