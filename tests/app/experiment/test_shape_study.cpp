// The shape study (app/experiment/shape_study.h): the heap's angle read
// from a surface profile, and the ci preset's column collapses, where a
// tetrahedral grain's heap must stand steeper than a sphere's.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <vector>

#include "app/experiment/shape_study.h"
#include "tests/support/test_support.h"

namespace simsols {
namespace {

// A plateau against the back wall, a straight slope at `deg`, a toe one
// grain deep and grains strewn beyond it.
TEST(ShapeStudy, TheHeapsAngleIsItsSlopesAndNotItsToes) {
  const double d = 3e-3, deg = 31.0, slope = std::tan(deg * std::numbers::pi / 180);
  std::vector<double> x, h;
  for (int k = 0; k < 200; ++k) {
    const double xk = (k + 0.5) * d / 2;
    double hk = std::min(0.03, 0.042 - slope * xk);  // plateau at 30 mm, slope from x = 4 mm
    if (hk < d) hk = (k % 7 == 0) ? d : 0;           // one deep, strewn
    x.push_back(xk);
    h.push_back(hk);
  }
  double rms = -1;
  const double angle = repose_angle(x, h, d, &rms);
  std::printf("[measure] synthetic heap at %.1f deg: fitted %.12f deg, RMS %.2e m\n", deg, angle, rms);
  EXPECT_NEAR(angle, deg, 1e-9);
  EXPECT_LT(rms, 1e-12);
  EXPECT_TRUE(std::isnan(repose_angle(std::vector<double>{0, 1e-3}, std::vector<double>{5e-3, 4e-3}, d)));
}

TEST(ShapeStudy, ATetrahedralGrainsHeapStandsSteeperThanASpheres) {
  const ShapePreset preset = shape_preset("ci");
  ASSERT_EQ(preset.cases.size(), 2u);
  std::vector<double> angle;
  for (const ShapeCase& c : preset.cases) {
    const ShapeResult r = run_shape_case(preset, c, default_device(), {});
    std::printf("[measure] %s: %d grains of %d spheres, heap %.1f deg (fit RMS %.2f mm, %.1f mm high, "
                "settled %.2f s, collapsed %.2f s), %.0f s\n",
                c.label.c_str(), r.repose.grains, r.repose.spheres / r.repose.grains, r.repose.angle,
                r.repose.fit_rms * 1e3, r.repose.height * 1e3, r.repose.fill_time,
                r.repose.collapse_time, r.wall_seconds);
    ASSERT_GT(r.repose.grains, 100);
    angle.push_back(r.repose.angle);
  }
  EXPECT_GT(angle[0], 3);   // the spheres' heap is a heap (7.3 deg here)
  EXPECT_GT(angle[1], angle[0] + 8);  // 26.6 against 7.3 deg here
}

}  // namespace
}  // namespace simsols
