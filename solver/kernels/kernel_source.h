// The OpenCL C sources of the solver, embedded at build time.
//
// kernels/*.cl are the single source of the physics. solver/kernels/
// CMakeLists.txt lists them in program order and embed_kernels.cmake turns them into string
// constants; cl_program.cpp concatenates them with a -D prelude derived from
// the Scene (precision, effects) and builds one program per configuration.
// The renderer's packing kernels (render/view/render_pack.cl) are embedded
// the same way by render/view and built, with common.cl in front, only when
// something draws (view_pack.h).
#pragma once

#include <span>
#include <string_view>

namespace simsols {

struct KernelFile {
  const char* name;
  const char* text;
};

// In program order: definitions before their use.
std::span<const KernelFile> kernel_files();

}  // namespace simsols
