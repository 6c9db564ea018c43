// The OpenCL C sources of the solver, embedded at build time.
//
// kernels/*.cl are the single source of the physics. solver/CMakeLists.txt
// lists them in program order and embed_kernels.cmake turns them into string
// constants; cl_program.cpp concatenates them with a -D prelude derived from
// the Scene (precision, effects) and builds one program per configuration.
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
