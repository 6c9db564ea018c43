#include "app/lab/lab_apparatus.h"

#include "app/experiment/default_scenes.h"
#include "solver/apparatus/registry.h"

namespace simsols {

const char* to_string(LabStage s) {
  switch (s) {
    case LabStage::Empty: return "no specimen";
    case LabStage::Building: return "building the specimen";
    case LabStage::Prepared: return "specimen prepared";
    case LabStage::Loading: return "loading";
    case LabStage::Loaded: return "loaded";
    case LabStage::Running: return "running";
    case LabStage::Done: return "done";
  }
  return "?";
}

namespace {

// In the registry's order, at most one bench per kind (tests/app/lab/test_lab_benches.cpp).
const LabBench kBenches[] = {
    {"shear_box", "shear box", make_lab_shear_box, nullptr, nullptr},
    {"oedometer", "oedometer", make_lab_oedometer, default_oedometer_scene_text,
     kDefaultOedometerSceneName},
    {"triaxial", "triaxial", make_lab_triaxial, default_triaxial_scene_text,
     kDefaultTriaxialSceneName},
    {"periodic_cell", "periodic cell", make_lab_periodic_cell, default_cell_scene_text,
     kDefaultCellSceneName},
};

}  // namespace

std::span<const LabBench> lab_benches() { return kBenches; }

int lab_bench_index(std::string_view kind) {
  const LabBench* bench = entry_for_kind<LabBench>(kBenches, kind);
  return bench ? static_cast<int>(bench - kBenches) : -1;
}

int lab_bench_index(const Scene& scene) {
  const ApparatusKind* kind = apparatus_kind(scene);
  return kind ? lab_bench_index(kind->name) : -1;
}

std::string lab_kind_names() {
  std::string out;
  for (const LabBench& b : kBenches) out += (out.empty() ? "" : "|") + std::string(b.kind);
  return out;
}

std::unique_ptr<LabApparatus> make_lab_apparatus(Simulation& sim) {
  const int i = lab_bench_index(sim.scene());
  return i < 0 ? nullptr : kBenches[i].make(sim);
}

std::string LabApparatus::choose(const std::string& key, const std::string&, Scene& scene) {
  std::string list;
  for (const LabChoice& c : choices(scene)) {
    list += (list.empty() ? "" : ", ") + c.key + " (";
    for (size_t i = 0; i < c.options.size(); ++i) list += (i ? "|" : "") + c.options[i];
    list += ")";
  }
  return std::string("the ") + kind() + " has no choice '" + key + "'" +
         (list.empty() ? "; it has none" : "; its choices: " + list);
}

std::string unknown_setting(const LabApparatus& a, const std::string& key) {
  std::string list;
  for (const LabSetting& s : a.settings())
    list += (list.empty() ? "" : ", ") + s.key + " (" + s.unit + ")";
  return std::string("the ") + a.kind() + " has no setting '" + key + "'" +
         (list.empty() ? "; it has no live settings" : "; its settings: " + list);
}

}  // namespace simsols
