#include "solver/scene/apparatus/triaxial.h"

namespace simsols {

// [triaxial] path
SIMSOLS_CHOICES(Triaxial::Path, {Triaxial::Path::ConstantSigma3, "constant_sigma3"},
                {Triaxial::Path::ConstantP, "constant_p"},
                {Triaxial::Path::TrueTriaxial, "true_triaxial"})

}  // namespace simsols
