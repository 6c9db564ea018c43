// The state of a prepared specimen, as a laboratory reports it before a
// test: how dense it is, how many contacts each grain has, how the
// contacts are oriented.
//
// Two void ratios. The bulk one is the laboratory's: all the solid over
// the volume up to the highest grain's top, where a platen laid on the
// specimen rests (e = A H / V_s - 1, as the apparatus tests report it and
// as tamping aims it). The slab one is that of a mould struck level below
// the rough top: the solid inside the slab from the floor to the highest
// top less one largest grain diameter, over the slab's volume (each bead
// counts with the spherical segment inside the slab, so the value is exact
// for any arrangement); it leaves out the loose top layer and suits a
// specimen many grains tall. Floor and side walls are inside both, as in a
// mould. A grain is a bead or a clump: the coordination counts the grains
// and walls each grain touches (several member contacts between two
// grains are one), the grain coordination the grains alone; the fabric is
// that of the sphere pairs' contact normals, phi = <n n>, with the
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
  int beads = 0;            // spheres
  int grains = 0;           // beads and clumps
  double height = 0;        // m, floor to the highest top
  double bulk_void_ratio = 0;  // e = A height / V_solid - 1
  double slab_height = 0;   // m, floor to the highest top less one largest grain diameter
  double void_ratio = 0;    // e = V_voids / V_solid in the slab
  double solid_fraction = 0;   // in the slab
  double coordination = 0;  // grains and walls touched, per grain
  double grain_coordination = 0;  // grains touched, per grain
  std::array<double, 3> fabric{};  // phi_xx, phi_yy, phi_zz over bead pairs
  double fabric_anisotropy = 0;    // (15/2)(phi_zz - (phi_xx + phi_yy)/2)
};

// The volume of the sphere (centre height z, radius r) between the
// horizontal planes lo < hi.
double sphere_volume_between(double z, double r, double lo, double hi);

// The fabric anisotropy of the bead pairs' contact normals (see above).
double fabric_anisotropy(const ContactSample& sample);

// Which grain each bead belongs to and its share of that grain's solid:
// empty for a specimen of beads. `share` scales each bead's segment: a
// clump member's share of its union's volume over its sphere's (clump.h,
// solid_volumes), so overlapping members count once (exactly for a clump
// wholly inside the slab, in proportion for one cut by its top). `grain`
// numbers the grains from 0.
struct GrainMap {
  std::vector<double> share;
  std::vector<int> grain;
};

// The packing of the beads in a cell of footprint length x width (m) with
// its floor at z = floor_z.
Packing measure_packing(const ContactSample& sample, double length, double width, double floor_z,
                        const GrainMap& grains = {});

// D_r = (e_max - e) / (e_max - e_min).
inline double relative_density(double e, double e_min, double e_max) {
  return (e_max - e) / (e_max - e_min);
}

}  // namespace simsols
