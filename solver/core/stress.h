// Stress from contact forces: the Love-Weber average.
//
// For a region of volume V the mean stress carried by the contacts is
//   sigma_ab = -(1/V) sum_c f_a l_b        (compression positive)
// with f the force on bead a from its partner and l the branch vector from
// a's centre to the partner's centre (bead pairs) or to the contact point
// (bead-wall contacts; the wall's closest point). Over a horizontal slab
// z in [z_lo, z_hi] each branch vector counts with the fraction of its
// length inside the slab, so the slab average equals the mean over its
// horizontal planes of the force per area transmitted across each plane:
// a thin slab around the shear box's split plane gives the stress on the
// shear plane itself, which is what the wall forces T/A and N/A claim to
// measure. Body forces (gravity) are left out: below 1% of sigma for the
// paper's specimens under 50 kPa or more. Compare docs/shear-box.md.
//
// Rigid grains (clumps): the average is over bodies, so a branch vector
// runs between the two grains' centroids (to the contact point for a
// wall), not between the member spheres that touch. Summed over a body's
// contacts, f (x_contact - x_centroid) is the grain's share of the stress;
// the two ends of a contact add up to f (x_B - x_A). Branch vectors
// between member centres would leave out what each grain carries through
// its own body (9.8-13 % of the stress in a test of elongated grains).
#pragma once

#include <array>
#include <optional>
#include <vector>

#include "solver/core/simulation.h"

namespace simsols {

using Tensor3 = std::array<std::array<double, 3>, 3>;  // [force component][branch component]

// What the average reads from the device at one step: the beads, their
// contacts and the walls' reference points (read once when a caller also
// wants other averages of the same contacts).
struct ContactSample {
  ParticleSnapshot beads;
  std::vector<ContactForce> contacts;
  std::vector<Vec3> wall_points;
  std::vector<Wall> walls;  // the scene's walls as they stand (tilted_wall: a turned cap)
  std::vector<Vec3> body_centre;  // per bead: its grain's centroid (a free bead's own centre)
};
ContactSample sample_contacts(Simulation& sim);

// Slab z in [z_lo, z_hi], horizontal area `area` (m^2). Pa.
Tensor3 love_weber_slab(const ContactSample& sample, const std::vector<Wall>& walls, double z_lo,
                        double z_hi, double area);
Tensor3 love_weber_slab(Simulation& sim, double z_lo, double z_hi, double area);

// The beads [0, inside) of a volume (m^3) wrapped by others (a membrane's
// beads, past `inside`): a contact with an outside bead is a boundary
// force at the contact point (on the line of centres, in proportion to
// the radii), as a wall's is; contacts among outside beads do not count.
Tensor3 love_weber_inside(const ContactSample& sample, size_t inside, double volume);

// Contact c when it joins a bead inside (index < inside) and one outside:
// the inside bead, the force on it and the contact point on the line of
// centres, in proportion to the radii; nullopt for any other contact.
struct BoundaryContact {
  size_t bead = 0;
  Vec3 force{};  // N, on the inside bead
  Vec3 point{};  // m
};
std::optional<BoundaryContact> boundary_contact(const ContactSample& sample, const ContactForce& c,
                                                size_t inside);

// The sample without the beads from `inside` on and their contacts.
ContactSample beads_inside(const ContactSample& sample, size_t inside);

}  // namespace simsols
