// simsols bench --render: for each size, the jammed cubic lattice of the
// solver benchmark (6 contacts per bead, so the force chains are real) is
// stepped once, then timed:
//   pack      beads (positions + field) from the solver's buffers to the GL
//             buffers (kernels + the shared or host-copy path)
//   contacts  the same for the force-chain segments
//   opaque / transparent / chains   one frame at W x H, draw + glFinish
// With --stereo: the eight views of the Alioscopy rig (each at the profile's
// view_scale of the output: the 1920 x 1080 panel, or --frame-size, such as
// a lab window), opaque and transparent, plus the interleaving pass.
// Medians over `frames` repetitions, in milliseconds. llvmpipe renders on
// the CPU with all cores; a GPU driver reports its own figures.
#include "app/cli/bench_render.h"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <memory>

#include "render/gl/alioscopy.h"
#include "render/gl/gl_context.h"
#include "render/gl/renderer.h"
#include "render/view/sim_view.h"
#include "solver/common/errors.h"
#include "solver/core/engine_options.h"
#include "solver/core/simulation.h"

namespace simsols {

namespace {

double median_ms(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v[v.size() / 2] * 1e3;
}

template <typename F>
double time_median(int frames, F f) {
  std::vector<double> t;
  for (int k = 0; k < frames; ++k) {
    const auto t0 = std::chrono::steady_clock::now();
    f();
    t.push_back(std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
  }
  return median_ms(t);
}

}  // namespace

namespace {

// One size in the 8-view Alioscopy form: the views (opaque, transparent)
// and the interleave, in ms.
void time_stereo(const RenderBenchOptions& opt, const render::Gl& gl,
                 render::AlioscopyOutput& alioscopy, render::Renderer& renderer,
                 const render::Camera& cam, const render::FrameGeometry& g,
                 render::ViewSettings s, int n) {
  render::StereoRig rig;
  double views[2];
  for (int m = 0; m < 2; ++m) {
    s.mode = m == 0 ? render::ViewMode::Opaque : render::ViewMode::Transparent;
    alioscopy.render_views(renderer, rig, cam, g, s);  // warm-up
    gl.Finish();
    views[m] = time_median(opt.frames, [&] {
      alioscopy.render_views(renderer, rig, cam, g, s);
      gl.Finish();
    });
  }
  const double inter = time_median(opt.frames, [&] {
    alioscopy.compose(render::AlioscopyOutput::Mode::Interleaved);
    gl.Finish();
  });
  std::printf("%10d %16.2f %14.2f %18.2f %14.2f\n", n, views[0], inter, views[1],
              views[0] + inter);
  std::fflush(stdout);
}

// One size in the flat views: opaque, transparent and chains frames, in ms.
void time_flat(const RenderBenchOptions& opt, const render::Gl& gl, render::Renderer& renderer,
               const render::Camera& cam, const render::FrameGeometry& g, render::ViewSettings s,
               double out[3]) {
  int k = 0;
  for (render::ViewMode m :
       {render::ViewMode::Opaque, render::ViewMode::Transparent, render::ViewMode::Chains}) {
    s.mode = m;
    renderer.draw(cam, g, s);  // warm-up (shader variants, first upload)
    gl.Finish();
    out[k++] = time_median(opt.frames, [&] {
      renderer.draw(cam, g, s);
      gl.Finish();
    });
  }
}

void print_header(const RenderBenchOptions& opt, const render::AlioscopyOutput* alioscopy) {
  if (alioscopy) {
    std::printf("Alioscopy: %d views of %dx%d, interleaved at %dx%d\n", alioscopy->profile().views,
                alioscopy->view_width(), alioscopy->view_height(), alioscopy->output_width(),
                alioscopy->output_height());
    std::printf("%10s %16s %14s %18s %14s\n", "beads", "8 views opaque", "interleave",
                "8 views transp.", "total opaque");
  } else {
    std::printf("%10s %10s %12s %10s %12s %10s %9s  %s\n", "beads", "contacts", "pack (ms)",
                "chains(ms)", "opaque (ms)", "transp(ms)", "chains", "buffers");
  }
}

}  // namespace

int bench_render(const RenderBenchOptions& opt) {
  auto backend = render::parse_gl_backend(opt.gl);
  if (!backend) throw UsageError("bad_enum", "--gl", "'" + opt.gl + "' is not one of: auto, egl, osmesa");
  auto ctx = render::create_headless_context(*backend);
  auto device = Device::open(engine_options_from_environment(),
                             render::cl_share_properties(ctx->share_handles()));
  const render::Gl& gl = ctx->gl();
  render::DisplayProfile profile;
  const int width = opt.width > 0 ? opt.width : profile.width;
  const int height = opt.height > 0 ? opt.height : profile.height;
  render::Renderer renderer(gl);
  renderer.resize(width, height);
  std::printf("GL: %s\nOpenCL: %s\nframe %dx%d, median of %d\n", ctx->description().c_str(),
              device->description().c_str(), width, height, opt.frames);
  std::unique_ptr<render::AlioscopyOutput> alioscopy;
  if (opt.stereo) {
    alioscopy = std::make_unique<render::AlioscopyOutput>(gl, profile);
    alioscopy->resize_output(width, height);
  }
  print_header(opt, alioscopy.get());
  for (int n : opt.sizes) {
    Simulation sim(device, bench_scene(n, Precision::Float, false));
    sim.advance(2);
    render::SimulationView view(gl, sim);
    render::Camera cam;
    cam.set_preset(render::ViewPreset::ThreeQuarter);
    cam.fit(view.lo(), view.hi(), double(width) / height);
    ViewPacker::Range range;
    ViewPacker::ContactStats stats;
    const double pack = time_median(opt.frames, [&] {
      range = view.update(ColorField::Contacts, false).range;
      gl.Finish();
    });
    const double contacts = time_median(opt.frames, [&] {
      stats = view.update(ColorField::Contacts, true).contacts;
      gl.Finish();
    });
    render::ViewSettings s;
    s.bead_map = render::colormap_for(ColorField::Contacts);
    s.value_min = range.min;
    s.value_max = range.max;
    if (opt.stereo) {
      time_stereo(opt, gl, *alioscopy, renderer, cam, view.geometry(), s, n);
      continue;
    }
    double ms[3];
    time_flat(opt, gl, renderer, cam, view.geometry(), s, ms);
    std::printf("%10d %10zu %12.2f %10.2f %12.2f %10.2f %9.2f  %s\n", n, stats.total, pack,
                contacts, ms[0], ms[1], ms[2], view.bridge().path().c_str());
    std::fflush(stdout);
  }
  return 0;
}

}  // namespace simsols
