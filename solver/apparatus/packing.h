// The state of a prepared specimen, as a laboratory reports it before a
// test: how dense it is, how many contacts each grain has, how the
// contacts are oriented.
//
// The void ratio is that of a mould struck level below the specimen's
// rough top: the solid volume of the beads inside the slab from the floor
// to the highest bead top less one largest diameter, over the slab's
// volume (each bead counts with the spherical segment inside the slab, so
// the value is exact for any arrangement). Floor and side walls are inside
// the slab, as in a mould, so their loosening counts. The coordination
// counts every contact, bead or wall, once per bead touching it; the
// fabric is that of the bead pairs' contact normals, phi = <n n>, with the
// deviatoric anisotropy a = (15/2)(phi_zz - (phi_xx + phi_yy)/2), zero for
// isotropic contacts (Oda; Rothenburg and Bathurst's a_ij = 15/2 phi'_ij).
// The relative density D_r = (e_max - e) / (e_max - e_min) needs the
// material's index void ratios (docs/specimens.md).
#pragma once

#include <optional>
#include <span>
#include <vector>

#include "solver/core/stress.h"

namespace simsols {

struct Packing {
  int beads = 0;
  double slab_height = 0;   // m, floor to the highest top less one largest diameter
  double void_ratio = 0;    // e = V_voids / V_solid in the slab
  double solid_fraction = 0;
  double coordination = 0;  // contacts (beads and walls) per bead
  double bead_coordination = 0;  // bead pairs x 2 per bead
  std::array<double, 3> fabric{};  // phi_xx, phi_yy, phi_zz over bead pairs
  double fabric_anisotropy = 0;    // (15/2)(phi_zz - (phi_xx + phi_yy)/2)
};

// The volume of the sphere (centre height z, radius r) between the
// horizontal planes lo < hi.
double sphere_volume_between(double z, double r, double lo, double hi);

// The fabric anisotropy of the bead pairs' contact normals (see above).
double fabric_anisotropy(const ContactSample& sample);

// The packing of the beads in a cell of footprint length x width (m) with
// its floor at z = floor_z. `share`, when given, scales each bead's
// segment: a clump member's share of its union's volume over its sphere's
// (clump.h, solid_volumes), so overlapping members count once (exactly
// for a clump wholly inside the slab, in proportion for one cut by its
// top).
Packing measure_packing(const ContactSample& sample, double length, double width, double floor_z,
                        std::span<const double> share = {});

// D_r = (e_max - e) / (e_max - e_min).
inline double relative_density(double e, double e_min, double e_max) {
  return (e_max - e) / (e_max - e_min);
}

}  // namespace simsols
