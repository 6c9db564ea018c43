// What the periodic cell's rows say (cell.csv): their columns, the steady
// state a test reaches and its interval, and summary.txt.
//
// The steady state of a test is the mean over its rows from half its
// strain on (simple shear to gamma = 1: gamma >= 0.5), with a 95 %
// interval from five batch means of those rows (Student's t with four
// degrees of freedom), which accounts for the rows' correlation along the
// strain as long as a batch is longer than it. A campaign over several
// specimens (seeds) gives the interval between specimens as well
// (app/experiment/periodic_cell/cell_campaign.h).
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <vector>

namespace simsols {

// The rows' columns, in order (cell.csv): name and unit.
struct CellColumn {
  const char* name;
  const char* unit;
};
enum CellCol : int {
  kColStage, kColTime, kColStep, kColStrain, kColVolumetric, kColSxx, kColSyy, kColSzz, kColSxy,
  kColSxz, kColSyz, kColP, kColQ, kColRatio, kColPhi, kColVoid, kColZ, kColZBackbone,
  kColFabricAniso, kColFabricXz, kColInertial, kColKinetic, kCellColumns
};
const std::array<CellColumn, kCellColumns>& cell_columns();
// One row: the means over a row's controls (stage 0 compression, 1 the test).
using CellRow = std::array<double, kCellColumns>;

std::string cell_rows_csv(const std::vector<CellRow>& rows);
// Throws ReadError for a text that is not a cell.csv.
std::vector<CellRow> parse_cell_rows_csv(const std::string& text);

struct SteadyValue {
  double mean = 0, half_width = 0;  // half_width 0: fewer than ten rows
  int rows = 0;
};
SteadyValue steady_value(const std::vector<CellRow>& rows, int column, double from);
// The same of a value derived from each row.
SteadyValue steady_value(const std::vector<CellRow>& rows, double (*value)(const CellRow&), double from);
// The row's mobilised friction angle (deg), Mohr-Coulomb's from its major
// and minor principal stresses: sin phi = (s1 - s3) / (s1 + s3). In simple
// shear it is larger than atan(tau / sigma_zz), the angle on the plane of
// shearing, since that plane is not the one of maximum obliquity.
double mobilised_angle(const CellRow& row);

struct CellSummary {
  std::string test;
  int particles = 0;
  double pressure = 0, inertial_number = 0;  // Pa, -
  double strain = 0, from = 0;               // the test's last strain, the steady part's start
  SteadyValue ratio, phi, z, p, volumetric;  // p in kPa
  SteadyValue angle;                          // mobilised friction angle, deg
  double phi_compressed = 0, z_compressed = 0;  // at the end of the compression
  std::int64_t compression_steps = 0, steps = 0;
  double wall_seconds = 0;
};
// The steady values of `rows` from strain `from` on (other fields left).
CellSummary cell_summary(const std::vector<CellRow>& rows, double from);
std::string cell_summary_text(const CellSummary& s);

}  // namespace simsols
