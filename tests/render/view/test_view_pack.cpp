// The renderer's data path (view_pack.h): beads and contact segments packed
// on the device agree with what the host computes from download() and
// contact_list(); the view origin, the reference positions and the layer
// bands do what they say; the segment buffer truncates at its capacity;
// the grain field follows the clumps, and no chain joins a clump's members.
#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <stdexcept>
#include <vector>

#include "tests/support/test_support.h"
#include "render/plot/colormap.h"
#include "render/view/frames.h"
#include "render/view/sim_view.h"
#include "render/view/view_pack.h"
#include "solver/scene/clump.h"

namespace simsols::testing {
namespace {

constexpr double kR = 1e-3;               // mean radius
constexpr double kPitch = 2.2e-3;         // lattice spacing: the largest diameter
const Vec3 kOffset{0.1, -0.05, 0.2};      // the specimen sits away from the axes (float frame)

constexpr int kSettle = 10000;            // steps

double radius_of(int i) { return kR * (0.9 + 0.1 * (i % 3)); }  // 0.9, 1.0, 1.1 mm

// 36 beads of three sizes in a 3 x 3 x 4 lattice, jittered sideways, in a
// box: a floor, three planes and one rectangle for sides. A strong gravity
// brings them onto the floor and against one another in a few milliseconds.
Scene box_scene(Precision p) {
  Scene s = empty_scene(p, soft(0.5, 0.3, 0.0));
  s.effects.gravity = {0, 0, -200};
  int i = 0;
  for (int k = 0; k < 4; ++k)
    for (int y = -1; y <= 1; ++y)
      for (int x = -1; x <= 1; ++x, ++i) {
        const double jx = 1e-4 * ((i * 7) % 5 - 2) / 2, jy = 1e-4 * ((i * 3) % 5 - 2) / 2;
        s.particles.push_back(sphere(radius_of(i),
                                     {kOffset[0] + x * kPitch + jx, kOffset[1] + y * kPitch + jy,
                                      kOffset[2] + 1.1e-3 + k * kPitch}));
      }
  const double side = 1.5 * kPitch + 2e-5;
  auto at = [](double x, double y, double z) {
    return Vec3{kOffset[0] + x, kOffset[1] + y, kOffset[2] + z};
  };
  s.walls = {plane("floor", at(0, 0, 0), {0, 0, 1}), plane("left", at(-side, 0, 0), {1, 0, 0}),
             plane("front", at(0, -side, 0), {0, 1, 0}), plane("back", at(0, side, 0), {0, -1, 0})};
  Wall right;
  right.name = "right";
  right.shape = WallShape::Rectangle;
  right.point = at(side, 0, 5e-3);
  right.normal = {-1, 0, 0};
  right.axis_u = {0, 0, 1};
  right.half_u = 6e-3;
  right.half_v = 6e-3;
  s.walls.push_back(right);
  return s;
}

// 8 beads in a cube, edges slightly overlapping, no walls, drifting.
Scene cluster_scene(Precision p) {
  Scene s = empty_scene(p, soft(0.5, 0.3, 0.0));
  const double a = 2 * kR * 0.999;
  for (int i = 0; i < 8; ++i)
    s.particles.push_back(sphere(kR, {kOffset[0] + a * (i & 1), kOffset[1] + a * ((i >> 1) & 1),
                                      kOffset[2] + a * ((i >> 2) & 1)},
                                 {0.01, 0.002 * i, 0}, {0, 0, 3.0 * i}));
  return s;
}


// The field on the host, from a snapshot, the reference positions and the bands.
std::vector<double> host_field(ColorField f, const ParticleSnapshot& p,
                               const std::vector<Vec3>& ref, double z0, double band) {
  std::vector<double> v(p.position.size());
  for (size_t i = 0; i < v.size(); ++i) {
    switch (f) {
      case ColorField::Size: v[i] = p.radius[i]; break;
      case ColorField::Layer: v[i] = std::floor((ref[i][2] - z0) / band + 0.5); break;
      case ColorField::Speed: v[i] = norm(p.velocity[i]); break;
      case ColorField::Displacement: v[i] = norm(sub(p.position[i], ref[i])); break;
      case ColorField::Contacts: v[i] = p.contacts[i]; break;
      case ColorField::Rotation: v[i] = norm(p.angular_velocity[i]); break;
      case ColorField::Grain: v[i] = double(i); break;  // no clumps: each bead its own grain
      case ColorField::NonAffine: {
        const AffineFit a = affine_fit(ref, p.position);
        Vec3 r = sub(ref[i], a.centre), fit{};
        for (int k = 0; k < 3; ++k)
          fit[k] = a.a[k][0] * r[0] + a.a[k][1] * r[1] + a.a[k][2] * r[2] + a.mean[k];
        v[i] = norm(sub(sub(p.position[i], ref[i]), fit));
        break;
      }
    }
  }
  return v;
}

void expect_positions(const ViewPacker::HostBeads& b, const ParticleSnapshot& p, const Vec3& origin) {
  ASSERT_EQ(b.xyzr.size(), 4 * p.position.size());
  for (size_t i = 0; i < p.position.size(); ++i) {
    for (int a = 0; a < 3; ++a) {
      const double want = p.position[i][a] - origin[a];
      EXPECT_NEAR(b.xyzr[4 * i + a], want, 2e-9 + 1e-6 * std::fabs(want)) << "bead " << i;
    }
    EXPECT_EQ(b.xyzr[4 * i + 3], static_cast<float>(p.radius[i])) << "bead " << i;
  }
}

void expect_values(const ViewPacker::HostBeads& b, const std::vector<double>& want,
                   ColorField f) {
  ASSERT_EQ(b.values.size(), want.size());
  double scale = 0;
  for (double w : want) scale = std::max(scale, std::fabs(w));
  float lo = b.values[0], hi = b.values[0];
  for (size_t i = 0; i < want.size(); ++i) {
    EXPECT_NEAR(b.values[i], want[i], 1e-5 * std::fabs(want[i]) + 1e-7 * scale + 1e-30)
        << to_string(f) << ", bead " << i;
    lo = std::min(lo, b.values[i]);
    hi = std::max(hi, b.values[i]);
  }
  EXPECT_EQ(b.range.min, lo) << to_string(f);
  EXPECT_EQ(b.range.max, hi) << to_string(f);
}

// A contact as the renderer should see it, computed on the host.
struct HostSegment {
  Vec3 a, b;
  double fn = 0;
  bool wall = false;
};

std::vector<HostSegment> host_segments(Simulation& sim, const Vec3& origin, bool walls) {
  const ParticleSnapshot p = sim.snapshot();
  const std::vector<Vec3> wp = wall_points(sim.model(), sim.state());
  std::vector<HostSegment> out;
  for (const ContactForce& c : contact_list(sim.model(), sim.state())) {
    HostSegment s;
    const Vec3& x = p.position[c.a];
    s.a = sub(x, origin);
    Vec3 d;
    if (c.b >= 0) {
      d = sub(p.position[c.b], x);
      s.b = sub(p.position[c.b], origin);
    } else {
      if (!walls) continue;
      const Wall& w = sim.scene().walls[-1 - c.b];
      const Vec3 to = sub(wp[-1 - c.b], x);  // centre -> wall reference point
      if (w.shape == WallShape::Plane) {
        const double s_n = dot(to, w.normal);
        for (int k = 0; k < 3; ++k) d[k] = s_n * w.normal[k];
      } else {
        const Vec3& n = w.normal;
        const Vec3& au = w.axis_u;
        const Vec3 av{n[1] * au[2] - n[2] * au[1], n[2] * au[0] - n[0] * au[2],
                      n[0] * au[1] - n[1] * au[0]};
        const double u = std::clamp(-dot(to, au), -w.half_u, w.half_u);
        const double v = std::clamp(-dot(to, av), -w.half_v, w.half_v);
        for (int k = 0; k < 3; ++k) d[k] = to[k] + u * au[k] + v * av[k];
      }
      // the contact point lies on the sphere, up to the (tiny) overlap and the
      // last step's drift: the list is of the forces' step, the positions one
      // step on (a bead leaving a wall with its force already at zero is 1e-9 m
      // past it)
      EXPECT_LE(norm(d), p.radius[c.a] * (1 + 1e-9) + norm(p.velocity[c.a]) * sim.dt());
      EXPECT_GT(norm(d), p.radius[c.a] * (1 - 1e-2));
      s.b = {x[0] + d[0] - origin[0], x[1] + d[1] - origin[1], x[2] + d[2] - origin[2]};
      s.wall = true;
    }
    s.fn = std::fabs(dot(c.force, d)) / norm(d);
    out.push_back(s);
  }
  return out;
}

struct Stats {
  double mean = 0, max = 0;
};
Stats stats_of(const std::vector<HostSegment>& h) {
  Stats s;
  for (const HostSegment& c : h) {
    s.mean += c.fn;
    s.max = std::max(s.max, c.fn);
  }
  if (!h.empty()) s.mean /= double(h.size());
  return s;
}

// Every device segment is one host contact (matched once, by its end points),
// with the same normal force. Returns how many were matched.
size_t match_segments(const std::vector<float>& seg, size_t count,
                      const std::vector<HostSegment>& host) {
  const Stats st = stats_of(host);
  std::vector<bool> used(host.size(), false);
  size_t matched = 0;
  for (size_t s = 0; s < count; ++s) {
    const float* q = &seg[8 * s];
    EXPECT_TRUE(q[7] == 0.0f || q[7] == 1.0f) << "segment " << s << ": kind " << q[7];
    size_t best = host.size();
    double best_err = 1e300;
    for (size_t h = 0; h < host.size(); ++h) {
      if (used[h]) continue;
      double err = 0;
      for (int k = 0; k < 3; ++k)
        err = std::max({err, std::fabs(q[k] - host[h].a[k]), std::fabs(q[4 + k] - host[h].b[k])});
      if (err < best_err) {
        best_err = err;
        best = h;
      }
    }
    EXPECT_LT(best_err, 1e-8) << "segment " << s << " matches no contact";
    if (best == host.size() || best_err >= 1e-8) continue;
    used[best] = true;
    ++matched;
    EXPECT_NEAR(q[3], host[best].fn, 1e-4 * host[best].fn + 1e-6 * st.max)
        << "segment " << s << (host[best].wall ? " (wall)" : " (pair)");
    EXPECT_EQ(q[7], host[best].wall ? 1.0f : 0.0f) << "segment " << s << ": its kind";
  }
  return matched;
}

void expect_stats(const ViewPacker::ContactStats& got, const std::vector<HostSegment>& host) {
  const Stats st = stats_of(host);
  EXPECT_EQ(got.total, host.size());
  EXPECT_NEAR(got.mean_force, st.mean, 1e-4 * st.mean);
  EXPECT_NEAR(got.max_force, st.max, 1e-4 * st.max);
}

std::vector<Vec3> scene_positions(const Scene& s) {
  std::vector<Vec3> p;
  for (const Particle& q : s.particles) p.push_back(q.position);
  return p;
}

class ViewPack : public PrecisionTest {};

TEST(ViewPackNames, FieldsRoundTripWithUnits) {
  for (ColorField f : kColorFields) EXPECT_EQ(parse_color_field(to_string(f)), f);
  EXPECT_EQ(parse_color_field("Speed"), ColorField::Speed);
  EXPECT_FALSE(parse_color_field("velocity"));
  EXPECT_FALSE(parse_color_field(""));
  EXPECT_STREQ(unit_of(ColorField::Size), "m");
  EXPECT_STREQ(unit_of(ColorField::Layer), "");
  EXPECT_STREQ(unit_of(ColorField::Speed), "m/s");
  EXPECT_STREQ(unit_of(ColorField::Displacement), "m");
  EXPECT_STREQ(unit_of(ColorField::Contacts), "");
  EXPECT_STREQ(unit_of(ColorField::Rotation), "rad/s");
  EXPECT_STREQ(unit_of(ColorField::Grain), "");
  EXPECT_STREQ(unit_of(ColorField::NonAffine), "m");
  EXPECT_EQ(parse_color_field("nonaffine"), ColorField::NonAffine);
  EXPECT_EQ(parse_color_field("Grain"), ColorField::Grain);
}

TEST_P(ViewPack, SettledBoxBeadsContactsOriginAndBands) {
  const Scene scene = box_scene(GetParam());
  Simulation sim(default_device(), scene);
  sim.advance(kSettle);
  std::printf("[measure] dt %.3g s\n", sim.dt());
  ViewPacker view(sim);
  const auto t0 = std::chrono::steady_clock::now();
  view.build();
  std::printf("[measure] %s: packing program built in %.2f s\n", precision_name(GetParam()),
              std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
  const ParticleSnapshot p = sim.snapshot();
  const std::vector<Vec3> initial = scene_positions(scene);

  // Defaults: origin at the centre of the initial packing, bands from the
  // lowest initial centre, one mean diameter high.
  const Vec3 centre{kOffset[0], kOffset[1], kOffset[2] + 1.1e-3 + 1.5 * kPitch};
  for (int a = 0; a < 3; ++a) EXPECT_NEAR(view.origin()[a], centre[a], 1e-12);
  EXPECT_DOUBLE_EQ(view.layer_z0(), kOffset[2] + 1.1e-3);
  EXPECT_NEAR(view.layer_band(), 2 * kR, 1e-15);

  // Every field against the host.
  for (ColorField f : kColorFields) {
    const ViewPacker::HostBeads b = view.pack_beads_host(f);
    expect_positions(b, p, view.origin());
    expect_values(b, host_field(f, p, initial, view.layer_z0(), view.layer_band()), f);
  }
  const ViewPacker::HostBeads contacts = view.pack_beads_host(ColorField::Contacts);
  EXPECT_GT(contacts.range.max, 2) << "the pile has settled into contacts";
  EXPECT_GT(view.pack_beads_host(ColorField::Displacement).range.min, 0);

  // Contacts: the same set as contact_list(), walls included or not.
  const std::vector<HostSegment> all = host_segments(sim, view.origin(), true);
  const std::vector<HostSegment> pairs = host_segments(sim, view.origin(), false);
  const size_t wall_contacts = all.size() - pairs.size();
  std::printf("[measure] %s: %zu contacts, %zu with walls\n", precision_name(GetParam()),
              all.size(), wall_contacts);
  ASSERT_GT(pairs.size(), 30u);
  ASSERT_GT(wall_contacts, 9u);  // at least the floor under the bottom layer
  {
    const ViewPacker::HostContacts c = view.pack_contacts_host(1000);
    EXPECT_EQ(c.stats.count, all.size());
    expect_stats(c.stats, all);
    EXPECT_EQ(match_segments(c.segments, c.stats.count, all), all.size());
  }
  {
    const ViewPacker::HostContacts c = view.pack_contacts_host(1000, false);
    EXPECT_EQ(c.stats.count, pairs.size());
    expect_stats(c.stats, pairs);
    EXPECT_EQ(match_segments(c.segments, c.stats.count, pairs), pairs.size());
  }
  {  // again: the same statistics bit for bit, the same segments in some order
    const ViewPacker::HostContacts c1 = view.pack_contacts_host(1000);
    const ViewPacker::HostContacts c2 = view.pack_contacts_host(1000);
    EXPECT_EQ(c1.stats.total, c2.stats.total);
    EXPECT_EQ(c1.stats.mean_force, c2.stats.mean_force);
    EXPECT_EQ(c1.stats.max_force, c2.stats.max_force);
    auto sorted = [](const std::vector<float>& seg) {
      std::vector<std::vector<float>> rows;
      for (size_t i = 0; i + 8 <= seg.size(); i += 8) rows.emplace_back(&seg[i], &seg[i] + 8);
      std::sort(rows.begin(), rows.end());
      return rows;
    };
    EXPECT_EQ(sorted(c1.segments), sorted(c2.segments));
  }
  {  // truncated: half the segments written, all counted
    const size_t cap = all.size() / 2;
    const ViewPacker::HostContacts c = view.pack_contacts_host(cap);
    EXPECT_EQ(c.stats.count, cap);
    EXPECT_LT(c.stats.count, c.stats.total);
    expect_stats(c.stats, all);
    EXPECT_EQ(match_segments(c.segments, c.stats.count, all), cap);
  }

  // Shifting the origin shifts beads and segments.
  const Vec3 moved{view.origin()[0] + 1e-3, view.origin()[1] - 2e-3, view.origin()[2] + 5e-4};
  view.set_origin(moved);
  EXPECT_EQ(view.origin(), moved);
  expect_positions(view.pack_beads_host(ColorField::Size), p, moved);
  {
    const std::vector<HostSegment> shifted = host_segments(sim, moved, true);
    const ViewPacker::HostContacts c = view.pack_contacts_host(1000);
    EXPECT_EQ(match_segments(c.segments, c.stats.count, shifted), shifted.size());
  }

  // Layer bands of the lattice: four layers of nine.
  view.set_layer_bands(kOffset[2] + 1.1e-3, kPitch);
  const ViewPacker::HostBeads layers = view.pack_beads_host(ColorField::Layer);
  expect_values(layers, host_field(ColorField::Layer, p, initial, kOffset[2] + 1.1e-3, kPitch),
                ColorField::Layer);
  EXPECT_EQ(layers.range.min, 0);
  EXPECT_EQ(layers.range.max, 3);
  for (int k = 0; k < 4; ++k)
    EXPECT_EQ(std::count(layers.values.begin(), layers.values.end(), float(k)), 9) << k;
}

// A cap that has tilted (Wall::tilts): the segments of its contacts end on
// the plate as it stands, a contact's overlap from each sphere's surface
// (where the untilted plate would put them about 1 mm off for the smaller).
TEST_P(ViewPack, WallSegmentsEndOnATiltedCap) {
  Simulation sim(default_device(), testing::tilting_cap_scene(GetParam(), 5e-3, 4e-3, true));
  sim.advance(60000);
  ASSERT_LT(sim.wall_tilt(1).angle, -0.09);
  ViewPacker view(sim);
  const ViewPacker::HostContacts c = view.pack_contacts_host(64);
  const ParticleSnapshot p = sim.snapshot();
  int on_cap = 0;
  for (size_t k = 0; k < c.stats.count; ++k) {
    const float* s = &c.segments[8 * k];
    if (s[7] != 1.0f || s[6] + view.origin()[2] < 5e-3) continue;  // the cap's, not the floor's
    const Vec3 a{s[0] + view.origin()[0], s[1] + view.origin()[1], s[2] + view.origin()[2]};
    const Vec3 b{s[4] + view.origin()[0], s[5] + view.origin()[1], s[6] + view.origin()[2]};
    const size_t i = a[0] < 0 ? 0 : 1;
    EXPECT_NEAR(norm(sub(b, a)), p.radius[i], 1e-4) << "sphere " << i;  // overlap 7e-6 m
    ++on_cap;
  }
  EXPECT_EQ(on_cap, 2);
}

TEST_P(ViewPack, ReferenceFollowsTheStateOrTheCaller) {
  const Scene scene = cluster_scene(GetParam());
  Simulation sim(default_device(), scene);
  EXPECT_FALSE(sim.model().config().walls);
  sim.advance(1);
  ViewPacker view(sim);

  // Without walls (HAS_WALLS compiled out): the 12 edges of the cube touch.
  const std::vector<HostSegment> host = host_segments(sim, view.origin(), true);
  ASSERT_EQ(host.size(), 12u);
  const ViewPacker::HostContacts c = view.pack_contacts_host(64);
  EXPECT_EQ(c.stats.count, 12u);
  expect_stats(c.stats, host);
  EXPECT_EQ(match_segments(c.segments, c.stats.count, host), 12u);

  // The current state as reference: the drift since then, and the layers
  // of the reference (z0 follows its lowest centre).
  view.set_reference();
  const ParticleSnapshot before = sim.snapshot();
  sim.advance(300);
  const ParticleSnapshot after = sim.snapshot();
  const ViewPacker::HostBeads d = view.pack_beads_host(ColorField::Displacement);
  expect_values(d, host_field(ColorField::Displacement, after, before.position, 0, 1),
                ColorField::Displacement);
  EXPECT_GT(d.range.min, 0.01 * sim.time() * 0.5) << "every bead drifted";
  double zmin = 1e300;
  for (const Vec3& x : before.position) zmin = std::min(zmin, x[2]);
  EXPECT_EQ(view.layer_z0(), zmin);
  expect_values(view.pack_beads_host(ColorField::Layer),
                host_field(ColorField::Layer, after, before.position, zmin, 2 * kR),
                ColorField::Layer);

  // Given positions: every bead 0.5 mm from its reference.
  std::vector<Vec3> ref = after.position;
  for (Vec3& x : ref) {
    x[0] += 3e-4;
    x[2] += 4e-4;
  }
  view.set_reference(ref);
  const ViewPacker::HostBeads g = view.pack_beads_host(ColorField::Displacement);
  for (float v : g.values) EXPECT_NEAR(v, 5e-4, 5e-9);
  expect_values(view.pack_beads_host(ColorField::Speed),
                host_field(ColorField::Speed, after, ref, 0, 1), ColorField::Speed);
  expect_values(view.pack_beads_host(ColorField::Rotation),
                host_field(ColorField::Rotation, after, ref, 0, 1), ColorField::Rotation);
}

// The affine fit recovers an affine displacement field exactly, from points
// in a plane too (a pseudo-inverse), and refuses lists that do not pair.
TEST(ViewPackNames, AffineFitRecoversAnAffineField) {
  const double g[3][3] = {{0.01, 0.02, 0}, {0, -0.01, 0.03}, {0.005, 0, 0.02}};
  for (const bool plane : {false, true}) {
    std::vector<Vec3> ref, cur;
    for (int i = 0; i < 20; ++i) {
      const Vec3 x{1e-3 * std::sin(1.3 * i), 2e-3 * std::cos(0.7 * i), plane ? 0.0 : 1e-3 * (i % 5)};
      Vec3 u{};
      for (int k = 0; k < 3; ++k) u[k] = g[k][0] * x[0] + g[k][1] * x[1] + g[k][2] * x[2] + 1e-4 * k;
      ref.push_back(x);
      cur.push_back({x[0] + u[0], x[1] + u[1], x[2] + u[2]});
    }
    const AffineFit f = affine_fit(ref, cur);
    for (size_t i = 0; i < ref.size(); ++i)
      for (int k = 0; k < 3; ++k) {
        const Vec3 r = sub(ref[i], f.centre);
        const double fit = f.a[k][0] * r[0] + f.a[k][1] * r[1] + f.a[k][2] * r[2] + f.mean[k];
        EXPECT_NEAR(fit, cur[i][k] - ref[i][k], 1e-15) << (plane ? "plane, " : "") << "point " << i;
      }
    if (!plane) {
      EXPECT_NEAR(f.a[1][2], 0.03, 1e-12);
    }
  }
  EXPECT_THROW(affine_fit({{0, 0, 0}}, {}), std::invalid_argument);
  EXPECT_THROW(affine_fit({}, {}), std::invalid_argument);
}

// NonAffine: beads whose reference is an affine image of where they are
// now show nothing, however far they moved; one bead's reference moved
// 0.2 mm more stands out, as the host computes it.
TEST_P(ViewPack, NonAffineShowsWhatTheBestAffineFieldLeaves) {
  Simulation sim(default_device(), cluster_scene(GetParam()));
  sim.advance(1);
  ViewPacker view(sim);
  const ParticleSnapshot now = sim.snapshot();
  std::vector<Vec3> ref;
  for (const Vec3& x : now.position)
    ref.push_back({x[0] + 0.02 * (x[0] - kOffset[0]) + 0.03 * (x[2] - kOffset[2]) + 1e-4,
                   x[1] - 0.01 * (x[1] - kOffset[1]) - 2e-4, x[2] + 0.015 * (x[0] - kOffset[0])});
  view.set_reference(ref);
  const ViewPacker::HostBeads affine = view.pack_beads_host(ColorField::NonAffine);
  EXPECT_GT(view.pack_beads_host(ColorField::Displacement).range.min, 1e-4);
  EXPECT_LT(affine.range.max, 1e-8) << "an affine field leaves nothing";
  ref[3][0] += 2e-4;
  view.set_reference(ref);
  const ViewPacker::HostBeads one = view.pack_beads_host(ColorField::NonAffine);
  expect_values(one, host_field(ColorField::NonAffine, now, ref, 0, 1), ColorField::NonAffine);
  EXPECT_EQ(one.range.max, one.values[3]) << "the bead moved on its own stands out";
  // (8 beads: the fit's 12 parameters take up about half of the 0.2 mm)
  EXPECT_GT(one.values[3], 5e-5);
}

TEST_P(ViewPack, BadArgumentsAreRefused) {
  Simulation sim(default_device(), cluster_scene(GetParam()));
  ViewPacker view(sim);
  Device& dev = sim.model().device();
  const ClMem small = dev.alloc(16);
  const ClMem big = dev.alloc(8 * 16), big2 = dev.alloc(8 * 16);
  EXPECT_THROW(view.pack_contacts(big.get(), 0), std::invalid_argument);
  EXPECT_THROW(view.pack_contacts(small.get(), 2), std::invalid_argument);
  EXPECT_THROW(view.pack_contacts(nullptr, 1), std::invalid_argument);
  EXPECT_THROW(view.pack_contacts_host(0), std::invalid_argument);
  EXPECT_THROW(view.pack_beads(ColorField::Size, small.get(), big.get()), std::invalid_argument);
  EXPECT_THROW(view.pack_beads(ColorField::Size, big.get(), small.get()), std::invalid_argument);
  EXPECT_THROW(view.set_reference(std::vector<Vec3>(3)), std::invalid_argument);
  EXPECT_THROW(view.set_layer_bands(0, 0), std::invalid_argument);
  EXPECT_THROW(view.set_origin({0, NAN, 0}), std::invalid_argument);
  // Before any step nothing touches yet; packing still works.
  EXPECT_EQ(view.pack_contacts(big.get(), 4).total, 0u);
  const ViewPacker::Range r = view.pack_beads(ColorField::Size, big.get(), big2.get());
  EXPECT_FLOAT_EQ(r.min, float(kR));
  EXPECT_FLOAT_EQ(r.max, float(kR));
}

// Three "peanut" clumps of two overlapping spheres (along x) in a row along
// y, each touching the next with both spheres, between two free spheres
// that touch a first sphere at the row's ends: particle 0 free, 1-2 clump
// 0, 3-4 clump 1, 5-6 clump 2, 7 free. No gravity: the overlaps push the
// grains apart.
constexpr double kPeanutGap = 0.99 * 2 * kR;  // centre rows: touching, 1 % overlap
Scene peanut_row(Precision p) {
  Scene s = empty_scene(p, soft(0.5, 0.3, 0.0));
  s.grains.push_back({"peanut", {{-0.6 * kR, 0, 0, kR}, {0.6 * kR, 0, 0, kR}}, ""});
  const GrainBody body = grain_body(s.grains[0]);
  auto at = [](double x, double y) { return Vec3{kOffset[0] + x, kOffset[1] + y, kOffset[2]}; };
  s.particles.push_back(sphere(kR, at(-0.6 * kR, -kPeanutGap)));  // beside a clump's first sphere
  for (int c = 0; c < 3; ++c) {
    Clump k;
    k.position = at(0, c * kPeanutGap);
    add_clump(s, k, body);
  }
  s.particles.push_back(sphere(kR, at(-0.6 * kR, 3 * kPeanutGap)));
  return s;
}

// The grain field: members of a clump share their clump's number, free
// spheres count on after the clumps; each grain's colour is the same on
// all its members and differs from the other grains' here.
TEST_P(ViewPack, GrainNumbersAndColoursFollowTheClumps) {
  const Scene scene = peanut_row(GetParam());
  ASSERT_EQ(scene.particles.size(), 8u);
  ASSERT_EQ(scene.clumps.size(), 3u);
  EXPECT_EQ(default_color_field(scene), ColorField::Grain);
  Simulation sim(default_device(), scene);
  sim.advance(20);
  ViewPacker view(sim);
  const ViewPacker::HostBeads b = view.pack_beads_host(ColorField::Grain);
  const std::vector<float> want{3, 0, 0, 1, 1, 2, 2, 10};  // C + i for the free spheres
  ASSERT_EQ(b.values.size(), want.size());
  for (size_t i = 0; i < want.size(); ++i) EXPECT_EQ(b.values[i], want[i]) << "bead " << i;
  EXPECT_EQ(b.range.min, 0);
  EXPECT_EQ(b.range.max, 10);
  expect_positions(b, sim.snapshot(), view.origin());

  // The colours the renderer gives them (render/plot/colormap.h).
  const plot::ColorMap map = render::colormap_for(ColorField::Grain);
  EXPECT_EQ(map, plot::ColorMap::Qualitative);
  auto colour = [&](size_t i) { return plot::colormap_color(map, b.values[i]); };
  for (size_t i : {1, 3, 5}) EXPECT_EQ(colour(i), colour(i + 1)) << "clump of bead " << i;
  const size_t one_per_grain[] = {0, 1, 3, 5, 7};
  for (size_t a : one_per_grain)
    for (size_t c : one_per_grain)
      EXPECT_TRUE(a >= c || !(colour(a) == colour(c))) << "beads " << a << " and " << c;
}

// The force chains join grains, never two members of one clump (their
// spheres overlap, but a clump's members are not each other's neighbours).
TEST_P(ViewPack, ChainsJoinGrainsNotTheMembersOfAClump) {
  const Scene scene = peanut_row(GetParam());
  Simulation sim(default_device(), scene);
  sim.advance(1);
  ViewPacker view(sim);
  const ParticleSnapshot p = sim.snapshot();
  auto nearest = [&](const float* q) {
    size_t best = 0;
    double best_d = 1e300;
    for (size_t i = 0; i < p.position.size(); ++i) {
      double d = 0;
      for (int a = 0; a < 3; ++a) d += std::pow(q[a] - (p.position[i][a] - view.origin()[a]), 2);
      if (d < best_d) best_d = d, best = i;
    }
    EXPECT_LT(std::sqrt(best_d), 1e-8);
    return best;
  };
  const ViewPacker::HostContacts c = view.pack_contacts_host(64);
  // free-clump 0, clump 0-1 (both spheres), 1-2 (both), clump 2-free
  EXPECT_EQ(c.stats.total, 6u);
  for (size_t k = 0; k < c.stats.count; ++k) {
    const size_t i = nearest(&c.segments[8 * k]), j = nearest(&c.segments[8 * k + 4]);
    const int ci = scene.particles[i].clump, cj = scene.particles[j].clump;
    EXPECT_TRUE(ci < 0 || ci != cj) << "segment " << k << " joins beads " << i << " and " << j
                                    << " of clump " << ci;
  }
}

// Frames (snapshot, run --frames) of a scene with clumps are coloured by
// grain unless the flag or the scene's [view] says otherwise; other scenes
// by layer.
TEST(ViewPackNames, FramesOfClumpsDefaultToGrain) {
  const FrameFlags none;
  EXPECT_EQ(FrameOptions::resolve(none).field, ColorField::Layer);
  Scene clumps = peanut_row(Precision::Float);
  const FrameOptions o = FrameOptions::resolve(none, &clumps);
  EXPECT_EQ(o.field, ColorField::Grain);
  EXPECT_EQ(o.settings.bead_map, plot::ColorMap::Qualitative);
  const Scene spheres = cluster_scene(Precision::Float);
  EXPECT_EQ(FrameOptions::resolve(none, &spheres).field, ColorField::Layer);
  clumps.view.color_by = "speed";
  EXPECT_EQ(FrameOptions::resolve(none, &clumps).field, ColorField::Speed);
  FrameFlags grain;
  grain.color_by = "grain";
  EXPECT_EQ(FrameOptions::resolve(grain, &spheres).field, ColorField::Grain);
}

// Without clumps each bead is its own grain, numbered by its index, and a
// scene is drawn by layer unless asked otherwise.
TEST_P(ViewPack, GrainWithoutClumpsIsTheBead) {
  const Scene scene = cluster_scene(GetParam());
  EXPECT_EQ(default_color_field(scene), ColorField::Layer);
  Simulation sim(default_device(), scene);
  ViewPacker view(sim);
  const ViewPacker::HostBeads b = view.pack_beads_host(ColorField::Grain);
  for (size_t i = 0; i < b.values.size(); ++i) EXPECT_EQ(b.values[i], float(i));
  EXPECT_EQ(b.range.max, float(b.values.size() - 1));
}

SIMSOLS_BOTH_PRECISIONS(ViewPack);

}  // namespace
}  // namespace simsols::testing
