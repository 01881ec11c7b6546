#include "solver/CholmodFactor.hpp"

#include <Eigen/CholmodSupport>
#include <stdexcept>

namespace orthosim {

struct CholmodFactor::Impl {
  Eigen::CholmodSupernodalLLT<Eigen::SparseMatrix<double>, Eigen::Lower> llt;
};

CholmodFactor::CholmodFactor() : impl_(std::make_unique<Impl>()) {
  // An indefinite matrix is an expected outcome (the solver then projects); report it, don't print.
  impl_->llt.cholmod().print = 0;
}
CholmodFactor::~CholmodFactor() = default;

void CholmodFactor::analyze(const Eigen::SparseMatrix<double>& lower) {
  impl_->llt.analyzePattern(lower);
  if (impl_->llt.info() != Eigen::Success) throw std::runtime_error("CHOLMOD symbolic analysis failed");
  factored_ = false;
}

bool CholmodFactor::factorize(const Eigen::SparseMatrix<double>& lower) {
  impl_->llt.factorize(lower);
  factored_ = impl_->llt.info() == Eigen::Success;
  return factored_;
}

Eigen::VectorXd CholmodFactor::solve(const Eigen::VectorXd& rhs) const {
  if (!factored_) throw std::logic_error("CholmodFactor::solve without a valid factorisation");
  return impl_->llt.solve(rhs);
}

}  // namespace orthosim
