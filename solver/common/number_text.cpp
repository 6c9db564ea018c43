#include "solver/common/number_text.h"

#include <charconv>

namespace simsols {

std::string shortest_number(double v) {
  char buf[64];
  const auto res = std::to_chars(buf, buf + sizeof buf, v);
  return std::string(buf, res.ptr);
}

}  // namespace simsols
