#include "app/experiment/calibration/surrogate.h"

#include <cmath>

namespace simsols {

namespace {

int quadratic_terms(int p) { return (p + 1) * (p + 2) / 2; }

}  // namespace

Eigen::VectorXd Surrogate::basis(const Eigen::VectorXd& u) const {
  Eigen::VectorXd b(terms_);
  int k = 0;
  b(k++) = 1;
  if (terms_ > 1)
    for (int i = 0; i < parameters_; ++i) b(k++) = u(i) - 0.5;
  if (terms_ > parameters_ + 1)
    for (int i = 0; i < parameters_; ++i)
      for (int j = i; j < parameters_; ++j) b(k++) = (u(i) - 0.5) * (u(j) - 0.5);
  return b;
}

Surrogate::Surrogate(const Eigen::MatrixXd& u, const Eigen::MatrixXd& y) {
  parameters_ = static_cast<int>(u.cols());
  const int n = static_cast<int>(u.rows());
  terms_ = n >= 2 * quadratic_terms(parameters_) ? quadratic_terms(parameters_)
           : n >= parameters_ + 2                 ? parameters_ + 1
                                                  : 1;
  coef_ = Eigen::MatrixXd::Zero(terms_, y.cols());
  loo_ = Eigen::VectorXd::Constant(y.cols(), NAN);
  Eigen::MatrixXd a(n, terms_);
  for (int r = 0; r < n; ++r) a.row(r) = basis(u.row(r).transpose()).transpose();
  for (int f = 0; f < y.cols(); ++f) {
    std::vector<int> rows;
    for (int r = 0; r < n; ++r)
      if (std::isfinite(y(r, f))) rows.push_back(r);
    const int m = static_cast<int>(rows.size());
    if (m < terms_) {  // too few simulations reached this point: no prediction
      coef_.col(f).setConstant(NAN);
      continue;
    }
    Eigen::MatrixXd af(m, terms_);
    Eigen::VectorXd yf(m);
    for (int i = 0; i < m; ++i) {
      af.row(i) = a.row(rows[i]);
      yf(i) = y(rows[i], f);
    }
    const Eigen::CompleteOrthogonalDecomposition<Eigen::MatrixXd> qr(af);
    coef_.col(f) = qr.solve(yf);
    if (m <= terms_) continue;  // an exact fit: no left-out error to say
    // PRESS: the left-out residual of row i is e_i / (1 - h_ii).
    const Eigen::MatrixXd hat = af * qr.pseudoInverse();
    const Eigen::VectorXd e = yf - af * coef_.col(f);
    double press = 0;
    for (int i = 0; i < m; ++i) {
      const double h = std::min(hat(i, i), 1 - 1e-9);
      press += std::pow(e(i) / (1 - h), 2);
    }
    loo_(f) = std::sqrt(press / m);
  }
}

Eigen::VectorXd Surrogate::predict(const Eigen::VectorXd& u) const {
  return coef_.transpose() * basis(u);
}

}  // namespace simsols
