// The apparatus kinds a scene can hold, each described in its own header
// here: the Apparatus variant lists them in the registry's order
// (solver/apparatus/registry.h: a new kind is added there and here, with
// its description header in this folder). Apart from this list, the
// registry and each kind's folders, no source names a kind
// (tests/layout/check_kind_names.sh).
#pragma once

#include <variant>

#include "solver/scene/apparatus/oedometer.h"
#include "solver/scene/apparatus/periodic_cell.h"
#include "solver/scene/apparatus/shear_box.h"
#include "solver/scene/apparatus/triaxial.h"

namespace simsols {

// A scene's apparatus: none, or one of the kinds.
using Apparatus = std::variant<std::monostate, ShearBox, Oedometer, Triaxial, PeriodicCell>;

}  // namespace simsols
