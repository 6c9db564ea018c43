// The calibration's surrogate: each compared value (a curve's y at one
// comparison point) as a quadratic polynomial of the parameters, fitted by
// least squares to the simulations run so far.
//
// The parameters enter scaled to u in [0, 1] (calibration_spec.h). With P
// parameters a full quadratic has (P + 1)(P + 2)/2 terms; with fewer
// simulations than twice that, the fit drops to a linear one (P + 1
// terms), and with fewer than P + 2, to a constant. A response surface is
// the simplest surrogate that has a minimum inside the ranges; its
// leave-one-out error (the PRESS residual, from the hat matrix) says how
// well it follows the simulations, and enters the calibration's
// likelihood as the surrogate's own uncertainty.
#pragma once

#include <Eigen/Dense>

namespace simsols {

class Surrogate {
 public:
  // Rows of `u` are the simulations' scaled parameters (n x P); rows of
  // `y` their compared values (n x F). A NaN in y (a curve that did not
  // reach a point) leaves that simulation out of that value's fit.
  Surrogate(const Eigen::MatrixXd& u, const Eigen::MatrixXd& y);

  // F values; NaN for a value too few simulations reached to fit.
  Eigen::VectorXd predict(const Eigen::VectorXd& u) const;
  // Each value's leave-one-out r.m.s. error over the simulations (F).
  const Eigen::VectorXd& loo_error() const { return loo_; }
  int terms() const { return terms_; }

 private:
  Eigen::VectorXd basis(const Eigen::VectorXd& u) const;
  int parameters_ = 0, terms_ = 0;
  Eigen::MatrixXd coef_;  // terms x F
  Eigen::VectorXd loo_;
};

}  // namespace simsols
