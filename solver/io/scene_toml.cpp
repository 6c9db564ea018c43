// TOML scene files in: the document walked table by table (scene_tables.h),
// then the semantic checks (scene_check.h), every problem located by file,
// line and field. See scene_toml.h for the design.
#include "solver/io/scene_toml.h"

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "solver/apparatus/registry.h"
#include "solver/common/input_file.h"
#include "solver/io/scene_tables.h"

namespace simsols {
namespace {

using namespace scene_toml;

// The tables a scene may have: the fixed ones and one per apparatus kind.
std::vector<std::string> top_level_keys() {
  std::vector<std::string> keys = {"scene", "materials", "interactions", "particles", "generators",
                                   "grains", "clumps", "walls", "effects", "numerics", "output"};
  for (const ApparatusKind& k : apparatus_kinds()) keys.emplace_back(k.name);
  keys.emplace_back("view");
  return keys;
}

// Reads one document into a Scene.
class Loader {
 public:
  explicit Loader(const std::string& file) { ctx_.file = file; }

  Scene load(const toml::table& root) {
    root_ = &root;
    Reader r(root, "", ctx_, top_level_keys());
    read_info(r, scene_);
    read_materials(r, scene_);
    read_interactions(r, scene_);
    read_particles(r, scene_);
    explicit_particles_ = scene_.particles.size();
    generator_of_ = read_generators(r, scene_);
    read_clumps(r, scene_);
    read_walls(r, scene_);
    read_effects(r, scene_);  // before the apparatus: a pour rains under its gravity
    if (auto issue = one_apparatus(root)) fail(std::move(*issue));
    if (auto issue = read_apparatus(r, scene_)) fail(std::move(*issue));
    read_numerics(r, scene_);
    read_outputs(r, scene_);
    read_view(r, scene_);
    for (SceneIssue& issue : find_scene_issues(scene_)) note(std::move(issue));
    ctx_.throw_if_any();
    return std::move(scene_);
  }

 private:
  // Line of `field` in the document, or of its closest existing parent
  // ("walls[1]" for a defaulted "walls[1].velocity"); 0 when none.
  int line_for(std::string field) const {
    while (!field.empty()) {
      if (const toml::node* n = toml::at_path(*root_, field).node()) return line_of(n->source());
      const size_t cut = field.find_last_of(".[");
      if (cut == std::string::npos || cut == 0) break;
      field.resize(cut);
    }
    return 0;
  }

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

  // Issues about generated particles are reported at their generator.
  void note(SceneIssue issue) {
    size_t k = 0;
    if (std::sscanf(issue.field.c_str(), "particles[%zu]", &k) == 1 && k >= explicit_particles_) {
      if (k < scene_.particles.size() && scene_.particles[k].clump >= 0) {
        const Clump& c = scene_.clumps[scene_.particles[k].clump];
        issue.message = "member sphere " + std::to_string(k - c.first) + ": " + issue.message;
        issue.field = item("clumps", scene_.particles[k].clump);
      } else if (k - explicit_particles_ < generator_of_.size()) {
        issue.message = "generated particle " + std::to_string(k) + ": " + issue.message;
        issue.field = item("generators", generator_of_[k - explicit_particles_]);
      }
    }
    ctx_.note(issue.code, line_for(issue.field), issue.field, issue.message);
  }
  // The reading cannot go on: this issue and those noted before it.
  [[noreturn]] void fail(SceneIssue issue) {
    note(std::move(issue));
    throw SceneError(ctx_.file, ctx_.found);
  }

  Context ctx_;
  const toml::table* root_ = nullptr;
  Scene scene_;
  size_t explicit_particles_ = 0;
  std::vector<size_t> generator_of_;  // per generated particle
};

}  // namespace

Scene parse_scene(std::string_view text, const std::string& path_for_messages) {
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

Scene load_scene(const std::string& path) {
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
  return parse_scene(text.str(), path);
}

}  // namespace simsols
