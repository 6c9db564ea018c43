// The shape study: how the grains' shape shows in the bulk, one shape at a
// time, everything else equal (docs/specimens.md, "Shape and strength").
//
// Each case is one grain template (grain_templates.h: a form, its aspect
// ratio and angularity, the spheres that fill it), given as the keys of a
// `[[grains]]` table. For each, two experiments on the same material:
//
//   Angle of repose, by a column collapse (the "draining" angle): grains
//   of volume-equivalent diameter d are rained into a column a = 10 d long
//   and 5 d wide behind a gate, between a back wall and two side walls,
//   and settle; the gate is taken away and the grains run out over the
//   floor until the heap rests. The heap's free surface is the highest
//   grain top in each d/2 wide strip along the run-out; a straight line
//   fitted to its slope, between 80 % and 20 % of the highest (or 1.5 d),
//   gives the angle (repose_angle). The side walls are as rough as the
//   grains, as in a lab's narrow box.
//
//   Shear strength: the grains poured into a 10 d square shear box, 6
//   bead layers of solid, settled with their own friction, consolidated to
//   10 kPa and sheared 15 % of the box' length; the peak and residual
//   friction angles as every shear test reports them (shear_analysis.h).
//
// The material is glass-like but softened (E = 300 MPa) so that a case
// runs in minutes: at the collapse's and the shear's stresses the grains
// stay stiff (κ = (E/σ)^(2/3) ≈ 1000 at 10 kPa), where the strength of a
// granular material is that of its geometry and friction, not of its
// stiffness. No rolling resistance: a sphere's only resistance to rolling
// is then its neighbours, and what a shape adds shows undiluted.
#pragma once

#include <cmath>
#include <filesystem>
#include <functional>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include "solver/apparatus/shear_box/shear_analysis.h"
#include "solver/core/cl_device.h"

namespace simsols {

struct ShapeCase {
  std::string label;      // "tetrahedral, angularity 0.5"
  std::string grain_keys;  // the [[grains]] table's keys, one per line
  double rolling_friction = 0;  // m, the material's mu_r (none in the shape presets)
  std::string rolling;          // [effects] rolling; empty: the built-in default
};

// quick: a sphere, an elongated and a flat grain, the tetrahedral form at
// three angularities and the sand form; ci: the sphere and one
// tetrahedron, smaller and shorter (a check that it runs, not figures);
// rolling: spheres with rolling resistance, mu_r = 0.05, 0.1 and 0.2 R
// under each rolling law (and none), heaps only, each watched 1 s after
// it rests (Ai et al. 2011's comparison of the laws on a pile).
struct ShapePreset {
  std::string name;
  std::vector<ShapeCase> cases;
  double diameter = 3e-3;   // m, volume-equivalent
  int column_layers = 10;   // the column's solid, in layers of 10 x 5 beads
  int shear_layers = 6;     // the shear box' solid, in layers of 10 x 10 beads
  double shear_fraction = 0.15;  // of the box' length
  bool shear = true;
  double hold = 0;  // s: the rested heap watched this much longer (its slump)
  double collapse_limit = 2.0;  // s: the collapse ends here if the heap has not rested
};
ShapePreset shape_preset(const std::string& name);  // throws UsageError for an unknown one

// The heap's angle (degrees) from its surface profile: tops h at strips x
// (m), x rising from the back wall; a least-squares line over the heap's
// slope, the strips from the highest on whose top lies at most 80 % of the
// highest, up to where the surface first drops below 20 % of it or below
// 1.5 `layer` (the grain diameter: grains strewn one deep beyond the toe
// are no part of the heap). `rms` receives the line's RMS misfit (m). NaN
// with fewer than three such strips.
double repose_angle(std::span<const double> x, std::span<const double> h, double layer,
                    double* rms = nullptr);

struct ReposeResult {
  int grains = 0, spheres = 0;
  double angle = 0;      // degrees
  double fit_rms = 0;    // m
  double height = 0;     // m, the heap's highest top
  double height_later = std::nan(""), angle_later = std::nan("");  // after the hold
  double runout = 0;     // m, from the back wall to the farthest grain
  double fill_time = 0, collapse_time = 0;  // s, simulated
  std::vector<double> x, top;  // the profile (m)
};

struct ShapeResult {
  ShapeCase shape;
  std::string fidelity;  // how well the spheres fill the shape (the template's comment)
  ReposeResult repose;
  ShearSummary shear;
  std::vector<double> shear_mm, shear_ratio;  // tau/sigma against displacement
  double wall_seconds = 0;
};

using ShapeLog = std::function<void(const std::string&)>;
ShapeResult run_shape_case(const ShapePreset& preset, const ShapeCase& c,
                           const std::shared_ptr<Device>& device, const ShapeLog& log);

// shapes.csv (one row per case, units in the header), summary.md (the
// table) and the pictures repose_profiles.png and shear_curves.png in
// `dir`; rewritten after every case.
void write_shape_results(const std::vector<ShapeResult>& results, const ShapePreset& preset,
                         const std::filesystem::path& dir);
std::string shape_table(const std::vector<ShapeResult>& results);

}  // namespace simsols
