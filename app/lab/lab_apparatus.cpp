#include "app/lab/lab_apparatus.h"

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

const char* to_string(LabApparatusKind k) {
  switch (k) {
    case LabApparatusKind::ShearBox: return "shear_box";
    case LabApparatusKind::Triaxial: return "triaxial";
    case LabApparatusKind::Oedometer: return "oedometer";
  }
  return "?";
}

std::optional<LabApparatusKind> parse_apparatus_kind(const std::string& name) {
  for (LabApparatusKind k :
       {LabApparatusKind::ShearBox, LabApparatusKind::Triaxial, LabApparatusKind::Oedometer})
    if (name == to_string(k)) return k;
  return std::nullopt;
}

std::optional<LabApparatusKind> apparatus_kind(const Scene& scene) {
  if (scene.shear_box) return LabApparatusKind::ShearBox;
  if (scene.triaxial) return LabApparatusKind::Triaxial;
  if (scene.oedometer) return LabApparatusKind::Oedometer;
  return std::nullopt;
}

std::unique_ptr<LabApparatus> make_lab_apparatus(Simulation& sim) {
  const std::optional<LabApparatusKind> kind = apparatus_kind(sim.scene());
  if (!kind) return nullptr;
  switch (*kind) {
    case LabApparatusKind::ShearBox: return make_lab_shear_box(sim);
    case LabApparatusKind::Triaxial: return make_lab_triaxial(sim);
    case LabApparatusKind::Oedometer: return make_lab_oedometer(sim);
  }
  return nullptr;
}

std::string unknown_setting(const LabApparatus& a, const std::string& key) {
  std::string list;
  for (const LabSetting& s : a.settings())
    list += (list.empty() ? "" : ", ") + s.key + " (" + s.unit + ")";
  return std::string("the ") + to_string(a.kind()) + " has no setting '" + key + "'" +
         (list.empty() ? "; it has no live settings" : "; its settings: " + list);
}

}  // namespace simsols
