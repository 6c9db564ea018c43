// The oedometer as a scene describes it ([oedometer], docs/oedometer.md).
#pragma once

#include <vector>

#include "solver/scene/specimen.h"

namespace simsols {

// The oedometer (one-dimensional compression, docs/oedometer.md): a rigid
// square ring x in [0, length], y in [0, width] on a floor at z = 0, and a
// top platen servo-controlled to each vertical stress of `load_steps` in
// turn, each held until the specimen is in equilibrium under it (or for
// step_time at most). The steps up to the largest are the loading branch,
// those after it the unloading branch. build_oedometer() (apparatus/
// oedometer.h) turns this into six walls (and particles) and resolves the
// automatic values (0 below).
struct Oedometer : ApparatusCell {
  Oedometer() { length = 60e-3; width = 60e-3; }  // inside
  std::vector<double> load_steps = {25e3, 50e3, 100e3, 200e3, 400e3, 800e3, 200e3, 50e3, 25e3};  // Pa
  double step_time = 0.1;          // s, longest hold of one load step
  double servo_gain = 0;           // m/(s N); 0 = automatic (from the Hertz stiffness)
  double servo_max_speed = 0.5;    // m/s, the platen's speed cap
  double servo_integral_time = 0;  // s; 0 = automatic
  double friction_angle = 0;       // deg, phi' for Jaky's K0 = 1 - sin phi'; 0 = none given
};

// The oedometer's walls, in this order from Oedometer::first_wall.
enum OedometerWall : int {
  kOedFloor = 0, kOedX0, kOedX1, kOedY0, kOedY1, kOedPlaten, kOedometerWalls
};

}  // namespace simsols
