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
// [[grains]] and [[clumps]]: each clump's member spheres appended to the
// particles (solver/scene/clump.h).
void read_clumps(const Reader& root, Scene& scene);

// scene_tables_generators.cpp: [[generators]], into Scene::generators
// (placed by place_scene, scene_toml.h).
void read_generators(const Reader& root, Scene& scene);

// scene_tables_apparatus.cpp: the scene's apparatus table, whichever kind
// of the registry (solver/apparatus/registry.h) it is, read into
// Scene::apparatus (Scene::apparatus_pending: place_scene builds its walls
// and specimen with the kind's `build`). Each kind's reader only reads:
void read_apparatus(const Reader& root, Scene& scene);
// True when `kind` (a registry name) has a table reader here.
bool has_apparatus_reader(std::string_view kind);

void read_shear_box(const Reader& table, Scene& scene);  // scene_tables_shear_box.cpp
void read_oedometer(const Reader& table, Scene& scene);  // scene_tables_oedometer.cpp
void read_triaxial(const Reader& table, Scene& scene);   // scene_tables_triaxial.cpp

// The [<apparatus>.specimen] sub-table of an apparatus table
// (scene_tables_specimen.cpp).
Specimen read_specimen(const Reader& apparatus, const Scene& scene);

// scene_tables_settings.cpp
void read_effects(const Reader& root, Scene& scene);   // [effects]
void read_numerics(const Reader& root, Scene& scene);  // [numerics]
void read_outputs(const Reader& root, Scene& scene);   // [output]
void read_view(const Reader& root, Scene& scene);      // [view]

}  // namespace simsols::scene_toml
