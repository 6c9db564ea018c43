// simsols bench --render: frame times of the renderer and its data path.
#pragma once

#include <string>
#include <vector>

#include "solver/scene/scene.h"

namespace simsols {

// The jammed lattice of `simsols bench` (see cmd_bench.cpp).
Scene bench_scene(int target, Precision precision, bool fcc);

struct RenderBenchOptions {
  std::vector<int> sizes{5000, 100000, 1000000};
  int width = 1280, height = 720;
  int frames = 5;  // timed frames per case; the median is printed
  std::string gl = "auto";
  bool stereo = false;  // eight Alioscopy views + interleaving instead of the three modes
};

int bench_render(const RenderBenchOptions& options);

}  // namespace simsols
