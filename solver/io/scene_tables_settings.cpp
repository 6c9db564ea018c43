// [effects], [numerics], [output], [view]: how a scene is simulated and
// shown (docs/scene-format.md).
#include "solver/io/scene_tables.h"

namespace simsols::scene_toml {

namespace {

void legacy_pair(const Reader& r, const char* key, const char* legacy) {
  if (r.has(key) && r.has(legacy))
    r.fail("conflicting_keys", legacy,
           std::string("give either ") + key + " or the older " + legacy + ", not both");
}

}  // namespace

// [effects]: one named choice per slot (docs/scene-format.md). The older
// boolean keys (damping = true, tangential_friction, rolling_friction)
// are still read: true keeps the default model, false means "none".
void read_effects(const Reader& root, Scene& scene) {
  Reader r = root.sub("effects", {"gravity", "normal", "damping", "tangential", "rolling",
                                  "rolling_damping", "cohesion", "capillary", "fluid", "drag",
                                  "tangential_friction", "rolling_friction"});
  Effects& e = scene.effects;
  e.gravity = r.vec3("gravity", e.gravity);
  r.choice("normal", "hertz", {"hertz"});
  if (r.is_boolean("damping"))
    e.damping = r.boolean("damping", true) ? DampingModel::Viscous : DampingModel::None;
  else
    e.damping = r.choice("damping", DampingModel::Viscous);
  legacy_pair(r, "tangential", "tangential_friction");
  legacy_pair(r, "rolling", "rolling_friction");
  if (r.has("tangential_friction"))
    e.tangential =
        r.boolean("tangential_friction", true) ? TangentialModel::Mindlin : TangentialModel::None;
  else
    e.tangential = r.choice("tangential", TangentialModel::Mindlin);
  if (r.has("rolling_friction")) {
    e.rolling =
        r.boolean("rolling_friction", true) ? RollingModel::ConstantTorque : RollingModel::None;
  } else {
    e.rolling = r.choice("rolling", RollingModel::ConstantTorque);
  }
  if (e.rolling != RollingModel::SpringDashpot)
    r.forbid({"rolling_damping"}, "only allowed when rolling = \"spring_dashpot\"");
  e.rolling_damping = r.number("rolling_damping", e.rolling_damping);

  e.cohesion = r.choice("cohesion", CohesionModel::None);
  if (e.cohesion == CohesionModel::Capillary) {
    Reader c = r.sub("capillary", {"surface_tension", "contact_angle", "liquid_volume"});
    e.capillary.surface_tension = c.number("surface_tension", e.capillary.surface_tension);
    e.capillary.contact_angle = c.number("contact_angle", e.capillary.contact_angle);
    e.capillary.liquid_volume = c.number("liquid_volume");
  } else {
    r.forbid({"capillary"}, "only allowed when cohesion = \"capillary\"");
  }

  e.fluid = r.choice("fluid", FluidModel::None);
  if (e.fluid == FluidModel::Drag) {
    Reader f = r.sub("drag", {"density", "viscosity", "velocity"});
    e.fluid_params.density = f.number("density");
    e.fluid_params.viscosity = f.number("viscosity");
    e.fluid_params.velocity = f.vec3("velocity", {});
  } else {
    r.forbid({"drag"}, "only allowed when fluid = \"drag\"");
  }
}

void read_numerics(const Reader& root, Scene& scene) {
  Reader r = root.sub("numerics", {"precision", "dt", "dt_fraction", "force_dt", "duration", "skin",
                                   "neighbor_capacity"});
  Numerics& n = scene.numerics;
  n.precision = r.choice("precision", Precision::Double);
  n.dt = r.number("dt", n.dt);
  n.dt_fraction = r.number("dt_fraction", n.dt_fraction);
  n.force_dt = r.boolean("force_dt", n.force_dt);
  n.duration = r.number("duration");
  n.skin = r.number("skin", n.skin);
  const std::int64_t capacity = r.optional_integer("neighbor_capacity").value_or(0);
  if (capacity < 0 || capacity > 1'000'000)
    r.fail("out_of_range", "neighbor_capacity",
           std::to_string(capacity) + " is out of range, allowed 0 (automatic) or [4, 256]");
  n.neighbor_capacity = static_cast<int>(capacity);
}

void read_outputs(const Reader& root, Scene& scene) {
  Reader r = root.sub("output", {"series_interval", "dump_interval", "checkpoint_interval",
                                 "dump_csv", "dump_vtk"});
  Outputs& o = scene.outputs;
  o.series_interval = r.number("series_interval", o.series_interval);
  o.dump_interval = r.number("dump_interval", o.dump_interval);
  o.checkpoint_interval = r.number("checkpoint_interval", o.checkpoint_interval);
  o.dump_csv = r.boolean("dump_csv", o.dump_csv);
  o.dump_vtk = r.boolean("dump_vtk", o.dump_vtk);
}

void read_view(const Reader& root, Scene& scene) {
  Reader r = root.sub("view", {"view", "color_by", "mode", "size", "chains", "threshold"});
  ViewHints& v = scene.view;
  v.view = r.string("view", "");
  v.color_by = r.string("color_by", "");
  v.mode = r.string("mode", "");
  v.size = r.string("size", "");
  if (r.has("chains")) v.chains = r.boolean("chains", false);
  v.threshold = r.optional_number("threshold");
}

}  // namespace simsols::scene_toml
