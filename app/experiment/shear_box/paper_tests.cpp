#include "app/experiment/shear_box/paper_tests.h"

#include <cmath>
#include <cstdio>
#include <iterator>

#include "solver/common/errors.h"
#include "solver/io/scene_toml.h"
#include "solver/apparatus/shear_box/shear_box.h"

namespace simsols {

namespace {

// Table 1's sizes (kTable1SizesMm) and their layers.
constexpr int kTable1Layers[] = {8, 6, 5, 4, 4};
// How far a size may be from a Table 1 size and still name it: the printed
// sizes are rounded to 0.01 mm (at most 0.16 % off, 3.18 for 3.175); the
// nearest two sizes are 17 % apart.
constexpr double kTable1Tolerance = 0.005;

}  // namespace

std::optional<double> nearest_table1_size(double d_mm) {
  for (double d : kTable1SizesMm)
    if (std::fabs(d_mm - d) <= kTable1Tolerance * d) return d;
  return std::nullopt;
}

int table1_layers(double d_mm) {
  const std::optional<double> d = nearest_table1_size(d_mm);
  if (!d) return 0;
  for (size_t k = 0; k < std::size(kTable1SizesMm); ++k)
    if (kTable1SizesMm[k] == *d) return kTable1Layers[k];
  return 0;
}

std::string table1_sizes_text() {
  std::string s;
  for (size_t k = 0; k < std::size(kTable1SizesMm); ++k) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.2f", kTable1SizesMm[k] + 1e-9);  // 3.175 -> 3.18
    s += (k == 0 ? "" : k + 1 == std::size(kTable1SizesMm) ? " and " : ", ") + std::string(buf);
  }
  return s + " mm";
}

std::string paper_test_name(double d_mm, double s_kpa) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "d%gmm_%gkPa", d_mm, s_kpa);
  return buf;
}

Scene paper_test_scene(const Scene& base, const std::string& base_name, double d_mm, double s_kpa,
                       int layers, const std::function<void(Scene&)>& adjust) {
  if (!base.apparatus_as<ShearBox>())
    throw SceneError("missing_field", base_name, 0, "shear_box", "the base scene has no shear box");
  if (layers <= 0) {
    const std::optional<double> d = nearest_table1_size(d_mm);
    if (!d) {
      char buf[64];
      std::snprintf(buf, sizeof buf, "%g mm is not a Table 1 size (", d_mm);
      throw SceneError("out_of_range", base_name, 0, "specimen.diameter",
                       buf + table1_sizes_text() + "); give the layers for other sizes");
    }
    d_mm = *d;
    layers = table1_layers(d_mm);
  }
  Scene sc = base;
  sc.particles.clear();
  ShearBox b = *base.apparatus_as<ShearBox>();
  sc.walls.erase(sc.walls.begin() + b.first_wall, sc.walls.begin() + b.first_wall + kShearBoxWalls);
  if (b.specimen.method == Specimen::Method::Given)
    throw SceneError("bad_enum", base_name, 0, "shear_box.specimen.method",
                     "the programme prepares its own specimens: use \"layers\" or \"pour\"");
  // the gap keeps its share of the bead diameter (the default's 0.2 d, or
  // the base's own spacing); the split height is found again
  const double gap_share = b.specimen.diameter > 0 ? b.gap / b.specimen.diameter : 0;
  b.specimen.diameter = d_mm * 1e-3;
  b.specimen.layers = layers;
  b.normal_stress = s_kpa * 1e3;
  b.split_height = 0;
  b.gap = gap_share * b.specimen.diameter;
  sc.apparatus = b;
  sc.name = paper_test_name(d_mm, s_kpa);
  sc.source_text.clear();
  if (adjust) adjust(sc);
  if (auto issue = build_shear_box(sc))
    throw SceneError(issue->code, base_name + " (" + sc.name + ")", 0, issue->field, issue->message);
  return sc;
}

Scene default_shear_base() {
  Scene base = parse_scene(default_shear_scene_text(), kDefaultSceneName);
  base.outputs.dump_interval = 0;
  return base;
}

}  // namespace simsols
