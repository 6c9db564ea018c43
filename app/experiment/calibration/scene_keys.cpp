#include "app/experiment/calibration/scene_keys.h"

#include <toml++/toml.h>

#include <sstream>

#include "solver/common/errors.h"
#include "solver/io/scene_toml.h"

namespace simsols {

namespace {

std::vector<std::string> components(const std::string& key) {
  std::vector<std::string> out;
  std::string part;
  std::istringstream in(key);
  while (std::getline(in, part, '.')) out.push_back(part);
  return out;
}

// The entry of an array of tables whose `name` is `name`; nullptr when none.
toml::table* named_entry(toml::array& a, const std::string& name) {
  for (toml::node& e : a)
    if (toml::table* t = e.as_table(); t && t->get_as<std::string>("name") &&
                                        **t->get_as<std::string>("name") == name)
      return t;
  return nullptr;
}

void set_value(toml::table& doc, const SceneValue& v, const std::string& path) {
  const std::vector<std::string> parts = components(v.key);
  const auto missing = [&](const std::string& what) {
    throw SceneError("bad_key", path, 0, v.key, "the scene has no " + what + " for the key '" +
                                                     v.key + "' to be set in");
  };
  if (parts.empty() || parts.back().empty()) missing("key");
  toml::table* t = &doc;
  for (size_t i = 0; i + 1 < parts.size(); ++i) {
    toml::node* n = t->get(parts[i]);
    if (n && n->is_array() && i + 2 < parts.size()) {
      t = named_entry(*n->as_array(), parts[i + 1]);
      if (!t) missing("entry [[" + parts[i] + "]] named '" + parts[i + 1] + "'");
      ++i;
    } else if (n && n->is_table()) {
      t = n->as_table();
    } else {
      missing("table [" + parts[i] + "]");
    }
  }
  if (v.integer)
    t->insert_or_assign(parts.back(), static_cast<std::int64_t>(v.value));
  else
    t->insert_or_assign(parts.back(), v.value);
}

}  // namespace

toml::table parse_toml_file(const std::string& path) {
  try {
    return toml::parse_file(path);
  } catch (const toml::parse_error& e) {
    throw SceneError("toml_syntax", path, static_cast<int>(e.source().begin.line), "",
                     std::string(e.description()));
  }
}

std::string scene_text_with(const std::string& path, const std::vector<SceneValue>& values) {
  toml::table doc = parse_toml_file(path);
  for (const SceneValue& v : values) set_value(doc, v, path);
  std::ostringstream text;
  text << doc << '\n';
  return text.str();
}

std::vector<SceneValue> test_values(const KeyValues& first, const KeyValues& then,
                                    const char* seed_key, int seed) {
  std::vector<SceneValue> v;
  for (const KeyValues* kv : {&first, &then})
    for (const auto& [key, value] : *kv) v.push_back({key, value, false});
  if (seed > 0) v.push_back({seed_key, double(seed), true});
  return v;
}

Scene scene_with(const std::string& path, const std::vector<SceneValue>& values) {
  return read_scene_text(scene_text_with(path, values), path);
}

std::vector<std::string> set_material_values(
    Scene& scene, const std::vector<std::pair<std::string, double>>& values) {
  std::vector<std::string> not_set;
  for (const auto& [key, value] : values) {
    const std::vector<std::string> parts = components(key);
    const int m = parts.size() == 3 && parts[0] == "materials" ? scene.material_index(parts[1]) : -1;
    double* field = nullptr;
    if (m >= 0) {
      Material& mat = scene.materials[static_cast<size_t>(m)];
      const std::pair<const char*, double*> fields[] = {
          {"young_modulus", &mat.young_modulus}, {"poisson_ratio", &mat.poisson_ratio},
          {"density", &mat.density},             {"restitution", &mat.restitution},
          {"sliding_friction", &mat.sliding_friction},
          {"rolling_friction", &mat.rolling_friction}};
      for (const auto& [name, f] : fields)
        if (parts[2] == name) field = f;
    }
    if (field)
      *field = value;
    else
      not_set.push_back(key);
  }
  return not_set;
}

}  // namespace simsols
