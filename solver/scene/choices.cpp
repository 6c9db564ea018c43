#include "solver/scene/choices.h"

namespace simsols {

// [effects] slots: the default model first, then the others, "none" last
// where "none" is not the default.
SIMSOLS_CHOICES(DampingModel, {DampingModel::Viscous, "viscous"}, {DampingModel::None, "none"})
SIMSOLS_CHOICES(TangentialModel, {TangentialModel::Mindlin, "mindlin"},
                {TangentialModel::MindlinDeresiewicz, "mindlin_deresiewicz"},
                {TangentialModel::None, "none"})
SIMSOLS_CHOICES(RollingModel, {RollingModel::ConstantTorque, "constant_torque"},
                {RollingModel::SpringDashpot, "spring_dashpot"}, {RollingModel::None, "none"})
SIMSOLS_CHOICES(CohesionModel, {CohesionModel::None, "none"}, {CohesionModel::Capillary, "capillary"})
SIMSOLS_CHOICES(FluidModel, {FluidModel::None, "none"}, {FluidModel::Drag, "drag"})
// [numerics] precision, [[walls]] type
SIMSOLS_CHOICES(Precision, {Precision::Float, "float"}, {Precision::Double, "double"})
SIMSOLS_CHOICES(WallShape, {WallShape::Plane, "plane"}, {WallShape::Rectangle, "rectangle"})
// [<apparatus>.specimen] method and clearance
SIMSOLS_CHOICES(Specimen::Method, {Specimen::Method::Layers, "layers"},
                {Specimen::Method::Pour, "pour"}, {Specimen::Method::Given, "given"})
SIMSOLS_CHOICES(Specimen::Clearance, {Specimen::Clearance::Shift, "shift"},
                {Specimen::Clearance::Spread, "spread"})
// [*.specimen.grading] law
SIMSOLS_CHOICES(Grading::Law, {Grading::Law::Single, "single"}, {Grading::Law::Uniform, "uniform"},
                {Grading::Law::LogNormal, "lognormal"}, {Grading::Law::Fuller, "fuller"},
                {Grading::Law::Sieve, "sieve"})

// [[grains]] shape
SIMSOLS_CHOICES(GrainForm, {GrainForm::Elongated, "elongated"}, {GrainForm::Flat, "flat"},
                {GrainForm::Tetrahedral, "tetrahedral"}, {GrainForm::Sand, "sand"})

}  // namespace simsols
