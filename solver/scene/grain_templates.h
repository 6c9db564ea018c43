// Grain templates from a shape's description (docs/specimens.md, "Grain
// templates").
//
// A user describes a grain the way a sedimentologist would, by its form
// and its angularity, and gets a clump (a list of overlapping spheres):
//
//   elongated    a prolate body, length / width = aspect_ratio
//   flat         an oblate body, width / thickness = aspect_ratio
//   tetrahedral  a regular tetrahedron
//   sand         an irregular polyhedron: 20 random planes tangent to a
//                prolate ellipsoid (aspect_ratio), cut by that ellipsoid;
//                `seed` draws the planes
//
// Angularity (0 to 1) sharpens the form. The two smooth forms are
// superellipsoids |x/a|^n + |y/b|^n + |z/c|^n <= 1 with n = 2 + 8 a: an
// ellipsoid at 0, a nearly square-edged box at 1. The two polyhedra have
// their edges and corners rounded with a radius (1 - a) / 2 of their
// inradius: the polyhedron eroded by that radius and dilated back.
//
// The solid is laid on a VoxelBody (`resolution` cells along its longest
// side) and filled by grain_fill.h. The spheres are then scaled so the
// union's volume-equivalent diameter is `diameter`, the size a grading
// counts. Everything is deterministic: the same description gives the
// same spheres to the last bit.
#pragma once

#include <string>

#include "solver/scene/grain_fill.h"
#include "solver/scene/scene.h"
#include "solver/scene/voxel_body.h"

namespace simsols {

enum class GrainForm { Elongated, Flat, Tetrahedral, Sand };

struct GrainShape {
  GrainForm form = GrainForm::Elongated;
  double aspect_ratio = 1.5;  // [1, 10]; not for tetrahedral
  double angularity = 0;      // [0, 1]
  int seed = 1;               // sand: the planes' draw
  int resolution = 48;        // cells along the longest side, [16, 256]
};

// How faithful a filled template is (grain_fill.h).
struct TemplateFit {
  int spheres = 0;
  double coverage = 0;      // fraction of the solid's cells inside the spheres
  double volume_ratio = 0;  // union of the spheres' volume / the solid's (its cells')
};

// The shape's solid, its longest semi-axis (or circumradius) 1 m, centred
// at the origin, with two empty cells around it. Throws
// std::invalid_argument naming the field out of range.
VoxelBody shape_body(const GrainShape& shape);

// Fills `solid` and scales the spheres to the volume-equivalent diameter
// `diameter` (m; 0 keeps the solid's size). The spheres are centred on the
// union's centroid.
Grain grain_from_solid(std::string name, const VoxelBody& solid, const FillOptions& fill,
                       double diameter, TemplateFit* fit = nullptr);

// "12 spheres cover 95.1 % of the solid; their union has 0.970 of its volume".
std::string describe(const TemplateFit& fit);
// "elongated, aspect ratio 2.00, angularity 0.30: " + describe(fit).
std::string describe(const GrainShape& shape, const TemplateFit& fit);

}  // namespace simsols
