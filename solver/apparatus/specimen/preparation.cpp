#include "solver/apparatus/specimen/preparation.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <sstream>

#include "solver/apparatus/specimen/expansion.h"
#include "solver/apparatus/specimen/prep_log.h"
#include "solver/apparatus/specimen/tamping.h"
#include "solver/apparatus/registry.h"
#include "solver/common/number_text.h"
#include "solver/common/atomic_file.h"
#include "solver/scene/clump.h"

namespace simsols {
namespace {

using Log = PrepLog;

// The search's preparations, in order: at most kSearchTrials + 2.
double longest_settle(const Scene& s) { return s.cell() ? s.cell()->settle_time : 0; }

DensityTrial trial(const Scene& base, const std::shared_ptr<Device>& device, const char* role,
                   double friction, int number, const Log& log) {
  Scene scene = base;
  Preparation& p = scene.specimen()->preparation;
  p.friction = friction;
  p.relative_density.reset();
  p.void_ratio.reset();
  char head[96];
  std::snprintf(head, sizeof head, "preparation %d of at most %d (%s, friction %.4f): ", number,
                kSearchTrials + 2, role, friction);
  const Log say = log.with_head(head);
  if (!p.expansion) return {role, friction, settle_specimen(scene, device, say), nullptr};
  auto grown = std::make_shared<const Scene>(expand_specimen(scene, device, say).grown);
  return {role, friction, settle_specimen(*grown, device, say), grown};
}

std::string trial_line(const DensityTrial& t, const DensitySearch& s) {
  const Packing& p = t.result.packing;
  char buf[160];
  std::snprintf(buf, sizeof buf, "%-8s friction %.4f: e = %.4f, Z = %.2f, settled in %.3f s",
                t.role.c_str(), t.friction, p.void_ratio, p.coordination, t.result.seconds);
  std::string line = buf;
  if (s.e_max > s.e_min) {
    std::snprintf(buf, sizeof buf, ", D_r = %.3f", relative_density(p.void_ratio, s.e_min, s.e_max));
    line += buf;
  }
  return line;
}

std::string search_csv(const DensitySearch& s) {
  std::ostringstream o;
  o << "role,friction,void_ratio,relative_density,coordination,fabric_anisotropy,settle_s\n";
  for (const DensityTrial& t : s.trials) {
    const Packing& p = t.result.packing;
    o << t.role << ',' << shortest_number(t.friction) << ',' << shortest_number(p.void_ratio)
      << ',' << shortest_number(relative_density(p.void_ratio, s.e_min, s.e_max)) << ','
      << shortest_number(p.coordination) << ',' << shortest_number(p.fabric_anisotropy) << ','
      << shortest_number(t.result.seconds) << '\n';
  }
  return o.str();
}

double dr_of(const DensityTrial& t, const DensitySearch& s) {
  return relative_density(t.result.packing.void_ratio, s.e_min, s.e_max);
}

// e_min and e_max: given, or the densest and loosest preparations'.
void index_void_ratios(const Scene& scene, const std::shared_ptr<Device>& device, DensitySearch& s,
                       const Log& log) {
  const Preparation& prep = scene.specimen()->preparation;
  if (prep.e_min) {
    s.e_min = *prep.e_min;
    s.e_max = *prep.e_max;
  } else {
    s.trials.push_back(trial(scene, device, "densest", 0, 1, log));
    log(trial_line(s.trials.back(), s));
    s.trials.push_back(trial(scene, device, "loosest", kLooseFriction, 2, log));
    s.e_min = s.trials[0].result.packing.void_ratio;
    s.e_max = s.trials[1].result.packing.void_ratio;
    log(trial_line(s.trials.back(), s));
    if (!(s.e_max > s.e_min))
      throw SceneError("out_of_range", scene.source_path, 0, "specimen.preparation.relative_density",
                       "the loosest preparation (e = " + shortest_number(s.e_max) +
                           ") is not looser than the densest (e = " + shortest_number(s.e_min) +
                           "): the specimen is too small to tell them apart");
  }
}

// Regula falsi (Illinois) on x = sqrt(friction) between the densest (x = 0,
// D_r = 1) and the loosest (x = 1, D_r = 0) preparations: the density
// changes most at small friction, which x spreads out. At most
// kSearchTrials trials, ending within kSearchTolerance of the target.
void search(const Scene& scene, const std::shared_ptr<Device>& device, DensitySearch& s,
            const Log& log) {
  double x0 = 0, f0 = 1 - s.target, x1 = 1, f1 = -s.target;
  if (std::abs(f0) <= kSearchTolerance || std::abs(f1) <= kSearchTolerance) return;
  int side = 0;
  for (int k = 0; k < kSearchTrials; ++k) {
    const double x = std::clamp(x0 - f0 * (x1 - x0) / (f1 - f0), 0.02, 0.98);
    s.trials.push_back(trial(scene, device, "trial", x * x * kLooseFriction, int(s.trials.size()) + 1, log));
    log(trial_line(s.trials.back(), s));
    const double f = dr_of(s.trials.back(), s) - s.target;
    if (std::abs(f) <= kSearchTolerance) return;
    if ((f > 0) == (f0 > 0)) {
      x0 = x, f0 = f;
      if (side == -1) f1 /= 2;
      side = -1;
    } else {
      x1 = x, f1 = f;
      if (side == 1) f0 /= 2;
      side = 1;
    }
  }
}

}  // namespace

Packing measure_specimen(Simulation& sim) {
  const Scene& scene = sim.scene();
  const ApparatusCell* cell = scene.cell();
  GrainMap grains;
  if (!scene.clumps.empty()) {  // members' overlaps counted once
    grains.share = solid_volumes(scene);
    int free_beads = static_cast<int>(scene.clumps.size());  // numbered after the clumps
    for (size_t i = 0; i < grains.share.size(); ++i) {
      const Particle& b = scene.particles[i];
      grains.share[i] /= 4.0 / 3.0 * 3.14159265358979323846 * std::pow(b.radius, 3);
      grains.grain.push_back(b.clump >= 0 ? b.clump : free_beads++);
    }
  }
  return measure_packing(sample_contacts(sim), cell ? cell->length : 0, cell ? cell->width : 0, 0,
                         grains);
}

Settled settle_specimen(const Scene& scene, const std::shared_ptr<Device>& device,
                        const PrepLog& progress) {
  Simulation sim(device, scene);
  const std::unique_ptr<ApparatusProgramme> test = make_programme(sim);
  test->advance(1);
  Ticker ticker;
  while (!test->done() && std::strcmp(test->stage_name(), "settle") == 0) {
    test->advance(5000);
    progress.check();
    if (!progress || !ticker.due()) continue;
    char line[128];
    std::snprintf(line, sizeof line, "settling, t = %.4f s of at most %.3f s, step %lld, %.0f s", sim.time(),
                  longest_settle(scene), static_cast<long long>(sim.steps()), ticker.elapsed());
    progress(line);
  }
  Settled s;
  s.packing = measure_specimen(sim);
  s.seconds = sim.time();
  s.steps = sim.steps();
  return s;
}

namespace {

// Layered tamping to the preparation's void ratio, or to the one its
// relative density gives between the index void ratios (given, or found
// by the densest and loosest preparations).
bool prepare_by_tamping(Scene& scene, const std::shared_ptr<Device>& device,
                        const std::filesystem::path& out_dir, const Log& log) {
  Preparation& prep = scene.specimen()->preparation;
  double e = prep.void_ratio.value_or(0);
  if (!prep.void_ratio) {
    DensitySearch s;
    index_void_ratios(scene, device, s, log);
    e = s.e_max - *prep.relative_density * (s.e_max - s.e_min);
    char line[160];
    std::snprintf(line, sizeof line, "D_r %.3f asked: e %.4f between e_min %.4f and e_max %.4f",
                  *prep.relative_density, e, s.e_min, s.e_max);
    log(line);
    prep.e_min = s.e_min, prep.e_max = s.e_max;
  }
  return tamp_specimen(scene, device, e, out_dir, log);
}

// Radius expansion with the friction given (or the materials'): one
// growth, the grown specimen the scene's.
bool prepare_by_expansion(Scene& scene, const std::shared_ptr<Device>& device, const Log& log) {
  const Expansion e = expand_specimen(scene, device, log);
  char line[200];
  std::snprintf(line, sizeof line, "grown to full size in %.4f s (%lld steps): the lid at %.3f mm pushing %.1f kPa",
                e.seconds, e.steps, 1e3 * e.lid_height, e.lid_stress / 1e3);
  log(line);
  scene = e.grown;
  return true;
}

// The search's target D_r: asked, or the one the asked void ratio has
// between the index void ratios.
double target_density(const Scene& scene, const DensitySearch& s) {
  const Preparation& prep = scene.specimen()->preparation;
  if (prep.relative_density) return *prep.relative_density;
  const double dr = relative_density(*prep.void_ratio, s.e_min, s.e_max);
  if (dr < 0 || dr > 1)
    throw SceneError("out_of_range", scene.source_path, 0, "specimen.preparation.void_ratio",
                     shortest_number(*prep.void_ratio) + " is out of range, allowed [e_min = " +
                         shortest_number(s.e_min) + ", e_max = " + shortest_number(s.e_max) +
                         "] (the densest and loosest preparations)");
  return dr;
}

}  // namespace

bool prepare_specimen(Scene& scene, const std::shared_ptr<Device>& device,
                      const std::filesystem::path& out_dir, const PrepLog& log,
                      DensitySearch* searched) {
  Specimen* specimen = scene.specimen();
  if (specimen && specimen->preparation.tamping_layers > 0) return prepare_by_tamping(scene, device, out_dir, log);
  if (!specimen) return false;
  Preparation& prep = specimen->preparation;
  const bool grow = prep.expansion;
  if (grow && !prep.relative_density && !prep.void_ratio) return prepare_by_expansion(scene, device, log);
  if (!prep.relative_density && !prep.void_ratio) return false;
  DensitySearch s;
  index_void_ratios(scene, device, s, log);
  s.target = target_density(scene, s);
  search(scene, device, s, log);
  if (s.trials.empty()) {  // e_min, e_max given and the target at one end: that end's friction
    s.trials.push_back(trial(scene, device, "trial", s.target >= 0.5 ? 0 : kLooseFriction, 1, log));
    log(trial_line(s.trials.back(), s));
  }
  const DensityTrial* best = nullptr;
  for (const DensityTrial& t : s.trials)
    if (!best || std::abs(dr_of(t, s) - s.target) < std::abs(dr_of(*best, s) - s.target)) best = &t;
  s.friction = best->friction;
  s.achieved = dr_of(*best, s);
  const std::shared_ptr<const Scene> grown = best->grown;
  if (grown) scene = *grown;  // its preparation holds the friction; `prep` is now that scene's
  Preparation& chosen = scene.specimen()->preparation;
  chosen.friction = s.friction;
  chosen.e_min = s.e_min;
  chosen.e_max = s.e_max;
  chosen.relative_density.reset();
  chosen.void_ratio.reset();
  std::filesystem::create_directories(out_dir);
  write_file_atomic((out_dir / "density.csv").string(), search_csv(s));
  if (searched) *searched = s;
  char line[160];
  std::snprintf(line, sizeof line, "D_r %.3f asked, %.3f reached with friction %.4f (e_min %.4f, e_max %.4f)",
                s.target, s.achieved, s.friction, s.e_min, s.e_max);
  log(line);
  return true;
}

std::string packing_text(const Packing& p, const Preparation& prep) {
  std::ostringstream o;
  const auto put = [&](const char* key, double v) { o << key << " = " << shortest_number(v) << '\n'; };
  put("beads", p.beads);
  put("grains", p.grains);
  put("bulk_void_ratio", p.bulk_void_ratio);
  put("height_mm", p.height * 1e3);
  put("void_ratio", p.void_ratio);
  put("solid_fraction", p.solid_fraction);
  if (prep.e_min) {
    put("relative_density", relative_density(p.void_ratio, *prep.e_min, *prep.e_max));
    put("e_min", *prep.e_min);
    put("e_max", *prep.e_max);
  }
  put("coordination", p.coordination);
  put("grain_coordination", p.grain_coordination);
  put("fabric_xx", p.fabric[0]);
  put("fabric_yy", p.fabric[1]);
  put("fabric_zz", p.fabric[2]);
  put("fabric_anisotropy", p.fabric_anisotropy);
  put("slab_height_mm", p.slab_height * 1e3);
  if (prep.friction) put("preparation_friction", *prep.friction);
  return o.str();
}

}  // namespace simsols
