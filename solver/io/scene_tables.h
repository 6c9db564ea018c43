// The scene file's tables, one reader each (docs/scene-format.md).
//
// Each function reads its table(s) from the document's top-level Reader
// into the Scene, noting what lets the reading go on and failing at what
// does not (toml_reader.h). scene_toml.cpp calls them in the order the
// format needs: materials before the particles, walls and apparatus that
// name them. Reading only reads: the generators' spheres and the
// apparatus' walls and specimen are placed afterwards (place_scene,
// scene_toml.h). A new table
// (a new apparatus) is a new scene_tables_*.cpp and one line here.
#pragma once

#include <optional>
#include <sstream>
#include <string>
#include <string_view>
#include <vector>

#include "solver/io/toml_reader.h"
#include "solver/scene/scene.h"
#include "solver/scene/scene_check.h"

namespace simsols::scene_toml {

// scene_tables_bodies.cpp
void read_info(const Reader& root, Scene& scene);          // [scene]
void read_materials(const Reader& root, Scene& scene);     // [[materials]]
void read_interactions(const Reader& root, Scene& scene);  // [[interactions]]
void read_particles(const Reader& root, Scene& scene);     // [[particles]]
void read_walls(const Reader& root, Scene& scene);         // [[walls]]
void read_membrane(const Reader& root, Scene& scene);      // [membrane]
// [[grains]] and [[clumps]]: each clump's member spheres appended to the
// particles (solver/scene/clump.h).
void read_clumps(const Reader& root, Scene& scene);

// scene_tables_generators.cpp: [[generators]], into Scene::generators
// (placed by place_scene, scene_toml.h).
void read_generators(const Reader& root, Scene& scene);

// Writes a scene's tables back as TOML (scene_writer.cpp), every double in
// its shortest round-trip form; the apparatus' writers below use it too.
class TableWriter {
 public:
  TableWriter(const Scene& scene, std::ostringstream& out) : scene_(scene), out_(out) {}
  const Scene& scene() const { return scene_; }
  void header(std::string_view h);
  void line(std::string_view key, const std::string& toml_value);
  void line(std::string_view key, double value);
  void line(std::string_view key, bool value);
  void line(std::string_view key, const Vec3& value);
  void line(std::string_view key, const std::vector<double>& values);
  void text(std::string_view key, std::string_view value);  // a quoted string
  // A material by name (SceneError naming `field` for a bad index).
  void material(std::string_view key, int index, const std::string& field);
  // [<table>.specimen], placed: "given" (the particles are written
  // explicitly) with its preparation's settling friction and index voids.
  void given_specimen(const std::string& table, const Preparation& p);

 private:
  const Scene& scene_;
  std::ostringstream& out_;
};

// scene_tables_apparatus.cpp: the scene's apparatus table, whichever kind
// of the registry (solver/apparatus/registry.h) it is, read into
// Scene::apparatus (Scene::apparatus_pending: place_scene builds its walls
// and specimen with the kind's `build`), and written back. Each kind's
// reader only reads; its writer writes the resolved values (the walls are
// rebuilt from them, the specimen is the explicit particles):
void read_apparatus(const Reader& root, Scene& scene);
void write_apparatus(TableWriter& out);
// True when `kind` (a registry name) has a table reader and writer here.
bool has_apparatus_reader(std::string_view kind);

void read_shear_box(const Reader& table, Scene& scene);  // scene_tables_shear_box.cpp
void write_shear_box(TableWriter& out);
void read_oedometer(const Reader& table, Scene& scene);  // scene_tables_oedometer.cpp
void write_oedometer(TableWriter& out);
void read_periodic_cell(const Reader& table, Scene& scene);  // scene_tables_periodic_cell.cpp
void write_periodic_cell(TableWriter& out);
void read_triaxial(const Reader& table, Scene& scene);   // scene_tables_triaxial.cpp
void write_triaxial(TableWriter& out);

// An apparatus table's wall_material (scene_tables_apparatus.cpp): the
// material it names, or `fallback` when it names none or the built-in
// "steel" (default_box_steel) that the scene does not define itself.
int read_wall_material(const Reader& table, const Scene& scene, int fallback);

// The [<apparatus>.specimen] sub-table of an apparatus table
// (scene_tables_specimen.cpp).
Specimen read_specimen(const Reader& apparatus, const Scene& scene);

// scene_tables_settings.cpp
void read_effects(const Reader& root, Scene& scene);   // [effects]
void read_numerics(const Reader& root, Scene& scene);  // [numerics]
void read_outputs(const Reader& root, Scene& scene);   // [output]
void read_view(const Reader& root, Scene& scene);      // [view]

}  // namespace simsols::scene_toml
