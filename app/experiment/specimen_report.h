// The specimen's preparation as a run reports it: prepare_specimen
// (solver/apparatus/specimen/preparation.h) and, when it searched a
// density, the search drawn as density.png beside its density.csv.
#pragma once

#include <filesystem>
#include <memory>

#include "solver/apparatus/specimen/preparation.h"

namespace simsols {

// prepare_specimen, then density.png in `out_dir` when a density was
// searched: each preparation's void ratio against its friction, between
// the index void ratios, with the target and the chosen one.
bool prepare_to_relative_density(Scene& scene, const std::shared_ptr<Device>& device,
                                 const std::filesystem::path& out_dir, const PrepLog& log);

}  // namespace simsols
