#include "app/experiment/specimen_report.h"

#include <string>

#include "render/plot/chart.h"
#include "solver/common/number_text.h"

namespace simsols {
namespace {

// density.png: the void ratio each preparation reached against its
// friction, between the index void ratios, with the target and the choice.
void density_chart(const DensitySearch& s, const std::string& title, const std::string& path) {
  plot::Chart c;
  c.title = title + ": void ratio against preparation friction";
  c.x_label = "Friction while settling mu_prep";
  c.y_label = "Void ratio e";
  plot::Series trials;
  trials.label = "preparations";
  trials.line = false;
  trials.markers = true;
  for (const DensityTrial& t : s.trials) {
    trials.x.push_back(t.friction);
    trials.y.push_back(t.result.packing.void_ratio);
  }
  c.series.push_back(trials);
  const double e_target = s.e_max - s.target * (s.e_max - s.e_min);
  const auto level = [&](const std::string& label, double e) {
    plot::Series l;
    l.label = label;
    l.dashed = true;
    l.x = {0, kLooseFriction};
    l.y = {e, e};
    c.series.push_back(l);
  };
  level("e_max", s.e_max);
  level("target e (D_r " + shortest_number(s.target) + ")", e_target);
  level("e_min", s.e_min);
  for (const DensityTrial& t : s.trials)
    if (t.friction == s.friction)
      c.markers.push_back({t.friction, t.result.packing.void_ratio, "chosen"});
  c.x_min = 0;
  c.x_max = kLooseFriction;
  plot::write_chart_png(c, path);
}

}  // namespace

bool prepare_to_relative_density(Scene& scene, const std::shared_ptr<Device>& device,
                                 const std::filesystem::path& out_dir, const PrepLog& log) {
  DensitySearch search;
  const bool prepared = prepare_specimen(scene, device, out_dir, log, &search);
  if (!search.trials.empty()) density_chart(search, scene.name, (out_dir / "density.png").string());
  return prepared;
}

}  // namespace simsols
