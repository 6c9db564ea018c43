// The triaxial cell as a scene describes it ([triaxial], docs/triaxial.md).
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "solver/scene/choice_table.h"
#include "solver/scene/specimen.h"

namespace simsols {

// The triaxial test (docs/triaxial.md): a cuboid specimen between six
// rigid plates, x in [0, length], y in [0, width] on a floor at z = 0. The
// floor is fixed; the top platen and the four sides are servo-controlled.
// Stages: isotropic consolidation to confining_stress on all five, then
// drained axial compression, the platen moved down at a constant strain
// rate while the sides hold the lateral stresses of the stress path:
//   constant_sigma3  both lateral stresses at confining_stress (the
//                    conventional test);
//   constant_p       the lateral stresses follow sigma3 = (3 p0 - sigma1)/2
//                    so the mean stress p' stays at confining_stress (never
//                    below 5 % of it: the sides keep the specimen closed);
//   true_triaxial    sigma3 (x) at confining_stress, sigma2 (y) at
//                    sigma3 + b (sigma1 - sigma3).
// The sides are the cell's `cell`:
//   rigid     the four servo-controlled plates throughout;
//   membrane  the plates consolidate the specimen, then hand it to a
//             flexible membrane of bonded beads (scene.h, Membrane) under
//             the cell pressure for the compression (constant_sigma3 only).
// build_triaxial() (apparatus/triaxial.h) turns this into six walls (and
// particles) and resolves the automatic values (0 below).
struct Triaxial : ApparatusCell {
  Triaxial() { length = 30e-3; width = 30e-3; settle_time = 0.02; }  // inside at the start
  enum class Path : std::uint8_t { ConstantSigma3, ConstantP, TrueTriaxial };
  enum class Cell : std::uint8_t { Rigid, Membrane };
  Cell cell = Cell::Rigid;
  double membrane_stiffness = 420;  // N/m, the membrane's E t (docs/triaxial.md)
  double membrane_spacing = 0.5;    // its lattice spacing / the smallest bead's diameter (beads of radius the spacing)
  double confining_stress = 100e3; // Pa, p'0 and sigma3
  Path path = Path::ConstantSigma3;
  double b_value = 0.5;            // true_triaxial: (sigma2 - sigma3) / (sigma1 - sigma3), [0, 1]
  double axial_strain = 0.15;      // to compress to
  double strain_rate = 0;          // 1/s; 0 = from inertial_number
  double inertial_number = 5e-4;   // target I = strain_rate d sqrt(rho / p0)
  double consolidate_time = 0.1;   // s, longest isotropic consolidation
  double servo_gain = 0;           // m/(s N); 0 = automatic (from the Hertz stiffness)
  double servo_max_speed = 0.5;    // m/s, the plates' speed cap
  double servo_integral_time = 0;  // s; 0 = automatic
  int rows = 200;                  // rows over the axial strain
};

// The triaxial cell's walls, in this order from Triaxial::first_wall.
enum TriaxialWall : int {
  kTriFloor = 0, kTriX0, kTriX1, kTriY0, kTriY1, kTriPlaten, kTriaxialWalls
};

// [triaxial] path's and cell's names (choice_table.h).
template <> std::span<const Named<Triaxial::Path>> choices();
template <> std::span<const Named<Triaxial::Cell>> choices();

}  // namespace simsols
