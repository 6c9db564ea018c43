#include "solver/scene/apparatus/triaxial.h"

namespace simsols {

// [triaxial] path
SIMSOLS_CHOICES(Triaxial::Path, {Triaxial::Path::ConstantSigma3, "constant_sigma3"},
                {Triaxial::Path::ConstantP, "constant_p"},
                {Triaxial::Path::TrueTriaxial, "true_triaxial"})

// [triaxial] cell
SIMSOLS_CHOICES(Triaxial::Cell, {Triaxial::Cell::Rigid, "rigid"},
                {Triaxial::Cell::Membrane, "membrane"})

}  // namespace simsols
