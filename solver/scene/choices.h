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

#include "solver/scene/choice_table.h"
#include "solver/scene/grain_templates.h"
#include "solver/scene/scene.h"

namespace simsols {

// One table per enumeration of the scene (choices.cpp; an apparatus kind's
// own enumerations are declared with its description, apparatus/kinds.h).
template <> std::span<const Named<DampingModel>> choices();
template <> std::span<const Named<TangentialModel>> choices();
template <> std::span<const Named<RollingModel>> choices();
template <> std::span<const Named<CohesionModel>> choices();
template <> std::span<const Named<FluidModel>> choices();
template <> std::span<const Named<Precision>> choices();
template <> std::span<const Named<WallShape>> choices();
template <> std::span<const Named<Specimen::Method>> choices();
template <> std::span<const Named<Specimen::Clearance>> choices();
template <> std::span<const Named<Grading::Law>> choices();
template <> std::span<const Named<GrainForm>> choices();

}  // namespace simsols
