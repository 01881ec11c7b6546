#pragma once
// The contact potential of one node as a function of its penetration s = -d below a rigid surface
// (d the signed distance): zero outside (s <= 0), k psi(s) inside. Deeper than the onset width a it
// is the paper's penalty, psi = s^2 / 2 (less a constant), so the force is k s there; over the
// onset the stiffness psi'' rises from 0 (at s = 0) to 3/2 (at a/2) and falls back to 1 (at a),
// linearly in pieces, so that the force has caught up with k s at s = a. That makes psi twice
// continuously differentiable: Newton's Hessian no longer jumps from 0 to k when a node touches
// (the C1 penalty's jump makes contact-heavy solves chatter), and the contact force of any
// penetration beyond a is the paper's. Unlike IPC's barrier the potential is zero outside and
// finite inside, so tissue touching the teeth at rest is at rest, and a prescribed bone move may
// pass a node without making the state infeasible.
namespace orthosim {

struct SmoothPenalty {
  double onset = 0;  // a, mm (> 0)

  // s: penetration, mm; the values are per unit stiffness.
  double value(double s) const;
  double slope(double s) const;      // d psi / ds
  double curvature(double s) const;  // d2 psi / ds2
};

}  // namespace orthosim
