// integrate.cl — stage: finish particles (finish_particles, at the end), whose
// last part integrates each particle (integrate_one: leapfrog / kick-drift,
// second order):
//
//   v_{n+1/2} = v_{n-1/2} + (F_n / m + g) dt,   w likewise with T_n / I
//   x_{n+1}   = x_n + v_{n+1/2} dt              (compensated in float runs)
//
// Velocities in the state are the half-step ones; observables (reduce.cl)
// re-centre them to v_n.
//
// Fluid (HAS_FLUID, slot fluid = drag), per particle, no per-contact memory:
// a still or uniformly moving fluid u of density rho_f and viscosity mu_f
//   F_d = 3 pi mu_f d (u - v) f(Re),  Re = rho_f |u - v| d / mu_f,
//   f = 1 + 0.15 Re^0.687 (Re < 1000), 0.44 Re / 24 above   (Schiller-Naumann)
//   F_b = -rho_f V g                                         (buoyancy)
//   M_f = -pi mu_f d^3 (w - curl(u)/2) = -pi mu_f d^3 w       (uniform u)
// evaluated with the half-step velocities, like the contact dashpots. Also keeps the neighbour-list bookkeeping that the
// host reads every few steps (pipeline.cpp, detect_contacts): the flags
// FLAG_REBUILD, FLAG_MAX_SPEED2 and FLAG_LATE (layout.h, mark_travel in
// common.cl), and the runaway mark the Guard reads (guard.h): a particle
// whose new state is not finite, or which moved more than a tenth of its
// radius in this one step (a contact cannot be resolved: its overlap would
// jump by ten times the 1 % a resolved contact reaches), in
// FLAG_RUNAWAY_FIRST, FLAG_RUNAWAY_WHAT and FLAG_RUNAWAY_COUNT.

INLINE void integrate_one(int i, __global real4* pos, __global float4* pos_lo,
                          __global real4* vel, __global real4* omega,
                          __global const real4* force, __global const real4* torque,
                          __global const float4* pos_build, __global volatile int* flags,
                          __global int* contacts_last, __global const real* cell, real4 gravity,
                          real4 fluid, real fluid_viscosity, real dt, real skin) {
  real4 v = vel[i];
  real4 w = omega[i];
  real4 x = pos[i];
  const real m = v.w;
  const real4 fi = force[i];
  keep_contact_count(contacts_last, i, fi.w);  // the next step's rolling cap (forces.cl)
  real3 a = fi.xyz / m;
#ifdef HAS_GRAVITY
  a += gravity.xyz;
#endif
#ifdef HAS_FLUID
  const real pi = (real)3.14159265358979323846;
  const real diam = 2 * x.w;
  const real3 slip = fluid.xyz - v.xyz;
  const real re = fluid.w * length(slip) * diam / fluid_viscosity;
  // Re^0.687 as exp(0.687 ln Re): PoCL's pow() is far slower (bench --effects)
  const real re_pow = re > 0 ? exp((real)0.687 * log(re)) : (real)0;
  const real f = re < (real)1000 ? 1 + (real)0.15 * re_pow : (real)0.44 * re / 24;
  a += slip * (3 * pi * fluid_viscosity * diam * f / m);
#ifdef HAS_GRAVITY
  a -= gravity.xyz * (fluid.w * pi / 6 * diam * diam * diam / m);
#endif
  const real3 tq = torque[i].xyz - w.xyz * (pi * fluid_viscosity * diam * diam * diam);
#else
  const real3 tq = torque[i].xyz;
#endif
#ifdef HAS_PERIODIC
  a -= cell_apply(cell, CELL_GRAD, v.xyz);  // du/dt = F/m - L u (periodic.cl)
#endif
  v.xyz += a * dt;
  w.xyz += tq * (dt / ((real)0.4 * m * x.w * x.w));
#ifdef HAS_PERIODIC
  DRIFT(&x, pos_lo, i, (v.xyz + cell_apply(cell, CELL_GRAD, x.xyz - cell_corner(cell))) * dt);
#else
  DRIFT(&x, pos_lo, i, v.xyz * dt);
#endif
  vel[i] = v;
  omega[i] = w;
  pos[i] = x;
  // comparisons with NaN are false: a NaN anywhere counts as not finite
  const real3 dx = v.xyz * dt;
  const real step2 = dot(dx, dx);
  const int finite = (dot(w.xyz, w.xyz) < INFINITY) & (step2 < INFINITY) &
                     (fabs(x.x) + fabs(x.y) + fabs(x.z) < INFINITY);
  const int fast = step2 > (real)0.01 * x.w * x.w;  // a tenth of its radius
  if (!finite || fast) {
    atomic_min(&flags[FLAG_RUNAWAY_FIRST], i);
    atomic_or(&flags[FLAG_RUNAWAY_WHAT], finite ? 2 : 1);
    atomic_inc(&flags[FLAG_RUNAWAY_COUNT]);
  }
  // pos_build is float in every precision: it only measures a path against
  // the skin (~0.1 d), far above a float's rounding
#ifdef HAS_PERIODIC
  // the travel through the cell's flow: from where the flow alone would
  // have carried the particle since the build
  const real3 built = to_real3(pos_build[i].xyz);
  const real3 moved =
      x.xyz - built - cell_apply(cell, CELL_STRETCH, built - cell_corner(cell));
#else
  const real3 moved = x.xyz - to_real3(pos_build[i].xyz);
#endif
  const real moved2 = dot(moved, moved);
  mark_travel(flags, moved2, skin);
  // |v|^2 >= 0, so its float bits order like ints; only a new maximum pays
  // for the atomic (one shared word: contended if every particle wrote it)
  const int v2 = as_int((float)dot(v.xyz, v.xyz));
  if (v2 > flags[FLAG_MAX_SPEED2]) atomic_max(&flags[FLAG_MAX_SPEED2], v2);
}

// Stage: finish the particles, one launch per step for everything that is
// per particle once the pair forces are known. A work item takes the LANES
// particles of the pair stage (forces.cl) and, in this order, collects the
// shares their partners left (collect_one, forces.cl), adds their wall
// contacts (wall_contacts, walls.cl) and a membrane bead's bonds and
// pressure or its hold (membrane_one, membrane.cl), and integrates them
// (integrate_one, above). Each particle is read and written by its own work item only, so
// the three parts see each other's writes in program order, and the sums
// are those of three separate kernels, bit for bit. pos_lo and
// wall_point_lo are unused in double runs; the wall arguments without walls.
// With servo walls on CPUs (SERVO_IN_FINISH), the last work group to finish
// runs the walls' step (walls_step, walls.cl), so a step is two launches:
// after a barrier, each group's first work item counts the group out in
// `groups_done` (0 between launches), and the one that completes the count
// sees every wall force written (x86 stores are seen in order, the count is
// a locked instruction). The count has a buffer of its own, away from
// `flags`, which every particle reads: the two cores would otherwise pass
// the line between them at every count. GPUs, whose OpenCL 1.2 memory model
// promises no such thing across work groups, launch servo_walls instead.
__kernel void finish_particles(
    __global real* pos, __global float* pos_lo, __global real* vel, __global real* omega,
    __global real* force, __global real* torque, __global const float4* pos_build,
    __global volatile int* flags, __global volatile int* groups_done,
    __global int* contacts_last, __global const int* nbr_count,
    __global const int* nbr_upper, __global const uint* lo_off, __global const int* mirror,
    __global const real4* share,
    __global const real* walls, __global real* wall_point,
    __global float* wall_point_lo, __global real* wall_turn, __global real* wall_vel,
    __global const uint* wall_off, __global real* wall_spring, __global real* wall_force,
    int wall_stride, __global const real* pairs,
    __global int* wall_touch, __global const int* wall_near, __global const real* servo,
    __global real* wall_partial, __global real* wall_reaction, __global real* wall_mean,
    __global const real* body_offset, __global const real* membrane,
    __global const real* membrane_force, __global const real* cell, real4 gravity, real4 fluid,
    real fluid_viscosity, real dt, real rolling_damping, real skin,
    int stride, int n, int nwalls, int nmat, int wall_chunk, int wall_groups) {
  const int base = get_global_id(0) * LANES;
  if (base < n) {  // no early return: every work item reaches the barrier below
    const int count = min(LANES, n - base);
    for (int l = 0; l < count; ++l) {
      prefetch_shares(base + l + 2 * LANES, n, nbr_count, nbr_upper, lo_off, mirror, share);
      collect_one(base + l, nbr_count, nbr_upper, lo_off, mirror, share, (__global real4*)force,
                  (__global real4*)torque);
    }
#ifdef HAS_WALLS
    wall_contacts(base, pos POS_LO_PASS, vel, omega, walls, wall_point WALL_STATE_PASS, wall_vel,
                  wall_off, wall_spring, wall_force, wall_stride, pairs, force, torque, wall_touch,
                  wall_near, body_offset, contacts_last, dt, rolling_damping, n, nwalls, nmat);
#endif
#ifdef HAS_MEMBRANE
    for (int l = 0; l < count; ++l)
      membrane_one(base + l, (__global const real4*)membrane,
                   (__global const real4*)membrane_force, (__global const real4*)pos,
                   (__global const real4*)vel, (__global const real4*)omega,
                   (__global real4*)force, (__global real4*)torque,
                   (__global const real4*)wall_vel, gravity, dt);
#endif
    for (int l = 0; l < count; ++l)
      integrate_one(base + l, (__global real4*)pos, (__global float4*)pos_lo,
                    (__global real4*)vel, (__global real4*)omega, (__global const real4*)force,
                    (__global const real4*)torque, pos_build, flags, contacts_last, cell,
                    gravity, fluid, fluid_viscosity, dt, skin);
  }
#ifdef SERVO_IN_FINISH
  barrier(CLK_GLOBAL_MEM_FENCE);
  if (get_local_id(0) != 0) return;
  mem_fence(CLK_GLOBAL_MEM_FENCE);
  if (atomic_inc(groups_done) != (int)get_num_groups(0) - 1) return;
  *groups_done = 0;
  mem_fence(CLK_GLOBAL_MEM_FENCE);
  walls_step((__global const real4*)walls, (__global const real4*)servo, wall_near, wall_off,
             (__global const real4*)wall_force, (__global real4*)wall_partial,
             (__global real4*)wall_vel, (__global real4*)wall_reaction,
             (__global real4*)wall_mean, (__global real4*)wall_point,
             (__global float4*)wall_point_lo, (__global real4*)wall_turn,
             (__global const real4*)pos, flags, dt, skin, n, wall_chunk, wall_groups, 1, nwalls);
#endif
}
