// The apparatus table of a scene: which reader reads it (scene_tables.h);
// place_scene builds it afterwards with the registry's `build`.
#include <stdexcept>
#include <string_view>

#include "solver/apparatus/cell/cell_walls.h"
#include "solver/apparatus/registry.h"
#include "solver/io/scene_tables.h"

namespace simsols::scene_toml {
namespace {

struct ApparatusReader {
  std::string_view kind;  // the registry's name, the table's name
  void (*read)(const Reader& root, Scene& scene);
  void (*write)(TableWriter& out);
};

constexpr ApparatusReader kReaders[] = {
    {"shear_box", read_shear_box, write_shear_box},
    {"oedometer", read_oedometer, write_oedometer},
    {"triaxial", read_triaxial, write_triaxial},
    {"periodic_cell", read_periodic_cell, write_periodic_cell},
};

const ApparatusReader* reader_of(std::string_view kind) {
  return entry_for_kind<ApparatusReader>(kReaders, kind);
}

}  // namespace

bool has_apparatus_reader(std::string_view kind) { return reader_of(kind) != nullptr; }

int read_wall_material(const Reader& table, const Scene& scene, int fallback) {
  if (!table.has("wall_material")) return fallback;
  const std::string name = table.string("wall_material");
  if (name == "steel" && scene.material_index(name) < 0) return fallback;
  return table.material("wall_material", scene);
}

void read_apparatus(const Reader& root, Scene& scene) {
  for (const ApparatusKind& kind : apparatus_kinds()) {
    if (!root.has(kind.name)) continue;
    const ApparatusReader* reader = reader_of(kind.name);
    if (!reader)
      root.fail("unsupported", kind.name,
                std::string("no table reader for the apparatus '") + kind.name + "'");
    reader->read(root, scene);
    // the built-in steel is a material of the scene from the start (what
    // the kernels compile depends on it), as in the file's order
    if (ApparatusCell* cell = scene.cell()) resolve_wall_material(scene, cell->wall_material);
    scene.apparatus_pending = true;
    return;
  }
}

void write_apparatus(TableWriter& out) {
  const ApparatusKind* kind = apparatus_kind(out.scene());
  if (!kind) return;
  const ApparatusReader* table = reader_of(kind->name);
  if (!table) throw std::logic_error(std::string("no table writer for the apparatus ") + kind->name);
  table->write(out);
}

}  // namespace simsols::scene_toml
