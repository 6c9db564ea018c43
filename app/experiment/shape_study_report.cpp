// The shape study's presets and what it writes (shape_study.h).
#include <cmath>
#include <cstdio>
#include <sstream>

#include "app/experiment/shape_study.h"
#include "render/plot/chart.h"
#include "solver/common/errors.h"
#include "solver/io/output.h"

namespace simsols {
namespace {

const ShapeCase kSphere{"sphere", "spheres = [[0, 0, 0, 1.5e-3]]", 0, ""};  // the preset's 3 mm
ShapeCase form(const std::string& label, const std::string& keys, int spheres) {
  return {label, keys + "\nmax_spheres = " + std::to_string(spheres), 0, ""};
}

std::string number(double v, int digits) {
  if (!std::isfinite(v)) return "–";
  char b[32];
  std::snprintf(b, sizeof b, "%.*f", digits, v);
  return b;
}

}  // namespace

ShapePreset shape_preset(const std::string& name) {
  ShapePreset p;
  p.name = name;
  if (name == "quick") {
    p.cases = {kSphere,
               form("elongated 2:1, angularity 0.3", "shape = \"elongated\"\naspect_ratio = 2\nangularity = 0.3", 8),
               form("flat 2:1, angularity 0.3", "shape = \"flat\"\naspect_ratio = 2\nangularity = 0.3", 8),
               form("tetrahedral, angularity 0", "shape = \"tetrahedral\"\nangularity = 0", 8),
               form("tetrahedral, angularity 0.5", "shape = \"tetrahedral\"\nangularity = 0.5", 8),
               form("tetrahedral, angularity 1", "shape = \"tetrahedral\"\nangularity = 1", 8),
               form("sand 1.4, angularity 0.6", "shape = \"sand\"\naspect_ratio = 1.4\nangularity = 0.6", 8)};
    return p;
  }
  if (name == "rolling") {
    p.cases = {{"sphere, no rolling resistance", kSphere.grain_keys, 0, "none"}};
    for (const char* law : {"constant_torque", "spring_dashpot"})
      for (const double ratio : {0.05, 0.1, 0.2}) {
        char label[96];
        std::snprintf(label, sizeof label, "sphere, %s, mu_r = %.2f R", law, ratio);
        p.cases.push_back({label, kSphere.grain_keys, ratio * 1.5e-3, law});
      }
    p.shear = false;
    p.hold = 1.0;
    return p;
  }
  if (name == "ci") {
    p.cases = {kSphere, form("tetrahedral, angularity 1", "shape = \"tetrahedral\"\nangularity = 1", 4)};
    p.column_layers = 5;
    p.collapse_limit = 0.5;  // the spheres' heap never rests (they roll off over the floor)
    p.shear = false;
    return p;
  }
  throw UsageError("bad_enum", "--preset",
                   "'" + name + "' is not a shape study preset: quick, rolling, ci");
}

std::string shape_table(const std::vector<ShapeResult>& results) {
  std::ostringstream o;
  o << "| grain | spheres | angle of repose (°) | fit RMS (mm) | heap height (mm), then after the "
       "hold | φ′ peak (°) | φ′ residual (°) | ψ max (°) | wall time (s) |\n"
       "|---|---|---|---|---|---|---|---|---|\n";
  for (const ShapeResult& r : results) {
    const int per = r.repose.grains > 0 ? r.repose.spheres / r.repose.grains : 0;
    const bool shear = !r.shear_mm.empty();
    o << "| " << r.shape.label << " | " << per << " | " << number(r.repose.angle, 1) << " | "
      << number(r.repose.fit_rms * 1e3, 2) << " | " << number(r.repose.height * 1e3, 2) << ", "
      << number(r.repose.height_later * 1e3, 2) << " | "
      << (shear ? number(r.shear.peak_angle, 1) : "–")
      << " | " << (shear ? number(r.shear.residual_angle, 1) : "–") << " | "
      << (shear ? number(r.shear.max_dilatancy_angle, 1) : "–") << " | " << number(r.wall_seconds, 0)
      << " |\n";
  }
  return o.str();
}

void write_shape_results(const std::vector<ShapeResult>& results, const ShapePreset& preset,
                         const std::filesystem::path& dir) {
  std::filesystem::create_directories(dir);
  std::ostringstream csv;
  csv << "grain,rolling,rolling_friction_m,spheres_per_grain,grains_in_column,repose_angle_deg,"
         "fit_rms_m,heap_height_m,runout_m,fill_s,collapse_s,hold_s,heap_height_after_hold_m,"
         "repose_angle_after_hold_deg,peak_angle_deg,residual_angle_deg,max_dilatancy_deg,wall_s\n";
  for (const ShapeResult& r : results) {
    const ReposeResult& q = r.repose;
    csv << '"' << r.shape.label << "\"," << (r.shape.rolling.empty() ? "default" : r.shape.rolling)
        << ',' << r.shape.rolling_friction << ',' << (q.grains ? q.spheres / q.grains : 0) << ','
        << q.grains << ',' << q.angle << ',' << q.fit_rms << ',' << q.height << ',' << q.runout << ','
        << q.fill_time << ',' << q.collapse_time << ',' << preset.hold << ',' << q.height_later << ','
        << q.angle_later << ',' << r.shear.peak_angle << ',' << r.shear.residual_angle << ','
        << r.shear.max_dilatancy_angle << ',' << r.wall_seconds << '\n';
  }
  write_file_atomic((dir / "shapes.csv").string(), csv.str());
  std::string md = "# Shape study (" + preset.name + ")\n\n" + shape_table(results) + "\n";
  for (const ShapeResult& r : results) md += "- " + r.shape.label + ": " + (r.fidelity.empty() ? "a sphere" : r.fidelity) + "\n";
  write_file_atomic((dir / "summary.md").string(), md);

  plot::Chart heap;
  heap.title = "Heaps after the column collapse";
  heap.x_label = "Distance from the back wall x (mm)";
  heap.y_label = "Surface height (mm)";
  heap.y_min = 0;
  heap.x_min = 0;
  heap.x_max = 40e3 * preset.diameter;  // four column lengths: grains strewn beyond are left out
  plot::Chart shear;
  shear.title = "Direct shear at 10 kPa";
  shear.x_label = "Shear displacement δ (mm)";
  shear.y_label = "τ/σ";
  shear.y_min = 0;
  for (const ShapeResult& r : results) {
    plot::Series s;
    s.label = r.shape.label + " (" + number(r.repose.angle, 1) + "°)";
    for (size_t k = 0; k < r.repose.x.size(); ++k) {
      s.x.push_back(r.repose.x[k] * 1e3);
      s.y.push_back(r.repose.top[k] * 1e3);
    }
    heap.series.push_back(s);
    if (r.shear_mm.empty()) continue;
    plot::Series c;
    c.label = r.shape.label;
    c.x = r.shear_mm;
    c.y = r.shear_ratio;
    shear.series.push_back(c);
  }
  plot::write_chart_png(heap, (dir / "repose_profiles.png").string());
  if (!shear.series.empty()) plot::write_chart_png(shear, (dir / "shear_curves.png").string());
}

}  // namespace simsols
