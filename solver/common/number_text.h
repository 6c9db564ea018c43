// Numbers as text that reads back exactly.
#pragma once

#include <string>

namespace simsols {

// Shortest decimal text that parses back to exactly `v` ("0.1", "1e-05").
std::string shortest_number(double v);

}  // namespace simsols
