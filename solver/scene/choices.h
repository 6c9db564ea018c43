// The enumerated choices of a scene, each name spelled once.
//
// A scene file, the lab's controls and script, and the command line all
// name the same choices ("viscous", "spring_dashpot", "float", "pour"):
// choices<E>() is the one table of an enumeration's names, in the order
// messages list them (the default first where the scene format has one).
// parse_choice() reads a name, choice_name() writes one and
// choice_names() lists the allowed ones for an error message, so a new
// model is one line here and every reader and writer knows it.
#pragma once

#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "solver/scene/grain_templates.h"
#include "solver/scene/scene.h"

namespace simsols {

template <class E>
struct Named {
  E value;
  const char* name;
};

// One table per enumeration (choices.cpp).
template <class E>
std::span<const Named<E>> choices();
template <> std::span<const Named<DampingModel>> choices();
template <> std::span<const Named<TangentialModel>> choices();
template <> std::span<const Named<RollingModel>> choices();
template <> std::span<const Named<CohesionModel>> choices();
template <> std::span<const Named<FluidModel>> choices();
template <> std::span<const Named<Precision>> choices();
template <> std::span<const Named<WallShape>> choices();
template <> std::span<const Named<ShearBox::Loading>> choices();
template <> std::span<const Named<Specimen::Method>> choices();
template <> std::span<const Named<Specimen::Clearance>> choices();
template <> std::span<const Named<Grading::Law>> choices();
template <> std::span<const Named<Triaxial::Path>> choices();
template <> std::span<const Named<GrainForm>> choices();

// The name of `value` ("?" for a value outside the table).
template <class E>
const char* choice_name(E value) {
  for (const Named<E>& c : choices<E>())
    if (c.value == value) return c.name;
  return "?";
}

// The value named `name`, or nullopt.
template <class E>
std::optional<E> parse_choice(std::string_view name) {
  for (const Named<E>& c : choices<E>())
    if (name == c.name) return c.value;
  return std::nullopt;
}

// Every allowed name, in the table's order.
template <class E>
std::vector<std::string> choice_names() {
  std::vector<std::string> names;
  for (const Named<E>& c : choices<E>()) names.emplace_back(c.name);
  return names;
}

}  // namespace simsols
