// The CHOLMOD wrapper: solutions against Eigen's own sparse Cholesky, a factor that shares another's
// symbolic analysis, and an indefinite matrix reported instead of factored.
#include <gtest/gtest.h>

#include <Eigen/SparseCholesky>
#include <stdexcept>
#include <vector>

#include "solver/CholmodFactor.hpp"

namespace orthosim {
namespace {

// The 7-point Laplacian of an n^3 grid plus `shift` on the diagonal (lower triangle): the pattern a
// tetrahedral mesh's stiffness has, large enough that the ordering matters.
Eigen::SparseMatrix<double> gridLaplacian(int n, double shift) {
  const int N = n * n * n;
  auto id = [n](int i, int j, int k) { return (i * n + j) * n + k; };
  std::vector<Eigen::Triplet<double>> t;
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j)
      for (int k = 0; k < n; ++k) {
        const int a = id(i, j, k);
        t.emplace_back(a, a, 6.0 + shift);
        if (i + 1 < n) t.emplace_back(id(i + 1, j, k), a, -1.0);
        if (j + 1 < n) t.emplace_back(id(i, j + 1, k), a, -1.0);
        if (k + 1 < n) t.emplace_back(id(i, j, k + 1), a, -1.0);
      }
  Eigen::SparseMatrix<double> A(N, N);
  A.setFromTriplets(t.begin(), t.end());
  return A;
}

TEST(CholmodFactor, SolvesLikeEigensSparseCholesky) {
  const Eigen::SparseMatrix<double> A = gridLaplacian(12, 0.1);
  const Eigen::VectorXd b = Eigen::VectorXd::LinSpaced(A.rows(), -1.0, 2.0);
  CholmodFactor f;
  f.analyze(A);
  ASSERT_TRUE(f.factorize(A));
  Eigen::SimplicialLLT<Eigen::SparseMatrix<double>, Eigen::Lower> reference(A);
  ASSERT_EQ(reference.info(), Eigen::Success);
  const Eigen::VectorXd x = f.solve(b), y = reference.solve(b);
  EXPECT_LT((x - y).norm(), 1e-10 * y.norm());
  const Eigen::SparseMatrix<double> full = A.selfadjointView<Eigen::Lower>();
  EXPECT_LT((full * x - b).norm(), 1e-10 * b.norm());
  Eigen::MatrixXd B(A.rows(), 3);
  B << b, -2 * b, Eigen::VectorXd::Ones(A.rows());
  const Eigen::MatrixXd X = f.solveMany(B);  // several right-hand sides: each as if alone
  for (int k = 0; k < 3; ++k) EXPECT_LT((X.col(k) - f.solve(B.col(k))).norm(), 1e-12 * X.col(k).norm()) << k;
}

TEST(CholmodFactor, SharesTheSymbolicAnalysisOfAnotherFactor) {
  const Eigen::SparseMatrix<double> A = gridLaplacian(10, 0.1), B = gridLaplacian(10, 2.0);
  CholmodFactor first, second;
  EXPECT_THROW(second.analyzeLike(first), std::runtime_error);  // nothing to share yet
  first.analyze(A);
  ASSERT_TRUE(first.factorize(A));
  second.analyzeLike(first);
  EXPECT_FALSE(second.valid());
  ASSERT_TRUE(second.factorize(B));  // same pattern, other values
  const Eigen::VectorXd b = Eigen::VectorXd::Ones(A.rows());
  const Eigen::SparseMatrix<double> fullA = A.selfadjointView<Eigen::Lower>(),
                                    fullB = B.selfadjointView<Eigen::Lower>();
  EXPECT_LT((fullB * second.solve(b) - b).norm(), 1e-10 * b.norm());
  EXPECT_LT((fullA * first.solve(b) - b).norm(), 1e-10 * b.norm());  // the first factor is untouched
}

TEST(CholmodFactor, ReportsAnIndefiniteMatrixAndRefusesToSolveWithIt) {
  const Eigen::SparseMatrix<double> A = gridLaplacian(6, -7.0);  // eigenvalues -1 + (0, 12): some negative
  CholmodFactor f;
  f.analyze(A);
  EXPECT_FALSE(f.factorize(A));
  EXPECT_FALSE(f.valid());
  EXPECT_THROW(f.solve(Eigen::VectorXd::Ones(A.rows())), std::logic_error);
}

}  // namespace
}  // namespace orthosim
