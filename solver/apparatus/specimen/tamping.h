// Layered tamping by under-compaction (docs/specimens.md, "Layered
// tamping"): how a laboratory builds a specimen of a chosen density from
// moist or dry sand, after Ladd (Geotechnical Testing Journal 1, 1978).
//
// The specimen is built in n layers. Each layer's grains fall onto the
// layers below, settle, and are tamped: the apparatus' platen comes down
// at a steady speed to the height that gives the layer its target void
// ratio, stops, and is lifted off. Tamping a layer also compacts the ones
// below it, so the lower layers are compacted less: layer j (1 at the
// bottom) aims at the dry density of the target less U_j, the
// under-compaction, falling linearly from U_1 at the bottom to 0 at the
// top:
//   U_j = U_1 (n - j) / (n - 1),   1 + e_j = (1 + e) / (1 - U_j)
// and the platen stops at the top the layers up to k then need, those
// below at the target (tamping layer k compacts them to it; Ladd's
// h_k = (H/n)(k - 1 + 1 + U_k) for equal layers),
//   H_k = [(1 + e) sum_{j < k} V_s,j + (1 + e_k) V_s,k] / A,
// V_s,j the layer's solid volume, A the cell's area; the last stops at the
// specimen's height for e. It also stops when it pushes with more than
// kTampStress over the cell's area: a target denser than the grains allow
// must not crush them (1 MPa presses glass-stiff grains into each other by
// well under 0.1 % of their size, soft test beads by a few per cent).
//
// The layers are the poured column's grains, lowest first, n equal shares
// (so every layer has the specimen's grading); each falls from just above
// the layers before. Between layers the specimen is rebuilt from the
// settled state, grains at rest (contact history starts afresh: the
// tamper is lifted and the grains rest under gravity only). What comes out
// is the scene's specimen, `given`: the test then runs as for any other.
#pragma once

#include <filesystem>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "solver/apparatus/specimen/prep_log.h"
#include "solver/core/cl_device.h"
#include "solver/scene/scene.h"

namespace simsols {

inline constexpr double kTampStress = 1e6;  // Pa: the most the platen pushes with
inline constexpr double kTampSpeed = 0.05;    // m/s: the platen's speed down and up

struct TampedLayer {
  int layer = 0;              // 1 at the bottom
  int grains = 0;             // grains (or beads) added
  double target_void_ratio = 0;  // e_j
  double target_top = 0;      // m, H_k
  double platen_stop = 0;     // m, where the platen stopped
  double stress = 0;          // Pa, the platen's push when it stopped
  double void_ratio = 0;      // of the layers so far, settled after the tamper is lifted
};

// The void ratio the layer j of n aims at (above), 1-based.
double layer_void_ratio(double e, double undercompaction, int j, int n);

// Builds the scene's specimen by layered tamping to `void_ratio` when its
// preparation asks for it (tamping_layers > 0); writes tamping.csv in
// out_dir and logs a line per layer. Returns false (and changes nothing)
// when the scene asks for no tamping.
bool tamp_specimen(Scene& scene, const std::shared_ptr<Device>& device, double void_ratio,
                   const std::filesystem::path& out_dir,
                   const PrepLog& log);

// tamping.csv: one row per layer.
std::string tamping_csv(const std::vector<TampedLayer>& layers);

}  // namespace simsols
