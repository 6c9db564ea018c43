// The lab's effect-slot controls: one choice per slot (scene.h, Effects),
// with the parameters of the chosen law. Changes go to the experiment's
// scene and take effect at the next Prepare / Reset, which rebuilds the
// kernels with the new -D options (the status line shows what is compiled).
#include <imgui.h>

#include <algorithm>
#include <cmath>

#include "app/lab/lab_app.h"
#include "solver/scene/choices.h"

namespace simsols {

namespace {

template <typename E>
bool slot_combo(const char* label, E& value, std::initializer_list<E> choices) {
  bool changed = false;
  ImGui::SetNextItemWidth(160);
  if (ImGui::BeginCombo(label, choice_name(value))) {
    for (E c : choices)
      if (ImGui::Selectable(choice_name(c), c == value)) value = c, changed = true;
    ImGui::EndCombo();
  }
  return changed;
}

bool input_double(const char* label, double& v, double lo, const char* fmt) {
  ImGui::SetNextItemWidth(160);
  double x = v;
  if (!ImGui::InputDouble(label, &x, 0, 0, fmt) || !(x >= lo) || !std::isfinite(x)) return false;
  v = x;
  return true;
}

}  // namespace

bool LabApp::draw_effect_slots() {
  Effects e = exp_->scene().effects;
  bool fx = false;
  bool gravity = e.gravity[2] != 0;
  fx |= slot_combo("damping", e.damping, {DampingModel::Viscous, DampingModel::None});
  fx |= slot_combo("tangential", e.tangential,
                   {TangentialModel::Mindlin, TangentialModel::MindlinDeresiewicz,
                    TangentialModel::None});
  fx |= slot_combo("rolling", e.rolling,
                   {RollingModel::ConstantTorque, RollingModel::SpringDashpot, RollingModel::None});
  if (e.rolling == RollingModel::SpringDashpot)
    fx |= input_double("rolling damping (eta_r)", e.rolling_damping, 0, "%.2f");
  fx |= slot_combo("cohesion", e.cohesion, {CohesionModel::None, CohesionModel::Capillary});
  if (e.cohesion == CohesionModel::Capillary) {
    if (e.capillary.liquid_volume <= 0) {  // a default: 1e-3 of a bead's volume
      double r = 1e-3;
      const Scene& sc = exp_->scene();  // read, maybe not placed yet
      if (!sc.particles.empty()) r = sc.particles[0].radius;
      else if (const Specimen* s = sc.specimen(); s && s->diameter > 0) r = s->diameter / 2;
      e.capillary.liquid_volume = 1e-3 * 4.18879 * r * r * r;
      fx = true;
    }
    fx |= input_double("liquid volume (m^3)", e.capillary.liquid_volume, 1e-30, "%.3g");
    fx |= input_double("surface tension (N/m)", e.capillary.surface_tension, 1e-9, "%.4g");
    fx |= input_double("contact angle (rad)", e.capillary.contact_angle, 0, "%.3f");
    e.capillary.contact_angle = std::min(e.capillary.contact_angle, 1.5);
  }
  fx |= slot_combo("fluid", e.fluid, {FluidModel::None, FluidModel::Drag});
  if (e.fluid == FluidModel::Drag) {
    fx |= input_double("fluid density (kg/m^3)", e.fluid_params.density, 0, "%.4g");
    fx |= input_double("fluid viscosity (Pa s)", e.fluid_params.viscosity, 1e-12, "%.4g");
  }
  fx |= ImGui::Checkbox("gravity", &gravity);
  if (fx) {
    e.gravity = gravity ? Vec3{0, 0, -9.81} : Vec3{0, 0, 0};
    exp_->set_effects(e);
  }
  return fx;
}

}  // namespace simsols
