// membrane.cl — stage: membrane forces (membrane_forces, after contact_forces,
// before finish_particles), and the part of finish_particles that applies
// them (membrane_one, integrate.cl).
//
// A membrane (scene.h, Membrane) is a lattice of beads wrapped about the z
// axis: rows of `cols` beads, each row a closed ring, counter-clockwise
// seen from above. Bead (r, c) is particle first + r cols + c. Beads of one
// membrane never touch each other (HAS_GROUPS, neighbors.cl); they touch the
// specimen through the contact law like any other bead.
//
// Each bead, forces from its four neighbours (three in the first and last
// rows) and the cell pressure p acting on the outside:
//   bond to a neighbour at distance l along u:  k (l - l0) u + c (dv . u) u,
//     in tension and compression (the compression shell of laboratory
//     membrane corrections); k and l0 per direction (hoop, axial). Bonds
//     that only pulled let the rings of a frictionless membrane slide
//     together
//   pressure:  -p (t_c x t_r) / 4,  t_c = x(r, c+1) - x(r, c-1),
//     t_r = x(r+1, c) - x(r-1, c) (one-sided in the end rows, whose share
//     is half a strip): the outward normal times the bead's share of the
//     surface (central differences span two spacings each),
//     that share capped at twice its share at rest, l0_hoop l0_axial: a
//     bead pushed into a hole between grains spreads its neighbours, and
//     an uncapped share would push it on the harder the further it goes.
//     Where the lattice folds over (t_c x t_r points towards the axis) the
//     pressure acts horizontally towards the axis instead: a fold would
//     otherwise push outwards and turn the membrane inside out (measured
//     on a frictionless membrane about 150 grains, before this rule).
// For the square lattice of spacings s_c (hoop) and s_r (axial) that
// represents a sheet of E t (N/m): k_hoop = E t s_r / s_c, k_axial =
// E t s_c / s_r, a Poisson ratio of 0 (triaxial_programme.cpp sets them).
// A ring of radius R then balances p when k (l - l0) = p R s_r cos(pi/cols),
// l = 2 R sin(pi/cols): Laplace's T = p R on the polygon
// (tests/solver/core/test_membrane.cpp).
//
// Held: every bead while the membrane is held; the height of the first and
// last rows (sealed to the floor and the platen) always, while they move
// freely across. finish_particles replaces the held part of their force
// by the one that brings their velocity to the target in this step (0, or
// the platen's for the last row), and every bead's torque by the one that
// stops its spin: a membrane does not roll on the grains it wraps.
//
// Record `membrane` (MEMBRANE_RECORD real4, State::membrane):
//   [0] p (Pa, positive inwards), held (1/0), k_hoop, k_axial (N/m)
//   [1] l0_hoop, l0_axial (m), c_hoop, c_axial (N s/m)
//   [2] first, rows, cols, the platen wall (-1: the last row is held still)
//   [3] the axis it is wrapped about (x, y; m, relative to the origin), 0, 0

#ifdef HAS_MEMBRANE
#define MEMBRANE_RECORD 4

INLINE int membrane_bead(int first, int cols, int r, int c) {
  return first + r * cols + (c + cols) % cols;
}

// The pull on bead a of its bond to bead b (see above).
INLINE real3 bond_pull(int a, int b, __global const real4* pos POS_LO_CARG_FN,
                       __global const real4* vel, real k, real c, real rest) {
  const real3 d = rel_pos(pos[a], pos[b] LO(a) LO(b));
  const real len = length(d);
  const real3 u = d / len;
  return u * (k * (len - rest) + c * dot(vel[b].xyz - vel[a].xyz, u));
}

__kernel void membrane_forces(__global const real4* pos POS_LO_CARG, __global const real4* vel,
                              __global const real4* membrane, __global real4* membrane_force) {
  const real4 m0 = membrane[0], m1 = membrane[1], m2 = membrane[2], m3 = membrane[3];
  const int first = (int)m2.x, rows = (int)m2.y, cols = (int)m2.z;
  const int k = get_global_id(0);
  if (k >= rows * cols) return;
  const int r = k / cols, c = k % cols;
  real3 f = (real3)(0, 0, 0);
  if (m0.y == 0) {
    const int i = first + k;
    const int left = membrane_bead(first, cols, r, c - 1), right = membrane_bead(first, cols, r, c + 1);
    // an end row's missing neighbour is the bead itself: no bond, half a strip
    const int down = r > 0 ? membrane_bead(first, cols, r - 1, c) : i;
    const int up = r < rows - 1 ? membrane_bead(first, cols, r + 1, c) : i;
    f += bond_pull(i, left, pos POS_LO_PASS, vel, m0.z, m1.z, m1.x);
    f += bond_pull(i, right, pos POS_LO_PASS, vel, m0.z, m1.z, m1.x);
    if (down != i) f += bond_pull(i, down, pos POS_LO_PASS, vel, m0.w, m1.w, m1.y);
    if (up != i) f += bond_pull(i, up, pos POS_LO_PASS, vel, m0.w, m1.w, m1.y);
    const real3 tc = rel_pos(pos[left], pos[right] LO(left) LO(right));
    const real3 tr = rel_pos(pos[down], pos[up] LO(down) LO(up));
    const real3 share = cross(tc, tr) / 4;
    const real most = (down != i && up != i ? 2 : 1) * m1.x * m1.y;  // twice its share at rest
    const real a = length(share);
    // where the lattice folds over, the pressure still pushes towards the axis
    const real4 x = pos[i];
    const real3 out = (real3)(x.x - m3.x, x.y - m3.y, 0);
    const real3 n = dot(share, out) > 0 ? share / a : out / length(out);
    f -= n * (m0.x * min(a, most));
  }
  membrane_force[k] = (real4)(f, 0);
}

// Particle i's membrane force, or its hold (see above); nothing for a
// particle that is not a membrane bead. After its contacts, before it moves.
INLINE void membrane_one(int i, __global const real4* membrane,
                         __global const real4* membrane_force, __global const real4* pos,
                         __global const real4* vel, __global const real4* omega,
                         __global real4* force, __global real4* torque,
                         __global const real4* wall_vel, real4 gravity, real dt) {
  const real4 m0 = membrane[0], m2 = membrane[2];
  const int k = i - (int)m2.x, rows = (int)m2.y, cols = (int)m2.z;
  if (k < 0 || k >= rows * cols) return;
  const real4 v = vel[i];
  const real inertia = (real)0.4 * v.w * pos[i].w * pos[i].w;
  real4 t = torque[i];
  t.xyz = -omega[i].xyz * (inertia / dt);
  torque[i] = t;
  const int r = k / cols;
  real4 fi = force[i];
  // the force that brings the velocity to `target` in this step
  real3 target = (real3)(0, 0, 0);
  const int platen = (int)m2.w;
  if (m0.y == 0 && r == rows - 1 && platen >= 0) target = wall_vel[platen].xyz;
  real3 a = (target - v.xyz) / dt;
#ifdef HAS_GRAVITY
  a -= gravity.xyz;
#endif
  if (m0.y != 0) {
    fi.xyz = a * v.w;  // held
  } else {
    fi.xyz += membrane_force[k].xyz;
    if (r == 0 || r == rows - 1) fi.z = a.z * v.w;  // sealed: its height follows the plate
  }
  force[i] = fi;
}
#endif
