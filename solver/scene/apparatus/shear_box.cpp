#include "solver/scene/apparatus/shear_box.h"

namespace simsols {

// [shear_box] loading
SIMSOLS_CHOICES(ShearBox::Loading, {ShearBox::Loading::DeadWeight, "dead_weight"},
                {ShearBox::Loading::Servo, "servo"})

// [shear_box] upper_half
SIMSOLS_CHOICES(ShearBox::UpperHalf, {ShearBox::UpperHalf::Fixed, "fixed"},
                {ShearBox::UpperHalf::Floating, "floating"})

// [shear_box] cap
SIMSOLS_CHOICES(ShearBox::Cap, {ShearBox::Cap::Held, "held"}, {ShearBox::Cap::Tilting, "tilting"})

}  // namespace simsols
