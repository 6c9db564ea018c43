#include "app/experiment/grading_plots.h"

#include <filesystem>

#include "render/plot/chart.h"
#include "solver/apparatus/specimen/grading.h"
#include "solver/io/output.h"
#include "solver/scene/clump.h"
#include "solver/scene/choices.h"

namespace simsols {
namespace {

plot::Series sieve_series(const std::string& label, const GradingCurve& c) {
  plot::Series s;
  s.label = label;
  for (size_t i = 0; i < c.size.size(); ++i) {
    s.x.push_back(c.size[i] * 1e3);
    s.y.push_back(100 * c.passing[i]);
  }
  return s;
}

}  // namespace

const Specimen* graded_specimen(const Scene& scene) {
  const Specimen* s = scene.specimen();
  return s && s->method == Specimen::Method::Pour && s->grading.law != Grading::Law::Single ? s
                                                                                           : nullptr;
}

void write_grading_files(const Scene& scene, const std::string& dir) {
  const Specimen* s = graded_specimen(scene);
  if (!s) return;
  std::vector<double> diameters;  // beads', or grains' volume-equivalent
  if (s->grain >= 0) {
    const double d_eq = volume_equivalent_diameter(grain_body(scene.grains[s->grain]));
    for (const Clump& c : scene.clumps) diameters.push_back(d_eq * c.scale);
  } else {
    for (const Particle& p : scene.particles)
      if (p.material == s->material) diameters.push_back(2 * p.radius);
  }
  if (diameters.empty()) return;
  const GradingCurve asked = grading_curve(s->grading, s->diameter);
  const std::filesystem::path d = dir;
  write_file_atomic((d / "grading.txt").string(),
                    "# the specimen's grading: the beads drawn against the asked curve "
                    "(docs/specimens.md)\nlaw = " +
                        std::string(choice_name(s->grading.law)) +
                        "\nbeads = " + std::to_string(diameters.size()) + "\n" +
                        grading_report(asked, diameters));
  plot::Chart c;
  c.title = scene.name + ": grading, " + std::to_string(diameters.size()) + " beads";
  c.x_label = "Size d (mm)";
  c.y_label = "Passing by mass (%)";
  c.x_log = true;
  c.y_min = 0;
  c.y_max = 100;
  plot::Series want = sieve_series("asked (" + std::string(choice_name(s->grading.law)) + ")", asked);
  want.dashed = true;
  c.series.push_back(want);
  c.series.push_back(sieve_series("drawn", measured_curve(diameters)));
  plot::write_chart_png(c, (d / "grading.png").string());
}

}  // namespace simsols
