// simsols bench: particle-steps per second and device bytes per particle.
//
// Dense frictional packings of the paper's glass beads (d = 2.38125 mm,
// Table 2: mu_s = 0.02, mu_r = 5e-5 m, e = 0.87) with gravity, confined by
// six walls and pre-loaded so that they stay jammed:
//   cubic  simple cubic lattice, 6 contacts per bead: the coordination of a
//          settled shear-box packing (default)
//   fcc    face-centred cubic, 12 contacts per bead: twice the contact load
//   dimers the cubic lattice with neighbours along x joined in pairs into
//          rigid two-sphere clumps (solver/scene/clump.h): the clumps'
//          cost next to the same spheres free
// The first steps (first list build, kernel warm-up) are not timed; each case
// is then timed `repeat` times and the median rate is printed with the range.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <sstream>
#include <vector>

#include "solver/scene/choices.h"
#include "app/cli/bench_effects.h"
#include "app/cli/bench_render.h"
#include "app/cli/commands.h"
#include "render/view/frames.h"
#include "solver/core/simulation.h"
#include "solver/scene/clump.h"

namespace simsols {

Scene bench_scene(int target, Precision precision, bool fcc) {
  Scene s;
  s.name = "bench";
  s.materials = {paper_glass()};
  s.numerics.precision = precision;
  s.numerics.duration = 1;
  const double d = 2.38125e-3, R = d / 2;
  // FCC cell with every contact pre-loaded (overlap 2e-4 d ~ 0.5 um, i.e. a
  // confining stress of order 100 kPa) and walls on all six sides pressing
  // with the same overlap: the packing stays jammed for the whole run.
  const double squeeze = 2e-4;
  const double a = d * (fcc ? std::sqrt(2.0) : 1.0) * (1 - squeeze);
  const int per_cell = fcc ? 4 : 1;
  const int side = std::max(1, static_cast<int>(std::ceil(std::cbrt(double(target) / per_cell))));
  // (the last layer may be partial: the lid rests on the highest beads)
  const Vec3 basis_fcc[4] = {{0, 0, 0}, {0.5, 0.5, 0}, {0.5, 0, 0.5}, {0, 0.5, 0.5}};
  const std::vector<Vec3> basis(basis_fcc, basis_fcc + per_cell);
  for (int k = 0; k < side && int(s.particles.size()) < target; ++k)
    for (int j = 0; j < side && int(s.particles.size()) < target; ++j)
      for (int i = 0; i < side && int(s.particles.size()) < target; ++i)
        for (const Vec3& b : basis) {
          if (int(s.particles.size()) >= target) break;
          Particle p;
          p.radius = R;
          p.position = {R * (1 - 2 * squeeze) + (i + b[0]) * a,
                        R * (1 - 2 * squeeze) + (j + b[1]) * a,
                        R * (1 - 2 * squeeze) + (k + b[2]) * a};
          s.particles.push_back(p);
        }
  Vec3 hi{0, 0, 0};  // the walls touch the outermost beads with the same overlap
  for (const Particle& p : s.particles)
    for (int c = 0; c < 3; ++c) hi[c] = std::max(hi[c], p.position[c] + R * (1 - 2 * squeeze));
  auto plane = [](const char* name, Vec3 p, Vec3 n) {
    Wall w;
    w.name = name;
    w.point = p;
    w.normal = n;
    return w;
  };
  s.walls = {plane("floor", {0, 0, 0}, {0, 0, 1}), plane("lid", {0, 0, hi[2]}, {0, 0, -1}),
             plane("x0", {0, 0, 0}, {1, 0, 0}),    plane("x1", {hi[0], 0, 0}, {-1, 0, 0}),
             plane("y0", {0, 0, 0}, {0, 1, 0}),    plane("y1", {0, hi[1], 0}, {0, -1, 0})};
  return s;
}

namespace {

// The packing's beads along x joined in pairs into rigid dimers (the last
// of an odd row stays free).
Scene as_dimers(const Scene& beads) {
  Scene s = beads;
  s.particles.clear();
  const std::vector<Particle>& p = beads.particles;
  const double r = p.front().radius, a = 2 * r * (1 - 2e-4);
  s.grains = {{"dimer", {{-a / 2, 0, 0, r}, {a / 2, 0, 0, r}}, ""}};
  const GrainBody body = grain_body(s.grains[0]);
  const double x0 = p.front().position[0];
  for (size_t k = 0; k < p.size(); ++k) {
    const bool even = std::lround((p[k].position[0] - x0) / a) % 2 == 0;
    const bool pair = even && k + 1 < p.size() && p[k + 1].position[1] == p[k].position[1] &&
                      p[k + 1].position[2] == p[k].position[2];
    if (!pair) {
      s.particles.push_back(p[k]);
      continue;
    }
    Clump c;
    c.position = {0.5 * (p[k].position[0] + p[k + 1].position[0]), p[k].position[1],
                  p[k].position[2]};
    add_clump(s, c, body);
    ++k;
  }
  return s;
}

struct BenchOptions {
  std::vector<int> sizes{5000, 50000, 500000};
  std::vector<std::string> precisions{"float", "double"};
  std::string packing = "cubic";
  double budget = 3e7;  // particle-steps timed per repetition
  int repeat = 5;       // timed repetitions per case; the median is reported
  bool render = false;  // --render: renderer frame times instead
  bool effects = false; // --effects: each effect slot on and off
  bool buffers = false; // --buffers: the device memory buffer by buffer
  RenderBenchOptions render_opt;
  std::string frame_size = "1280x720";
};

// The state's buffers, bytes per particle, largest first (those under
// 0.5 B per particle summed in one line).
void print_buffers(const State& state, int n) {
  std::vector<std::pair<std::string, const Buffer*>> all = state.all_buffers();
  std::sort(all.begin(), all.end(),
            [](const auto& a, const auto& b) { return a.second->bytes > b.second->bytes; });
  double small = 0;
  for (const auto& [name, b] : all) {
    const double per = double(b->bytes) / n;
    if (per < 0.5) small += per;
    else std::printf("%10s   %-16s %8.1f bytes/particle\n", "", name.c_str(), per);
  }
  std::printf("%10s   %-16s %8.1f bytes/particle\n", "", "(the rest)", small);
}

int bench(const BenchOptions& opt) {
  auto device = open_command_device();
  std::printf("device: %s\npacking: %s\n", device->description().c_str(), opt.packing.c_str());
  std::printf("%10s %9s %8s %16s %20s %14s %10s %7s %11s\n", "particles", "precision", "steps",
              "particle-steps/s", "(min..max)", "bytes/particle", "build (s)", "lists",
              "contacts/p");
  for (const std::string& prec : opt.precisions) {
    const Precision p = *parse_choice<Precision>(prec);
    if (p == Precision::Double && !device->has_double()) {
      std::printf("(no double precision on this device)\n");
      continue;
    }
    for (int n : opt.sizes) {
      const Scene beads = bench_scene(n, p, opt.packing == "fcc");
      Simulation sim(device, opt.packing == "dimers" ? as_dimers(beads) : beads);
      sim.advance(5);  // first list build and warm-up, not timed
      device->finish();
      const auto steps = static_cast<std::int64_t>(std::clamp(opt.budget / n, 20.0, 5000.0));
      const std::int64_t builds0 = sim.state().list_builds;
      std::vector<double> rates;
      for (int r = 0; r < opt.repeat; ++r) {
        const auto t0 = std::chrono::steady_clock::now();
        sim.advance(steps);
        device->finish();
        const double sec =
            std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
        rates.push_back(double(n) * steps / sec);
      }
      std::sort(rates.begin(), rates.end());
      const Observables o = sim.observe();
      const double bytes = double(sim.state().device_bytes() + sim.model().device_bytes()) / n;
      char spread[64];
      std::snprintf(spread, sizeof spread, "(%.3g..%.3g)", rates.front(), rates.back());
      std::printf("%10d %9s %8lld %16.4g %20s %14.0f %10.2f %7lld %11.2f\n", n, prec.c_str(),
                  static_cast<long long>(steps), rates[rates.size() / 2], spread, bytes,
                  sim.model().program().build_seconds(),
                  static_cast<long long>(sim.state().list_builds - builds0), o.contacts / n);
      std::printf("%10s kernels: %d lanes per work item, work groups of %zu\n", "",
                  sim.model().config().lanes, sim.model().local_size());
      // The runaway guard (solver/core/guard.h): one device-side copy of the
      // dynamic state per interval, and that copy's memory (not in the
      // bytes/particle column).
      std::vector<double> copies;
      for (int r = 0; r < 3; ++r) {
        device->finish();
        const auto t0 = std::chrono::steady_clock::now();
        sim.guard().reset();
        device->finish();
        copies.push_back(
            std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
      }
      std::sort(copies.begin(), copies.end());
      const double step_s = double(n) / rates[rates.size() / 2];
      const double interval = double(sim.guard().interval());
      std::printf("%10s guard: a copy of the state takes %.3g ms, every %.0f steps: %.2g %% of "
                  "the stepping; its memory %.0f bytes/particle\n",
                  "", 1e3 * copies[1], interval, 100 * copies[1] / (interval * step_s),
                  double(sim.guard().backup_bytes()) / n);
      if (device->page_rounding_bytes() > 0)
        std::printf("%10s huge pages: the buffers' rounding to whole pages adds %.0f "
                    "bytes/particle (state and guard)\n",
                    "", double(device->page_rounding_bytes()) / n);
      if (opt.buffers) print_buffers(sim.state(), n);
      std::fflush(stdout);
    }
  }
  return 0;
}

}  // namespace

CommandRunner add_bench_command(CLI::App& app) {
  auto opt = std::make_shared<BenchOptions>();
  CLI::App* cmd = app.add_subcommand("bench", "Particle-steps per second and memory per particle");
  cmd->add_option("--sizes", opt->sizes, "Particle counts (default 5000 50000 500000)")
      ->check(CLI::Range(1, 50000000));
  cmd->add_option("--precision", opt->precisions, "float and/or double")
      ->check(CLI::IsMember(choice_names<Precision>()));
  cmd->add_option("--packing", opt->packing,
                  "cubic (6 contacts per bead, default), fcc (12) or dimers (cubic, beads paired "
                  "into rigid two-sphere clumps)")
      ->check(CLI::IsMember({"cubic", "fcc", "dimers"}));
  cmd->add_option("--budget", opt->budget, "Particle-steps per timed repetition (default 3e7)")
      ->check(CLI::Range(1e4, 1e11));
  cmd->add_option("--repeat", opt->repeat, "Timed repetitions per case; the median is printed (default 5)")
      ->check(CLI::Range(1, 100));
  cmd->add_flag("--render", opt->render,
                "Renderer frame times (opaque, transparent, chains) and data path instead; "
                "default sizes 5000 100000 1000000");
  cmd->add_option("--frame-size", opt->frame_size,
                  "--render: frame size WxH (default 1280x720; with --stereo the output, default "
                  "the 1920x1080 panel)");
  cmd->add_flag("--stereo", opt->render_opt.stereo,
                "--render: the eight Alioscopy views and the interleaving");
  CLI::Option* gl =
      cmd->add_option("--gl", opt->render_opt.gl, "--render: headless OpenGL auto, egl or osmesa")
      ->check(CLI::IsMember({"auto", "egl", "osmesa"}));
  cmd->add_flag("--buffers", opt->buffers,
                "Also print the device memory buffer by buffer (bytes per particle)");
  cmd->add_flag("--effects", opt->effects,
                "Time per step and bytes per contact with each effect slot on and off "
                "(default 50000 beads, float)");
  CLI::Option* sizes = cmd->get_option("--sizes");
  CLI::Option* repeat = cmd->get_option("--repeat");
  CLI::Option* precision = cmd->get_option("--precision");
  CLI::Option* frame_size = cmd->get_option("--frame-size");
  return [opt, sizes, repeat, precision, gl, frame_size] {
    if (opt->effects) {
      EffectsBenchOptions e;
      if (sizes->count() > 0) e.sizes = opt->sizes;
      if (precision->count() > 0) e.precisions = opt->precisions;
      e.fcc = opt->packing == "fcc";
      e.budget = opt->budget;
      e.repeat = opt->repeat;
      return bench_effects(e);
    }
    if (!opt->render) return bench(*opt);
    RenderBenchOptions r = opt->render_opt;
    if (sizes->count() > 0) r.sizes = opt->sizes;
    if (repeat->count() > 0) r.frames = opt->repeat;
    if (!r.stereo || frame_size->count() > 0)
      std::tie(r.width, r.height) = parse_frame_size(opt->frame_size, "--frame-size");
    else
      r.width = r.height = 0;  // the display profile's panel
    gl_from_environment(r.gl, gl->count() > 0);
    return bench_render(r);
  };
}

}  // namespace simsols
