// [[grains]] and [[clumps]]: rigid non-spherical grains (docs/specimens.md,
// "Grains"). A grain is listed as spheres or made from a template
// (grain_templates.h: a named shape); clumps place grains.
#include <cmath>
#include <limits>
#include <filesystem>
#include <stdexcept>

#include "solver/io/scene_tables.h"
#include "solver/scene/choices.h"
#include "solver/scene/clump.h"
#include "solver/scene/grain_templates.h"
#include "solver/scene/mesh_body.h"

namespace simsols::scene_toml {
namespace {

const std::vector<std::string> kShapeKeys = {"aspect_ratio", "angularity", "seed", "resolution", "diameter",
                                             "max_spheres", "coverage", "min_radius_ratio", "mesh_scale"};

FillOptions read_fill(const Reader& r) {
  FillOptions f;
  f.max_spheres = static_cast<int>(r.number("max_spheres", f.max_spheres));
  r.check_range("max_spheres", f.max_spheres, f.max_spheres >= 1 && f.max_spheres <= 64, "[1, 64]");
  f.coverage = r.number("coverage", f.coverage);
  r.check_range("coverage", f.coverage, f.coverage > 0 && f.coverage <= 1, "(0, 1]");
  f.min_radius_ratio = r.number("min_radius_ratio", f.min_radius_ratio);
  r.check_range("min_radius_ratio", f.min_radius_ratio, f.min_radius_ratio > 0 && f.min_radius_ratio <= 1,
                "(0, 1]");
  return f;
}

// shape = "elongated" | "flat" | "tetrahedral" | "sand", with its keys.
Grain shaped_grain(const Reader& r, std::string name) {
  GrainShape s;
  s.form = r.choice("shape", s.form);
  if (s.form == GrainForm::Tetrahedral) r.forbid({"aspect_ratio"}, "a tetrahedron has no aspect ratio");
  if (s.form != GrainForm::Sand) r.forbid({"seed"}, "only a \"sand\" grain draws its planes");
  r.forbid({"mesh_scale"}, "only allowed with mesh");
  s.aspect_ratio = r.number("aspect_ratio", s.aspect_ratio);
  r.check_range("aspect_ratio", s.aspect_ratio, s.aspect_ratio >= 1 && s.aspect_ratio <= 10, "[1, 10]");
  s.angularity = r.number("angularity", s.angularity);
  r.check_range("angularity", s.angularity, s.angularity >= 0 && s.angularity <= 1, "[0, 1]");
  s.seed = static_cast<int>(r.number("seed", s.seed));
  s.resolution = static_cast<int>(r.number("resolution", s.resolution));
  r.check_range("resolution", s.resolution, s.resolution >= 16 && s.resolution <= 256, "[16, 256]");
  const double diameter = r.number("diameter");
  r.check_range("diameter", diameter, diameter > 0 && diameter <= 1, "(0, 1] m");
  const FillOptions fill = read_fill(r);
  TemplateFit fit;
  try {
    Grain g = grain_from_solid(std::move(name), shape_body(s), fill, diameter, &fit);
    g.origin = describe(s, fit);
    return g;
  } catch (const std::invalid_argument& e) {
    r.fail("out_of_range", "shape", e.what());
  }
}

// mesh = "file.stl" (or .obj; relative to the scene's folder), its units
// times mesh_scale in metres, filled at `resolution` cells along its
// longest side.
Grain mesh_grain(const Reader& r, std::string name) {
  r.forbid({"aspect_ratio", "angularity", "seed"}, "only allowed with shape, not with mesh");
  std::filesystem::path path = r.string("mesh");
  if (path.is_relative()) path = std::filesystem::path(r.context().file).parent_path() / path;
  const double scale = r.number("mesh_scale", 1);
  r.check_range("mesh_scale", scale, scale > 0 && scale <= 1e3, "(0, 1000]");
  const int resolution = static_cast<int>(r.number("resolution", 64));
  r.check_range("resolution", resolution, resolution >= 16 && resolution <= 256, "[16, 256]");
  const double diameter = r.number("diameter", 0);
  r.check_range("diameter", diameter, diameter >= 0 && diameter <= 1, "[0, 1] m (0: the mesh's own size)");
  const FillOptions fill = read_fill(r);
  try {
    SurfaceMesh mesh = load_surface_mesh(path.string());
    for (Vec3& v : mesh.vertices) v = simsols::scale(scale, v);
    TemplateFit fit;
    Grain g = grain_from_solid(std::move(name), voxelize(mesh, resolution), fill, diameter, &fit);
    g.origin = "mesh " + path.filename().string() + ": " + describe(fit);
    return g;
  } catch (const std::exception& e) {
    r.fail("bad_mesh", "mesh", e.what());
  }
}

Grain listed_grain(const Reader& r, std::string name) {
  r.forbid(kShapeKeys, "only allowed with shape or mesh (a template), not with spheres");
  Grain g;
  g.name = std::move(name);
  for (const std::vector<double>& row : r.rows("spheres", 4)) {
    if (!(row[3] > 0)) r.fail("out_of_range", "spheres", "a radius is not > 0 m");
    g.spheres.push_back({row[0], row[1], row[2], row[3]});
  }
  if (g.spheres.empty()) r.fail("out_of_range", "spheres", "a grain needs at least one sphere");
  if (g.spheres.size() > 64) r.fail("out_of_range", "spheres", "a grain has at most 64 spheres");
  return g;
}

Grain read_grain(const Reader& r, const Scene& scene) {
  const std::string name = r.string("name");
  for (const Grain& other : scene.grains)
    if (other.name == name) r.fail("duplicate_name", "name", "grain '" + name + "' is defined twice");
  const int given = r.has("spheres") + r.has("shape") + r.has("mesh");
  if (given != 1)
    r.fail(given ? "conflicting_keys" : "missing_field", "spheres",
           "a grain needs exactly one of spheres (a list), shape (a template) or mesh (a surface file)");
  if (r.has("mesh")) return mesh_grain(r, name);
  return r.has("shape") ? shaped_grain(r, name) : listed_grain(r, name);
}

Clump read_clump(const Reader& r, const Scene& scene) {
  Clump c;
  const std::string name = r.string("grain");
  c.grain = -1;
  for (size_t g = 0; g < scene.grains.size(); ++g)
    if (scene.grains[g].name == name) c.grain = static_cast<int>(g);
  if (c.grain < 0) r.fail("unknown_grain", "grain", "no grain named '" + name + "' ([[grains]])");
  c.scale = r.number("scale", 1);
  r.check_range("scale", c.scale, c.scale > 0 && c.scale <= 1e3, "(0, 1000]");
  c.material = r.material("material", scene);
  c.position = r.vec3("position");
  const std::vector<double> q = r.numbers("orientation", {1, 0, 0, 0});
  const double norm2 = q.size() == 4 ? q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3] : 0;
  if (!(norm2 > 1e-12)) r.fail("bad_vector", "orientation", "expected a quaternion [w, x, y, z], not zero");
  // unit within rounding is kept as written (a scene written by to_toml
  // reads back bit for bit), as normalized() does for vectors
  const double n = std::sqrt(norm2);
  const double inv = std::abs(n - 1) <= 4 * std::numeric_limits<double>::epsilon() ? 1 : 1 / n;
  c.orientation = {q[0] * inv, q[1] * inv, q[2] * inv, q[3] * inv};
  c.velocity = r.vec3("velocity", {});
  c.angular_velocity = r.vec3("angular_velocity", {});
  return c;
}

}  // namespace

void read_clumps(const Reader& root, Scene& scene) {
  std::vector<std::string> keys = {"name", "spheres", "shape", "mesh"};
  keys.insert(keys.end(), kShapeKeys.begin(), kShapeKeys.end());
  const auto grains = root.tables("grains");
  std::vector<GrainBody> bodies;
  for (size_t i = 0; i < grains.size(); ++i) {
    scene.grains.push_back(read_grain(Reader(*grains[i], item("grains", i), root.context(), keys), scene));
    bodies.push_back(grain_body(scene.grains.back()));
  }
  const auto clumps = root.tables("clumps");
  for (size_t i = 0; i < clumps.size(); ++i) {
    Reader r(*clumps[i], item("clumps", i), root.context(),
             {"grain", "scale", "material", "position", "orientation", "velocity", "angular_velocity"});
    const Clump c = read_clump(r, scene);
    add_clump(scene, c, bodies[c.grain]);
  }
}

}  // namespace simsols::scene_toml
