// The specimen of an apparatus with a rectangular cell, as a scene describes
// it: its grading, how it is placed and prepared (solver/apparatus/specimen/
// places and prepares it; docs/specimens.md), and ApparatusCell, the cell
// every apparatus kind is (apparatus/kinds.h).
#pragma once

#include <cstdint>
#include <optional>
#include <vector>

namespace simsols {

// A grading curve: the mass fraction of a specimen passing each size, as a
// sieve analysis gives it (docs/specimens.md; solver/apparatus/specimen/grading.h).
struct Grading {
  enum class Law : std::uint8_t { Single, Uniform, LogNormal, Fuller, Sieve };
  Law law = Law::Single;       // Single: every bead of specimen.diameter
  double d_min = 0, d_max = 0; // m, the cut-offs (0 = the law's default where it has one)
  double sigma = 0.25;         // LogNormal: standard deviation of ln d, by mass (D50 = diameter)
  double exponent = 0.5;       // Fuller: P = (d^n - d_min^n) / (d_max^n - d_min^n)
  std::vector<double> sizes;   // Sieve: m, increasing
  std::vector<double> passing; // Sieve: % by mass, from 0 to 100, non-decreasing
};

// How a specimen is brought to its density (docs/specimens.md). The
// friction applies while the specimen settles (lubricated or rough
// preparation), then the materials' own friction takes over; the pour's
// drop height and intensity shape its rain.
struct Preparation {
  std::optional<double> friction;          // mu_s of every pair while settling; unset: the materials'
  std::optional<double> rolling_friction;  // mu_r (m) while settling; unset: the materials'
  double drop_height = 0;  // m, Pour: the beads start at the speed of a free fall from this height
  double intensity = 0;    // Pour: solid fraction of the raining column, (0, 0.35]; 0: 3 specimen heights tall
  std::optional<double> relative_density;  // target D_r: the friction is searched (docs/specimens.md)
  std::optional<double> e_min, e_max;      // the material's index void ratios, when known
  int tamping_layers = 0;                  // Pour: built in this many tamped layers (0: poured at once)
  std::optional<double> void_ratio;        // target e of tamping or expansion (or from relative_density)
  double undercompaction = 0.05;           // Ladd's U_1: the bottom layer's shortfall of dry density
  bool expansion = false;                  // Pour of spheres: grown in the closed cell (radius expansion)
  bool settles_differently() const { return friction || rolling_friction; }
};

struct Specimen {
  enum class Method : std::uint8_t { Layers, Pour, Given };
  enum class Clearance : std::uint8_t { Shift, Spread };
  Method method = Method::Layers;  // Table 1 layers / random pour / the scene's particles
  int material = 0;                // the beads' material
  double diameter = 0;             // m (Layers, Pour)
  int layers = 0;                  // Layers: layers; Pour: beads for that many layers
  Clearance clearance = Clearance::Shift;  // Layers: how the row-wall clearance is used
  std::int64_t seed = 1;
  Grading grading;                 // Pour: the sizes' distribution
  int grain = -1;                  // Pour: clumps of this grain (Scene::grains) instead of beads
  Preparation preparation;         // how it settles (every method)
};

// What every apparatus is: a cell on a floor at z = 0, x in [0, length],
// y in [0, width], holding a specimen, its walls Scene::walls[first_wall..]
// (in the apparatus' own order). The builders (the registry's `build`,
// solver/apparatus/registry.h) place the specimen and add the walls.
struct ApparatusCell {
  double length = 0;           // m, inside, along x
  double width = 0;            // m, inside, along y
  int wall_material = -1;      // the walls' material; -1 = "steel" (added when absent)
  double settle_time = 0.01;   // s, longest settling under gravity
  Specimen specimen;
  int first_wall = 0;          // set by the builder
};

}  // namespace simsols
