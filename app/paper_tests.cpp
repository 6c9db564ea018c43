#include "paper_tests.h"

#include <cmath>
#include <cstdio>

#include "errors.h"
#include "scene_toml.h"
#include "shear_box.h"

namespace simsols {

int table1_layers(double d_mm) {
  const std::pair<double, int> table[] = {
      {2.38125, 8}, {3.175, 6}, {3.96875, 5}, {4.7625, 4}, {6.35, 4}};
  for (const auto& [d, n] : table)
    if (std::fabs(d - d_mm) < 1e-6) return n;
  return 0;
}

std::string paper_test_name(double d_mm, double s_kpa) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "d%gmm_%gkPa", d_mm, s_kpa);
  return buf;
}

Scene paper_test_scene(const Scene& base, const std::string& base_name, double d_mm, double s_kpa,
                       int layers, const std::function<void(Scene&)>& adjust) {
  if (!base.shear_box)
    throw SceneError("missing_field", base_name, 0, "shear_box", "the base scene has no shear box");
  if (layers <= 0) layers = table1_layers(d_mm);
  if (layers <= 0) {
    char buf[160];
    std::snprintf(buf, sizeof buf,
                  "%g mm is not a Table 1 size (2.38125, 3.175, 3.96875, 4.7625, 6.35); give the "
                  "layers for other sizes",
                  d_mm);
    throw SceneError("out_of_range", base_name, 0, "specimen.diameter", buf);
  }
  Scene sc = base;
  sc.particles.clear();
  sc.walls.erase(sc.walls.begin() + base.shear_box->first_wall,
                 sc.walls.begin() + base.shear_box->first_wall + kShearBoxWalls);
  ShearBox b = *base.shear_box;
  if (b.specimen.method == ShearSpecimen::Method::Given)
    throw SceneError("bad_enum", base_name, 0, "shear_box.specimen.method",
                     "the programme prepares its own specimens: use \"layers\" or \"pour\"");
  b.specimen.diameter = d_mm * 1e-3;
  b.specimen.layers = layers;
  b.normal_stress = s_kpa * 1e3;
  b.split_height = 0;
  b.gap = 0;
  sc.shear_box = b;
  sc.name = paper_test_name(d_mm, s_kpa);
  sc.source_text.clear();
  if (adjust) adjust(sc);
  if (auto issue = build_shear_box(sc))
    throw SceneError(issue->code, base_name + " (" + sc.name + ")", 0, issue->field, issue->message);
  return sc;
}

}  // namespace simsols
