#pragma once
// The contact problem of a locked drive under an output torque: which tooth flanks (and generator stations) carry
// force, how much, and by how much the output turns.
//
// Unknowns x_i ≥ 0: the force of each contact (a tooth flank pair, a generator station), each a fixed load pattern
// on the flexspline. The gap of contact i when the output has turned by ψ is
//     g_i = q_i − λ_i·ψ + (A·x)_i ,
// with A the compliance of the patterns (work-conjugate displacement per unit force: the body's influence
// coefficients plus whatever acts in series, e.g. tooth bending on the diagonal; symmetric positive definite), q_i the
// gap at ψ = 0 with no force (negative: overlap) and λ_i the gap a unit turn closes (the moment arm: the moment about
// the axis of a unit force of pattern i). Equilibrium of the output: λᵀx = T.
// Signorini conditions x ≥ 0, g ≥ 0, x·g = 0 with λᵀx = T are the optimality conditions of
//     min ½ xᵀA x + qᵀx   subject to x ≥ 0, λᵀx = T,
// ψ being the multiplier of the equality. Solved exactly (to round-off) by a Lawson–Hanson active-set method kept
// feasible for the equality (each iterate is a convex combination of feasible points). Written here because the
// problem is dense (tens to a few thousand contacts, a few hundred loaded) and no Debian library offers an
// equality-constrained NNLS. The passive set's block is held as a Cholesky factor updated as contacts join and leave
// (O(k²) a step instead of O(k³)), the gaps from the loaded columns only.
#include <Eigen/Core>

namespace sw {

struct ContactProblem {
  Eigen::MatrixXd A;       ///< n × n compliance (m/N), symmetric positive definite
  Eigen::VectorXd q;       ///< gap at ψ = 0, no force (m)
  Eigen::VectorXd lambda;  ///< moment arm (m): gap closed per radian of output turn, moment per newton
};

struct ContactSolution {
  Eigen::VectorXd force_N;  ///< ≥ 0
  Eigen::VectorXd gap_m;    ///< ≥ 0 (to round-off), 0 where force_N > 0
  double twist_rad = 0;     ///< ψ
  int iterations = 0;
  int in_contact() const { return static_cast<int>((force_N.array() > 0).count()); }
};

/// Solves the problem for output torque T ≠ 0 (N·m). Throws InputError when no contact can carry T's sign (every λ_i
/// of the other sign or zero). `warm`: forces of a nearby problem's solution (the same contacts: the previous torque
/// step, the previous pass of an iteration); the contacts it loads are the first passive set when the forces on that
/// set all come out positive, which saves the active-set steps from one contact up. The solution is the same
/// (the problem's optimum is unique); only the path to it changes.
ContactSolution solve_contact(const ContactProblem& p, double torque_Nm, const Eigen::VectorXd* warm = nullptr);

}  // namespace sw
