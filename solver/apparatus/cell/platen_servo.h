// The automatic settings of a platen's servo, shared by every apparatus
// that loads a specimen through a servo-controlled platen.
//
// A platen rests on about one bead per d^2 of its area; at a stress sigma
// each of those contacts carries f = sigma d^2 and has the Hertz tangent
// stiffness k_c = 3/2 f^(1/3) k^(2/3), k = 4/3 E* sqrt(d/2). The platen's
// stiffness is their sum. The proportional gain makes the platen's contacts
// relax in about 1/kGainFraction steps (gain = 0.5 / (k_platen dt)); the
// integral removes the steady error while the specimen deforms, over five
// periods of the specimen's vertical oscillation on the platen's stiffness
// shared among its layers (docs/shear-box.md). The contacts stiffen as
// sigma^(1/3), so the settings are retuned whenever the target changes.
#pragma once

#include "solver/scene/scene.h"

namespace simsols {

// What the tuning needs to know of a specimen, measured once from the scene.
struct SpecimenStats {
  double diameter = 0;       // m, mean bead diameter
  double bead_mass = 0;      // kg, mean
  double density = 0;        // kg/m^3, of the first bead
  double mass = 0;           // kg, all beads
  double count = 0;          // the beads (a membrane's not counted)
  double volume = 0;         // m^3, all beads (the solids' volume)
  double layers = 1;         // height of the beads' top over the diameter (>= 1)
  double k_hertz = 0;        // N/m^1.5, the bead-platen Hertz constant 4/3 E* sqrt(d/2)
};
SpecimenStats specimen_stats(const Scene& scene, int wall_material);

struct PlatenServo {
  double gain = 0;           // m/(s N)
  double integral_time = 0;  // s
};

// Settings for a platen of `area` at `stress`, time step dt; a positive
// gain or integral_time given by the scene is kept as it is.
PlatenServo tune_platen_servo(const SpecimenStats& s, double area, double stress, double dt,
                              double given_gain, double given_integral_time);

}  // namespace simsols
