// The periodic cell as a scene describes it ([periodic_cell],
// docs/periodic-cell.md).
#pragma once

#include <array>
#include <optional>
#include <cstdint>

namespace simsols {

// A specimen with no boundary: a cell repeated in all three directions
// (solver/core/periodic_box.h). build_periodic_cell() (solver/apparatus/
// periodic_cell/) fills a cube with a random gas of `particles` spheres at
// solid fraction start_solid_fraction; the programme compresses it
// isotropically to `pressure` with the preparation friction (0: dense,
// larger: looser), then runs the test at the materials' own friction:
//   simple_shear  v_x = gamma_dot z with the cell's sides fixed and sigma_zz
//                 held at `pressure`, to shear_strain;
//   triaxial      shortening along z at a constant rate, sigma_xx = sigma_yy
//                 held at `pressure` (path constant_sigma3) or moved to keep
//                 p = `pressure` (constant_p), to axial_strain;
//   isotropic     the compression alone, its rows the test;
//   oedometric    one-dimensional compression: z shortened at the test's
//                 rate with x and y held (no lateral strain) until sigma_zz
//                 reaches vertical_stress, then lengthened until it is back
//                 at `pressure` (loading and unloading, as an oedometer).
// Rates are set by inertial numbers I = rate d sqrt(rho / P).
struct PeriodicCell {
  enum class Test : std::uint8_t { SimpleShear, AxialCompression, Isotropic, Oedometric };  // "triaxial" is AxialCompression
  enum class Path : std::uint8_t { ConstantSigma3, ConstantP };
  int particles = 1000;
  double diameter = 1e-3;          // m, mean
  double size_spread = 0.1;        // diameters uniform in d (1 +- spread/2), [0, 1)
  int material = 0;
  std::int64_t seed = 1;
  double start_solid_fraction = 0.2;  // the gas, (0, 0.4]
  double preparation_friction = 0;    // mu_s while compressed
  double preparation_restitution = 0.5;  // restitution while compressed: the gas cools
  // The rolling friction (m) while compressed; unset: the materials' own. A
  // calibration that fits the rolling friction sets it, so the packing
  // does not change with the parameter.
  std::optional<double> preparation_rolling_friction;
  double pressure = 100e3;            // Pa
  Test test = Test::SimpleShear;
  Path path = Path::ConstantSigma3;
  double inertial_number = 1e-3;       // of the test's shear or axial rate
  double compression_inertial_number = 1e-2;  // the servo's fastest strain rate
  double shear_strain = 1.0;           // simple_shear: gamma at the end
  double axial_strain = 0.2;           // triaxial: epsilon_zz at the end
  double vertical_stress = 0;          // oedometric: Pa, the largest sigma_zz; 0 = 4 x pressure
  double row_strain = 0.01;            // strain between rows
  // Particles and cell as placed (a resolved scene: to_toml writes them, so
  // the same specimen is read back); unset: generated from the seed.
  bool given = false;
  std::array<double, 9> edges{};       // m, when given
};

}  // namespace simsols
