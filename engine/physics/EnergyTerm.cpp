#include "physics/EnergyTerm.hpp"

namespace orthosim {
namespace {

// Collects blocks as triplets of the full matrix; duplicates sum when the matrix is built.
class TripletSink : public HessianSink {
 public:
  void add(const int* nodes, int count, const Eigen::Ref<const Eigen::MatrixXd>& block) override {
    for (int a = 0; a < count; ++a)
      for (int b = 0; b < count; ++b)
        for (int i = 0; i < 3; ++i)
          for (int j = 0; j < 3; ++j)
            triplets.emplace_back(3 * nodes[a] + i, 3 * nodes[b] + j, block(3 * a + i, 3 * b + j));
  }
  std::vector<Eigen::Triplet<double>> triplets;
};

}  // namespace

double EnergyTerm::maxStep(const EnergyState&, const Eigen::Matrix3Xd&) const { return 1.0; }

Eigen::Matrix3Xd gradientOf(const EnergyTerm& term, const EnergyState& s) {
  Eigen::Matrix3Xd g = Eigen::Matrix3Xd::Zero(3, s.x.cols());
  term.addGradient(s, g);
  return g;
}

Eigen::SparseMatrix<double> hessianOf(const EnergyTerm& term, const EnergyState& s, bool projectToPSD) {
  TripletSink sink;
  term.addHessian(s, projectToPSD, sink);
  const Eigen::Index n = 3 * s.x.cols();
  Eigen::SparseMatrix<double> H(n, n);
  H.setFromTriplets(sink.triplets.begin(), sink.triplets.end());
  return H;
}

}  // namespace orthosim
