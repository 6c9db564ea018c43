// The periodic cell's plots (PNG): the stress ratio, the solid fraction and
// the coordination against the test's strain, the compression's rows left
// out; the steady part's mean drawn over each.
#pragma once

#include <string>
#include <vector>

#include "solver/apparatus/periodic_cell/cell_analysis.h"

namespace simsols {

// cell_ratio.png, cell_solid_fraction.png, cell_coordination.png in `dir`.
void write_cell_plots(const std::string& dir, const std::string& title,
                      const std::vector<CellRow>& rows, const CellSummary& summary);

}  // namespace simsols
