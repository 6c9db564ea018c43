// The periodic cell on the host: its shape as it deforms, and what the
// kernels read of it (periodic.cl, the CELL_* record of layout.h).
//
// A scene with a periodic cell (Scene::periodic, set by the periodic_cell
// apparatus) has no walls: its space repeats along the three edges of the
// cell, the columns of H (upper triangular: a = (Lx, 0, 0), b = (xy, Ly, 0),
// c = (xz, yz, Lz)). The cell deforms with a homogeneous velocity gradient
// L (upper triangular too, so H stays so), which the loading programme sets
// between steps: H <- (I + L dt) H at the end of every step, the affine
// part of the particles' motion the same map (periodic.cl).
//
// The device record is the cell's one true copy (a checkpoint and the
// guard's restore carry it); CellNow is the host's mirror, re-read by
// derive_state. Steps, in the pipeline's order:
//   detect_contacts  a rebuild first wraps the particles into the cell
//                    (wrap_positions), then restarts the map since the
//                    build (cell_rebuilt)
//   move_cell        the step's deformation (advance_cell), the tilts
//                    folded back when a shear passes half an edge (the same
//                    lattice, Lees & Edwards' flip), the record written
// A cell that would become thinner than twice the cut-off (the largest
// diameter plus the skin) stops the run: minimum images would be wrong.
#pragma once

#include <array>
#include <vector>

#include "solver/common/vec3.h"

namespace simsols {

class Model;
class State;

using Mat3 = std::array<double, 9>;  // row-major: [3 r + c]

Mat3 identity3();
Mat3 mul3(const Mat3& a, const Mat3& b);
Vec3 apply3(const Mat3& m, const Vec3& v);
Mat3 inverse3(const Mat3& m);
double det3(const Mat3& m);

// What the host keeps of the cell (the device record's content).
struct CellNow {
  Mat3 h{};            // edges as columns, m
  Mat3 grad{};         // velocity gradient L, 1/s
  Mat3 since_build{};  // the affine map since the last list build (F)
  Vec3 corner{};       // lowest corner, device frame, m
};

// The cell's widths between opposite faces (V / |b x c|, ...), m.
Vec3 cell_widths(const Mat3& h);
// The nearest image of the separation d (minimum image), as the kernels
// take it.
Vec3 min_image(const Mat3& h, const Vec3& d);
// The same lattice with its tilts within half an edge: |xy| <= Lx/2,
// |xz| <= Lx/2, |yz| <= Ly/2.
Mat3 fold_tilts(Mat3 h);
// True when m is upper triangular (the cell's and its gradient's form).
bool upper_triangular(const Mat3& m);

// The stages' part (pipeline.cpp): nothing in scenes without a cell.
void cell_rebuilt(const Model& model, State& state);
void move_cell(const Model& model, State& state);
// The device record of `cell` (CELL_REALS doubles, layout.h).
std::vector<double> cell_record(const Model& model, const CellNow& cell);
// The host's mirror written to the device / re-read from it (after the
// state was written wholesale, or a logged write replayed: guard.h).
void write_cell(const Model& model, State& state);
void read_cell(const Model& model, State& state);

}  // namespace simsols
