#include "solver/core/kernel_args.h"

#include <string>

namespace simsols::detail {

void check_count(const Kernel& k, cl_uint given) {
  if (given == k.count) return;
  throw DeviceError("kernel '" + k.name + "' takes " + std::to_string(k.count) +
                    " arguments; its call site binds " + std::to_string(given) +
                    " (solver/kernels/*.cl and the set_args call disagree)");
}

void check_arg(const Kernel& k, cl_uint i, const char* name) {
  if (k.params.empty()) return;  // the driver keeps no argument names
  const std::string& param = k.params[i];
  if (param == name || param == std::string(name) + "_unused") return;
  throw DeviceError("kernel '" + k.name + "' argument " + std::to_string(i) + " is '" + param +
                    "', but the call site binds '" + name +
                    "' there (solver/kernels/*.cl and the set_args call disagree)");
}

}  // namespace simsols::detail
