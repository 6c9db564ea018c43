// A grain from a surface mesh: an STL or OBJ file read into a VoxelBody
// (voxel_body.h), which grain_fill.h then fills with spheres.
//
// A scanned or drawn grain comes as a closed triangle surface. Reading it
// is Assimp's work: one Debian package reads STL (ASCII and binary) and OBJ
// alike, triangulates polygons and joins the duplicated corners an STL
// stores per facet; writing three parsers here would add nothing but bugs.
// Assimp is private to mesh_body.cpp: what leaves it is plain SurfaceMesh
// data (vertices and index triples), merged over all the file's meshes with
// corners at the same position joined. Debian's Assimp reads coordinates in
// single precision, so a vertex is good to a relative 6e-8: ample for a
// grain's shape, and the reason the asset meshes' volumes hold to 1e-7, not
// to round-off (assets/grains/README.md). No scale is applied: a mesh is in
// the units it was written in (the grain scale comes later, clump.h).
//
// A grain must be a solid, so load_surface_mesh() insists that the surface
// is closed and consistently oriented: after joining, every edge belongs to
// exactly two triangles, which run along it in opposite directions. An open
// or tangled mesh would otherwise give a volume and an inside that mean
// nothing, silently.
//
// The inside test casts, for each column (i, j) of cells, one ray along z
// through the cells' centres and fills between successive pairs of the
// crossings it finds (parity: a point is inside when a ray from it crosses
// the surface an odd number of times). Triangles are binned by the columns
// their xy box covers, so the cost is one pass over the triangles plus a
// sort per column, not cells times triangles. A ray through an edge or a
// vertex must count one crossing, not two or none, so two guards:
//   - each ray is nudged off the cells' centres by an irrational fraction
//     of a cell, 1e-6 (sqrt 2, sqrt 3), which no vertex of a mesh drawn on
//     a regular grid lines up with; the nudge moves the test point by a
//     millionth of a cell, so only a centre within that of the surface can
//     change sides;
//   - whether the ray passes left or right of an edge is decided once per
//     edge, from its two projected ends in a fixed (lexicographic) order,
//     so the two triangles sharing it agree; an exact hit is resolved by a
//     symbolic shift of the ray (simulation of simplicity), so it falls on
//     exactly one side.
// Limits: the grid resolves nothing finer than a cell (a sliver thinner
// than a cell may vanish or fill a whole row); parity takes a self-crossing
// surface's overlap as outside; and floating point can still, in principle,
// miscount a ray within round-off of a vertex, where the nudge makes that
// as unlikely as hitting a number at random (a column with an odd count
// fills its pairs and drops the last crossing).
#pragma once

#include <array>
#include <string>
#include <vector>

#include "solver/common/vec3.h"
#include "solver/scene/voxel_body.h"

namespace simsols {

struct SurfaceMesh {
  std::vector<Vec3> vertices;                 // in the file's units
  std::vector<std::array<int, 3>> triangles;  // indices into vertices, counter-clockwise seen from outside
};

// Reads an STL (ASCII or binary) or OBJ file. Throws std::runtime_error
// naming the file and the fault: missing or unreadable, not a mesh Assimp
// can read, no triangles, or a surface that is not closed (open edges,
// edges of more than two triangles, or triangles facing opposite ways).
SurfaceMesh load_surface_mesh(const std::string& path);

// The volume inside a closed surface: the divergence theorem as a sum of
// signed tetrahedra from a point inside the box, as an absolute value (so
// a surface oriented inside out counts the same).
double enclosed_volume(const SurfaceMesh& mesh);

struct Box3 {
  Vec3 lo{}, hi{};
};
Box3 bounding_box(const SurfaceMesh& mesh);

// The mesh's solid on a grid of cubic cells: cell = the box's longest side
// / cells, the grid the box plus one empty cell on each side (the box
// centred in it). A cell is inside when its centre is inside the surface.
// Expects a closed mesh (as load_surface_mesh returns); throws
// std::invalid_argument for cells outside [4, 512], no triangles or a box
// of zero size.
VoxelBody voxelize(const SurfaceMesh& mesh, int cells_along_longest_side);

}  // namespace simsols
