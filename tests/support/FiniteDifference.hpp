#pragma once
// Derivatives against central differences, (f(x + h e_j) - f(x - h e_j)) / 2h, for every test
// that checks a gradient against a value or a Jacobian (a Hessian) against a gradient. Each check
// is an AssertionResult: EXPECT_TRUE(gradientMatchesValue(...)) fails with the point's name, the
// entry, both numbers and the tolerance.
#include <gtest/gtest.h>

#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <functional>
#include <random>
#include <sstream>
#include <string>
#include <vector>

namespace orthosim::test {

using ValueFunction = std::function<double(const Eigen::VectorXd&)>;
using VectorFunction = std::function<Eigen::VectorXd(const Eigen::VectorXd&)>;
using MatrixFunction = std::function<Eigen::MatrixXd(const Eigen::VectorXd&)>;

// An entry passes when |analytic - difference| <= absolute + relative |difference|.
struct FdTolerance {
  double relative = 1e-6;
  double absolute = 0.0;
};

// Where and how to difference: the step h, which unknowns to move (all when empty), and the name
// the failure message gives the point.
struct FdPoint {
  std::string name;
  Eigen::VectorXd x;
  double h = 1e-6;
  std::vector<int> unknowns;
};

namespace detail {

class Mismatches {
 public:
  Mismatches(const FdPoint& p, FdTolerance tol) : point_(p), tol_(tol) {}
  void check(double analytic, double difference, const std::string& entry) {
    const double bound = tol_.absolute + tol_.relative * std::abs(difference);
    if (std::abs(analytic - difference) <= bound) return;  // NaN fails
    if (++count_ <= 5)
      text_ << "\n  at " << point_.name << ", " << entry << ": analytic " << analytic << ", central difference "
            << difference << ", off by " << std::abs(analytic - difference) << " > " << bound;
  }
  ::testing::AssertionResult result() const {
    if (count_ == 0) return ::testing::AssertionSuccess();
    return ::testing::AssertionFailure() << count_ << " entries differ from central differences (h = " << point_.h
                                         << ")" << text_.str();
  }

 private:
  const FdPoint& point_;
  FdTolerance tol_;
  int count_ = 0;
  std::ostringstream text_;
};

inline std::vector<int> unknownsOf(const FdPoint& p) {
  if (!p.unknowns.empty()) return p.unknowns;
  std::vector<int> all(p.x.size());
  for (int j = 0; j < static_cast<int>(all.size()); ++j) all[j] = j;
  return all;
}

}  // namespace detail

// gradient(x)[j] against the central difference of value in unknown j, for the unknowns of p.
inline ::testing::AssertionResult gradientMatchesValue(const ValueFunction& value, const VectorFunction& gradient,
                                                       const FdPoint& p, FdTolerance tol) {
  detail::Mismatches m(p, tol);
  const Eigen::VectorXd g = gradient(p.x);
  for (int j : detail::unknownsOf(p)) {
    Eigen::VectorXd plus = p.x, minus = p.x;
    plus[j] += p.h;
    minus[j] -= p.h;
    m.check(g[j], (value(plus) - value(minus)) / (2 * p.h), "entry " + std::to_string(j));
  }
  return m.result();
}

// jacobian(x)(i, j) against the central difference of f_i in unknown j: a Hessian against its
// gradient, a stress derivative against its stress. Every row i, the unknowns j of p.
inline ::testing::AssertionResult jacobianMatchesFunction(const VectorFunction& f, const MatrixFunction& jacobian,
                                                          const FdPoint& p, FdTolerance tol) {
  detail::Mismatches m(p, tol);
  const Eigen::MatrixXd J = jacobian(p.x);
  for (int j : detail::unknownsOf(p)) {
    Eigen::VectorXd plus = p.x, minus = p.x;
    plus[j] += p.h;
    minus[j] -= p.h;
    const Eigen::VectorXd column = (f(plus) - f(minus)) / (2 * p.h);
    for (int i = 0; i < column.size(); ++i)
      m.check(J(i, j), column[i], "entry (" + std::to_string(i) + ", " + std::to_string(j) + ")");
  }
  return m.result();
}

// `count` points about `base`, each unknown moved uniformly in [-spread, spread]; named
// "<name> sample k".
inline std::vector<FdPoint> perturbedPoints(const std::string& name, const Eigen::VectorXd& base, int count,
                                            double spread, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-spread, spread);
  std::vector<FdPoint> points;
  for (int k = 0; k < count; ++k) {
    FdPoint p{name + " sample " + std::to_string(k), base};
    for (int i = 0; i < p.x.size(); ++i) p.x[i] += u(rng);
    points.push_back(std::move(p));
  }
  return points;
}

}  // namespace orthosim::test
