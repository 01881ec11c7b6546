#pragma once
// The design of a prediction band: which model parameters a band varies, their
// ranges, and the runs. Young's modulus is not among them: with the bones' motion prescribed the
// face does not depend on it (docs/solver.md). The runs are the nominal one, each parameter at its
// low and high end one at a time (what a landmark's sensitivity to it is read from), and the
// corners of a two-level fractional factorial, so that the envelope also sees parameters pushing
// together rather than only one at a time.
#include <string>
#include <vector>

namespace orthosim {

enum class BandParameter {
  PoissonRatio,      // compressibility of the tissue
  BlendWidth,        // mm: how far the bond to the bone reaches past a cut
  LipsBonded,        // the lips' inner surface stuck to the teeth instead of sliding (two levels)
  ContactStiffness,  // factor on the case's contact penalty stiffness
  BondDistance,      // mm: how far from a bone surface given tetrahedra are bonded to it (volume cases)
};

struct ParameterRange {
  BandParameter parameter;
  std::string name;  // poisson_ratio, blend_width_mm, lips_bonded, contact_stiffness_factor, bond_distance_mm
  double low = 0, nominal = 0, high = 0;
  bool twoLevel = false;  // lips: low is the nominal (sliding), high bonded
};

struct DesignRun {
  std::string label;        // "nominal", "poisson_ratio low", "corner 3", ...
  std::string kind;         // nominal, one_at_a_time, corner
  std::vector<int> levels;  // per parameter: -1 low, 0 nominal, +1 high
  int parameter = -1;       // one_at_a_time: the parameter moved
  double value(const ParameterRange& r, int level) const;
};

struct ParameterDesign {
  std::vector<ParameterRange> parameters;
  std::vector<DesignRun> runs;  // runs[0] is the nominal
  // Index of the run with `parameter` alone at `level` (-1 or +1); the nominal run for the low end
  // of a two-level parameter; -1 when the design has no such run.
  int oneAtATime(int parameter, int level) const;
};

struct DesignNominal {
  double poissonRatio = 0.47;
  double blendWidth = 10.0;  // mm
  bool hasContact = false;   // a scene without contact gets no contact parameters
  // A volume case whose bonded nodes are derived from a bone surface: their distance (mm);
  // 0: none (surface cases, whose bonded nodes are the Boolean's vertices on the bone).
  double bondDistance = 0;
};

struct DesignOptions {
  // Scales every range about the nominal: 1 the full ranges (Poisson's ratio +-0.02, blend
  // width +-5 mm, contact stiffness x0.3 to x3, bond distance +-1 mm), 0.5 half of each (the stiffness factors'
  // logarithms halved). The lips' two levels do not scale.
  double rangeScale = 1.0;
  bool corners = true;  // the fractional factorial's corners besides the one-at-a-time runs
};

// Throws std::invalid_argument naming the option when the range scale is not in (0, 2], or a
// range would leave what the model accepts (Poisson's ratio in (0, 0.5), a blend width > 0).
ParameterDesign parameterDesign(const DesignNominal& nominal, const DesignOptions& options = {});

}  // namespace orthosim
