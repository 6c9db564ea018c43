// The direct shear box as a scene describes it ([shear_box], docs/shear-box.md).
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "solver/scene/choice_table.h"
#include "solver/scene/specimen.h"

namespace simsols {

// The direct shear apparatus of the reference paper (its section 5) and its
// loading program. The box is x in [0, length] (the shear direction),
// y in [0, width], floor at z = 0, split at z = split_height into a lower and
// an upper half with `gap` between them. The lower half (floor and four side
// plates) moves in +x at the shear speed; the upper half and the platen are
// held horizontally; the platen is servo-controlled to the normal stress.
// build_shear_box() (shear_box.h) turns this into twelve walls (and particles) and
// resolves the automatic values (0 below) into numbers.
struct ShearBox : ApparatusCell {
  ShearBox() { length = 60.23e-3; width = 60.07e-3; }  // inside: x the shear direction
  double split_height = 0;         // m; 0 = mid-height of the specimen (see shear_box.h)
  double gap = 0;                  // m between the halves; 0 = 0.2 x smallest diameter
  // The floor's and the platen's material (the inserts that grip the soil
  // in a laboratory box: porous stones, serrated plates); -1 = wall_material.
  int insert_material = -1;
  double normal_stress = 160e3;    // Pa, the platen's target
  double shear_speed = 0;          // m/s; 0 = from inertial_number
  double inertial_number = 8e-4;   // target I = (v/H) d sqrt(rho/sigma) for the automatic speed
  double shear_displacement = 6e-3;  // m of horizontal displacement to shear
  // How the platen carries the normal load (docs/shear-box.md): a dead
  // weight (a rigid platen of platen_mass under the constant force
  // sigma x area, as a hanger loads a real box) or a servo (PI on the
  // reaction, servo_* below). Consolidation is servo-controlled in both.
  enum class Loading : std::uint8_t { DeadWeight, Servo };
  Loading loading = Loading::DeadWeight;
  double platen_mass = 0;          // kg; 0 = automatic (a quarter layer of beads, pi rho d A / 24)
  double servo_gain = 0;           // m/(s N); 0 = automatic (from the Hertz stiffness)
  double servo_max_speed = 0.5;    // m/s, the platen's speed cap
  double servo_integral_time = 0;  // s; 0 = automatic
  // The upper half during shear (docs/shear-box.md "Apparatus choices"):
  // fixed (held vertically, the paper's box) or floating (free vertically,
  // held horizontally, as a box whose gap screws are backed off: its side
  // plates and frame move as one body under upper_half_weight, pulled by
  // the beads' friction on them, and come to rest on the lower half when
  // the gap closes). Consolidation holds it in both.
  enum class UpperHalf : std::uint8_t { Fixed, Floating };
  UpperHalf upper_half = UpperHalf::Fixed;
  double upper_half_weight = 0;    // N the floating half rests with; 0 = counterweighted
  // The loading cap (the platen) during shear: held level (the paper's
  // box) or free to tilt in the shear plane (about y through its centre,
  // as a cap on a ball seat: a rigid plate of platen_mass turned by the
  // beads' moment). Tilting needs loading = dead_weight; consolidation
  // holds it level in both.
  enum class Cap : std::uint8_t { Held, Tilting };
  Cap cap = Cap::Held;
  double consolidate_time = 0.1;   // s, longest consolidation under the platen
  int rows = 400;                  // output rows over the shear displacement
};

// The apparatus walls, in this order from ShearBox::first_wall: the lower
// half [kFloor, kLowerLast], the upper half and platen [kUpperX0, kPlaten].
// The frames are the top face of the lower half's x0 wall and the bottom
// face of the upper half's x1 wall (see shear_box.h).
enum ShearBoxWall : int {
  kFloor = 0, kLowerX0, kLowerX1, kLowerY0, kLowerY1, kLowerFrame,
  kUpperX0, kUpperX1, kUpperY0, kUpperY1, kUpperFrame, kPlaten, kShearBoxWalls,
  kLowerLast = kLowerFrame
};

// [shear_box] loading's names (choice_table.h).
template <> std::span<const Named<ShearBox::Loading>> choices();
template <> std::span<const Named<ShearBox::UpperHalf>> choices();
template <> std::span<const Named<ShearBox::Cap>> choices();

}  // namespace simsols
