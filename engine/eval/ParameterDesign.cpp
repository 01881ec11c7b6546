#include "eval/ParameterDesign.hpp"

#include <cmath>
#include <sstream>
#include <stdexcept>

namespace orthosim {

double DesignRun::value(const ParameterRange& r, int level) const {
  return level < 0 ? r.low : level > 0 ? r.high : r.nominal;
}

int ParameterDesign::oneAtATime(int parameter, int level) const {
  if (level < 0 && parameters[static_cast<size_t>(parameter)].twoLevel) return 0;
  for (size_t k = 0; k < runs.size(); ++k)
    if (runs[k].kind == "one_at_a_time" && runs[k].parameter == parameter &&
        runs[k].levels[static_cast<size_t>(parameter)] == level)
      return static_cast<int>(k);
  return -1;
}

ParameterDesign parameterDesign(const DesignNominal& nominal, const DesignOptions& options) {
  const double s = options.rangeScale;
  if (!(s > 0 && s <= 2))
    throw std::invalid_argument("band design: range_scale must be in (0, 2], got " + std::to_string(s));
  ParameterDesign d;
  const double nu = nominal.poissonRatio;
  d.parameters.push_back({BandParameter::PoissonRatio, "poisson_ratio", nu - 0.02 * s, nu, nu + 0.02 * s, false});
  const double w = nominal.blendWidth;
  d.parameters.push_back({BandParameter::BlendWidth, "blend_width_mm", w - 5.0 * s, w, w + 5.0 * s, false});
  if (nominal.hasContact) {
    d.parameters.push_back({BandParameter::LipsBonded, "lips_bonded", 0, 0, 1, true});
    d.parameters.push_back(
        {BandParameter::ContactStiffness, "contact_stiffness_factor", std::pow(0.3, s), 1.0, std::pow(3.0, s), false});
  }
  if (nominal.bondDistance > 0) {
    const double b = nominal.bondDistance;
    d.parameters.push_back({BandParameter::BondDistance, "bond_distance_mm", b - s, b, b + s, false});
    if (!(b - s > 0)) {
      std::ostringstream m;
      m << "band design: the bond distance would go down to " << b - s
        << " mm: it must stay above 0 (lower range_scale)";
      throw std::invalid_argument(m.str());
    }
  }
  const ParameterRange& p = d.parameters[0];
  if (!(p.low > 0 && p.high < 0.5)) {
    std::ostringstream m;
    m << "band design: Poisson's ratio would range over " << p.low << " to " << p.high
      << ", outside (0, 0.5): lower range_scale or the case's poisson_ratio";
    throw std::invalid_argument(m.str());
  }
  if (!(d.parameters[1].low > 0)) {
    std::ostringstream m;
    m << "band design: the blend width would go down to " << d.parameters[1].low
      << " mm: it must stay above 0 (lower range_scale)";
    throw std::invalid_argument(m.str());
  }

  const int n = static_cast<int>(d.parameters.size());
  d.runs.push_back({"nominal", "nominal", std::vector<int>(static_cast<size_t>(n), 0), -1});
  for (int k = 0; k < n; ++k)
    for (int level : {-1, 1}) {
      if (level < 0 && d.parameters[static_cast<size_t>(k)].twoLevel) continue;  // that is the nominal
      DesignRun r{d.parameters[static_cast<size_t>(k)].name + (level < 0 ? " low" : " high"), "one_at_a_time",
                  std::vector<int>(static_cast<size_t>(n), 0), k};
      r.levels[static_cast<size_t>(k)] = level;
      d.runs.push_back(r);
    }
  if (!options.corners) return d;
  // Two parameters: the full 2^2 factorial. Three or more: the half fraction 2^(n-1) whose last
  // parameter's level is the product of the others' (resolution III with three, IV with four, V
  // with five: no main effect is aliased with another).
  const int free = n <= 2 ? n : n - 1;
  for (int bits = 0; bits < (1 << free); ++bits) {
    DesignRun r{"corner " + std::to_string(bits + 1), "corner", std::vector<int>(static_cast<size_t>(n), 0), -1};
    int product = 1;
    for (int k = 0; k < free; ++k) {
      r.levels[static_cast<size_t>(k)] = (bits >> k) & 1 ? 1 : -1;
      product *= r.levels[static_cast<size_t>(k)];
    }
    if (free < n) r.levels[static_cast<size_t>(n - 1)] = product;
    d.runs.push_back(r);
  }
  return d;
}

}  // namespace orthosim
