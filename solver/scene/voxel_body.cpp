#include "solver/scene/voxel_body.h"

#include <algorithm>

namespace simsols {

double VoxelBody::volume() const {
  const auto count = std::count_if(inside.begin(), inside.end(), [](std::uint8_t c) { return c != 0; });
  return static_cast<double>(count) * cell * cell * cell;
}

}  // namespace simsols
