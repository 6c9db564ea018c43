// The data path from the solver's buffers to the GL vertex buffers
// (render/view/particle_bridge.h): whichever path the device allows (host copy on
// PoCL, cl_khr_gl_sharing on a GPU that shares the GL context), the GL
// buffers hold exactly what the packing kernels produce, and the path is
// decided from the extension string without calling a sharing function on a
// device that lacks it.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>

#include "render/gl/gl_context.h"
#include "solver/core/engine_options.h"
#include "render/view/particle_bridge.h"
#include "render/view/sim_view.h"
#include "solver/core/simulation.h"
#include "tests/support/test_support.h"

using namespace simsols;
using namespace simsols::render;

namespace {

std::vector<float> read_gl(const Gl& gl, GLuint buffer, size_t floats) {
  std::vector<float> out(floats);
  gl.BindBuffer(GL_ARRAY_BUFFER, buffer);
  const void* p = gl.MapBufferRange(GL_ARRAY_BUFFER, 0, GLsizeiptr(floats * 4), GL_MAP_READ_BIT);
  EXPECT_NE(p, nullptr);
  if (p) std::memcpy(out.data(), p, floats * 4);
  gl.UnmapBuffer(GL_ARRAY_BUFFER);
  gl.BindBuffer(GL_ARRAY_BUFFER, 0);
  return out;
}

// A 4 x 3 raft of beads slightly pressed into each other and into a floor:
// contacts between them and with the wall.
Scene pile(Precision p) {
  Scene s = simsols::testing::empty_scene(p, paper_glass());
  const double r = 1e-3;
  for (int k = 0; k < 12; ++k) {
    Particle b;
    b.radius = r;
    b.position = {1.9995 * r * (k % 4), 1.9995 * r * (k / 4), 0.9998 * r};
    s.particles.push_back(b);
  }
  Wall floor;
  floor.name = "floor";
  s.walls.push_back(floor);
  s.numerics.duration = 1;
  return s;
}

}  // namespace

TEST(ParticleBridge, GlBuffersHoldWhatThePackerWrites) {
  auto ctx = create_headless_context();
  const Gl& gl = ctx->gl();
  auto device = Device::open(engine_options_from_environment(), cl_share_properties(ctx->share_handles()));
  // A device that offers cl_khr_gl_sharing must share with this context (a
  // host copy there means the GL context is not on the OpenCL device, e.g.
  // llvmpipe beside a GPU); one that does not offers the host copy and says
  // why. The GPU check (tests/gpu/check.sh) requires the shared path.
  std::printf("GL: %s\nOpenCL: %s\n", ctx->description().c_str(), device->description().c_str());
  const char* expect = std::getenv("SIMSOLS_EXPECT_GL_SHARING");
  if (expect && std::string(expect) == "1") {
    ASSERT_TRUE(device->has_extension("cl_khr_gl_sharing")) << device->sharing_note();
  }
  EXPECT_EQ(device->gl_sharing(), device->has_extension("cl_khr_gl_sharing"))
      << device->sharing_note();
  if (!device->has_extension("cl_khr_gl_sharing")) {
    EXPECT_NE(device->sharing_note().find("cl_khr_gl_sharing"), std::string::npos);
  }
  // Sharing means the platform named the GL context's device
  // (clGetGLContextInfoKHR) and Device::open took it.
  if (device->gl_sharing()) {
    EXPECT_NE(device->sharing_note().find("device: the GL context's device"), std::string::npos)
        << device->sharing_note();
  }
  for (Precision p : {Precision::Float, Precision::Double}) {
    if (p == Precision::Double && !device->has_double()) continue;
    SCOPED_TRACE(simsols::testing::precision_name(p));
    Simulation sim(device, pile(p));
    sim.advance(20);
    SimulationView view(gl, sim);
    std::printf("data path: %s\n", view.bridge().path().c_str());
    // the bridge shares exactly when the device offers the extension (this
    // GL context then runs on it, above); PoCL offers none: the host copy
    const bool offered = device->has_extension("cl_khr_gl_sharing");
    EXPECT_EQ(view.bridge().shared(), offered);
    EXPECT_NE(view.bridge().path().find(offered ? "shared" : "host copy"), std::string::npos)
        << view.bridge().path();
    const auto u = view.update(ColorField::Speed, true);
    const FrameGeometry g = view.geometry();
    ASSERT_EQ(g.bead_count, 12u);
    const auto host = view.packer().pack_beads_host(ColorField::Speed);
    EXPECT_EQ(read_gl(gl, g.beads, 48), host.xyzr);
    EXPECT_EQ(read_gl(gl, g.values, 12), host.values);
    EXPECT_EQ(u.range.max, host.range.max);
    const auto contacts = view.packer().pack_contacts_host(1000);
    ASSERT_GE(contacts.stats.total, 12u + 17u) << "beads on the floor and on each other";
    ASSERT_EQ(g.segment_count, contacts.stats.total);
    EXPECT_FLOAT_EQ(g.mean_force, float(contacts.stats.mean_force));
    // same segments, maybe in another order (atomic compaction): compare sums
    const std::vector<float> seg = read_gl(gl, g.segments, g.segment_count * 8);
    double a = 0, b = 0;
    for (size_t k = 0; k < seg.size(); ++k) {
      a += seg[k] * (1 + k % 8);
      b += contacts.segments[k] * (1 + k % 8);
    }
    EXPECT_NEAR(a, b, 1e-6 * std::abs(b));
    // the floor is drawn where it is
    ASSERT_EQ(g.walls.size(), 1u);
    EXPECT_NEAR(g.walls[0].centre.z + view.packer().origin()[2], 0.0, 1e-7);
  }
}
