#pragma once
// Supernodal Cholesky of the reduced Newton matrix with CHOLMOD: the symbolic analysis (ordering,
// supernodes) is done once per model, the numeric factorisation once per Newton iteration.
#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <cstddef>
#include <memory>

namespace orthosim {

class CholmodFactor {
 public:
  CholmodFactor();
  ~CholmodFactor();
  CholmodFactor(const CholmodFactor&) = delete;
  CholmodFactor& operator=(const CholmodFactor&) = delete;

  // Symbolic analysis of the lower triangle `lower`; its pattern must not change afterwards.
  void analyze(const Eigen::SparseMatrix<double>& lower);
  // The symbolic analysis of `other` (analysed already), for a matrix of the same pattern: saves
  // analysing it again.
  void analyzeLike(const CholmodFactor& other);
  // Numeric factorisation; false when the matrix is not positive definite.
  bool factorize(const Eigen::SparseMatrix<double>& lower);
  Eigen::VectorXd solve(const Eigen::VectorXd& rhs) const;
  // Several right-hand sides at once (one pass over the factor: far faster than column by column).
  Eigen::MatrixXd solveMany(const Eigen::MatrixXd& rhs) const;
  bool valid() const { return factored_; }
  // Numeric entries of the factor L, known from the analysis on: what a factorisation of this
  // pattern holds (for memory estimates); 0 before the analysis.
  std::size_t entries() const;
  void invalidate() { factored_ = false; }

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
  bool factored_ = false;
};

}  // namespace orthosim
