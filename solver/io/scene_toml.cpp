// TOML scene files in: the document walked table by table (scene_tables.h),
// then the semantic checks (scene_check.h); placing what it describes
// (generators, the apparatus); every problem located by file, line and
// field. See scene_toml.h for the design.
#include "solver/io/scene_toml.h"

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "solver/apparatus/registry.h"
#include "solver/common/input_file.h"
#include "solver/io/scene_tables.h"
#include "solver/scene/generators.h"

namespace simsols {
namespace {

using namespace scene_toml;

// The tables a scene may have: the fixed ones and one per apparatus kind.
std::vector<std::string> top_level_keys() {
  std::vector<std::string> keys = {"scene", "materials", "interactions", "particles", "generators",
                                   "grains", "clumps", "walls", "membrane", "effects", "numerics", "output"};
  for (const ApparatusKind& k : apparatus_kinds()) keys.emplace_back(k.name);
  keys.emplace_back("view");
  return keys;
}

// The line of `field` in the document, or of its closest existing parent
// ("walls[1]" for a defaulted "walls[1].velocity"); 0 when none.
int line_for(const toml::table* root, std::string field) {
  while (root && !field.empty()) {
    if (const toml::node* n = toml::at_path(*root, field).node()) return line_of(n->source());
    const size_t cut = field.find_last_of(".[");
    if (cut == std::string::npos || cut == 0) break;
    field.resize(cut);
  }
  return 0;
}

// Issues about generated spheres and clump members are reported at the
// generator or clump that made them, each at its line in the document.
class Locator {
 public:
  Locator(const toml::table* root, Context& ctx) : root_(root), ctx_(ctx) {}
  // The generated spheres: particles [first, first + generator_of.size()).
  void generated(size_t first, std::vector<size_t> generator_of) {
    first_generated_ = first;
    generator_of_ = std::move(generator_of);
  }

  void note(const Scene& scene, SceneIssue issue) {
    size_t k = 0;
    if (std::sscanf(issue.field.c_str(), "particles[%zu]", &k) == 1 && k < scene.particles.size()) {
      if (scene.particles[k].clump >= 0) {
        const Clump& c = scene.clumps[scene.particles[k].clump];
        issue.message = "member sphere " + std::to_string(k - c.first) + ": " + issue.message;
        issue.field = item("clumps", scene.particles[k].clump);
      } else if (k >= first_generated_ && k - first_generated_ < generator_of_.size()) {
        issue.message = "generated particle " + std::to_string(k) + ": " + issue.message;
        issue.field = item("generators", generator_of_[k - first_generated_]);
      }
    }
    ctx_.note(issue.code, line_for(root_, issue.field), issue.field, issue.message);
  }

 private:
  const toml::table* root_;
  Context& ctx_;
  size_t first_generated_ = 0;
  std::vector<size_t> generator_of_;
};

// Reads one document into a Scene: only reads (place_scene places).
class Loader {
 public:
  explicit Loader(const std::string& file) { ctx_.file = file; }

  Scene load(const toml::table& root) {
    Locator where(&root, ctx_);
    Reader r(root, "", ctx_, top_level_keys());
    read_info(r, scene_);
    read_materials(r, scene_);
    read_interactions(r, scene_);
    read_particles(r, scene_);
    read_generators(r, scene_);
    read_clumps(r, scene_);
    read_walls(r, scene_);
    read_membrane(r, scene_);
    read_effects(r, scene_);
    if (auto issue = one_apparatus(root)) {
      where.note(scene_, std::move(*issue));
      ctx_.throw_if_any();
    }
    read_apparatus(r, scene_);
    read_numerics(r, scene_);
    read_outputs(r, scene_);
    read_view(r, scene_);
    for (SceneIssue& issue : find_scene_issues(scene_)) where.note(scene_, std::move(issue));
    ctx_.throw_if_any();
    return std::move(scene_);
  }

 private:
  // At most one apparatus table (registry.h), whatever their order: the
  // second found in the registry's order is the one at fault.
  static std::optional<SceneIssue> one_apparatus(const toml::table& root) {
    const char* first = nullptr;
    for (const ApparatusKind& k : apparatus_kinds()) {
      if (!root.contains(k.name)) continue;
      if (first)
        return SceneIssue{"conflicting_keys", k.name,
                          std::string("a scene holds one apparatus: [") + first + "] and [" +
                              k.name + "] are both given"};
      first = k.name;
    }
    return std::nullopt;
  }

  Context ctx_;
  Scene scene_;
};

// The issues of placing `scene`: the generators' and the apparatus' own,
// else the semantic checks of the whole.
// `generator_of` and `first` tell which particles the generators made.
std::vector<SceneIssue> placement_issues(Scene& scene, std::vector<size_t>& generator_of,
                                         size_t& first) {
  if (auto issue = expand_generators(scene, &generator_of, &first)) return {std::move(*issue)};
  if (scene.apparatus_pending) {
    scene.apparatus_pending = false;
    if (auto issue = required_apparatus_kind(scene).build(scene)) return {std::move(*issue)};
  }
  return find_scene_issues(scene);
}

}  // namespace

Scene read_scene_text(std::string_view text, const std::string& path_for_messages) {
  toml::table root;
  try {
    root = toml::parse(text, path_for_messages);
  } catch (const toml::parse_error& e) {
    throw SceneError("syntax", path_for_messages, line_of(e.source()), "",
                     "TOML syntax error: " + std::string(e.description()));
  }
  Scene scene = Loader(path_for_messages).load(root);
  scene.source_path = path_for_messages;
  scene.source_text = std::string(text);
  return scene;
}

void place_scene(Scene& scene) {
  if (scene.placed()) return;
  // placed in a copy (a read scene holds few spheres), so one that cannot
  // be placed is left as it was read
  Scene placed = scene;
  std::vector<size_t> generator_of;
  size_t first = 0;
  std::vector<SceneIssue> issues = placement_issues(placed, generator_of, first);
  if (issues.empty()) {
    scene = std::move(placed);
    return;
  }
  // the document again, only to point at lines (it was read without error)
  std::optional<toml::table> root;
  if (!scene.source_text.empty()) {
    try {
      root = toml::parse(scene.source_text, scene.source_path);
    } catch (const toml::parse_error&) {
      root.reset();
    }
  }
  Context ctx;
  ctx.file = scene.source_path.empty() ? scene.name : scene.source_path;
  Locator where(root ? &*root : nullptr, ctx);
  where.generated(first, std::move(generator_of));
  for (SceneIssue& issue : issues) where.note(placed, std::move(issue));
  ctx.throw_if_any();
}

Scene parse_scene(std::string_view text, const std::string& path_for_messages) {
  Scene scene = read_scene_text(text, path_for_messages);
  place_scene(scene);
  return scene;
}

Scene read_scene(const std::string& path) {
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec))
    throw SceneError("io", path, 0, "",
                     "cannot read the scene: no such file (or not a regular file)");
  if (require_scene_or_checkpoint(path, "a scene (TOML)") == InputKind::Checkpoint)
    throw SceneError("not_a_scene", path, 0, "",
                     "a SimSols checkpoint, not a scene: resume it with 'simsols run --resume "
                     "--out DIR' (DIR holding it as checkpoint.bin) or draw it with 'simsols "
                     "snapshot'");
  std::ifstream in(path, std::ios::binary);
  std::ostringstream text;
  if (in) text << in.rdbuf();
  if (!in || in.bad()) throw SceneError("io", path, 0, "", "cannot read the scene file");
  return read_scene_text(text.str(), path);
}

Scene load_scene(const std::string& path) {
  Scene scene = read_scene(path);
  place_scene(scene);
  return scene;
}

}  // namespace simsols
