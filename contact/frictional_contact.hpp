#pragma once
// The contact problem of a locked drive with Coulomb friction on the flanks, along a history of output torques.
//
// Per contact i (a flank pair, a generator station) two forces on the flexspline: the normal force p_i ≥ 0 along n_i
// (the direction of ContactProblem's pattern: the push of the circular spline on the flexspline's tooth) and the
// tangential force q_i along t_i, the unit vector along the flank's profile in the transverse plane (perpendicular to
// n_i; its sense is the contact's own choice: q_i, s_i and λt_i below change sign with it).
//
// Kinematics and signs (the circular spline fixed, the output turned by ψ):
//  - Compliance: the flexspline's contact point moves along n_i and t_i, per unit normal and tangential force, by
//        [u_n; u_t] = [[A, A_tnᵀ], [A_tn, A_tt]]·[p; q]      (2n × 2n, symmetric positive definite),
//    A the frictionless problem's (ContactProblem::A), A_tn the tangential displacement per unit normal force.
//  - A rigid turn ψ moves the point by −λ_i·ψ along n_i and by −λt_i·ψ along t_i, λ_i and λt_i the moments about the
//    axis of the unit forces on the circular spline (ContactProblem::lambda and lambda_t): the same arms give the
//    output's equilibrium  λᵀp + λtᵀq = T.
//  - Normal gap (ContactProblem's):    g_i = q0_i + (A p + A_tnᵀ q)_i − λ_i ψ ≥ 0,  p_i ≥ 0,  p_i·g_i = 0.
//  - Tangential relative displacement: s_i = (A_tn p + A_tt q)_i − λt_i ψ, the flexspline's point relative to the
//    circular spline's along t_i, zero in the unloaded state at ψ = 0.
//  - Coulomb's law on the increment Δs = s − s_prev of a load step (s_prev: the end of the previous step):
//        |q_i| ≤ μ_i p_i;   |q_i| < μ_i p_i  ⇒  Δs_i = 0 (stick);   Δs_i ≠ 0  ⇒  q_i = −μ_i p_i sign(Δs_i) (slip),
//    the friction on the flexspline opposing its slip. An open contact carries nothing (p = q = 0) and moves freely.
//    Power balance: T ψ̇ = d/dt(½ fᵀC f) + Σ|q||ṡ|, so a closed loop's area ∮T dψ is the friction work.
//
// Each step, for a given slip bound b, is a Tresca problem: the optimality conditions of the convex QP
//     min ½ [p;q]ᵀ C [p;q] + q0ᵀp − s_prevᵀq   subject to p ≥ 0, |q| ≤ b, λᵀp + λtᵀq = T,
// ψ the multiplier of the equality (the gradient is (g, Δs)). Coulomb's problem is the fixed point b = μ∘p: the
// successive approximation of Tresca problems of Nečas, Jarušek & Haslinger (1980; the discrete form in Haslinger,
// Hlaváček & Nečas, Handbook of Numerical Analysis IV, 1996), a contraction for small μ. Each Tresca problem is solved
// exactly by a primal active-set method for bounded variables (Lawson–Hanson's, two-sided as Stark & Parker's BVLS)
// kept feasible for the equality. After each pass the contact sets it found (open, stick, slip and its sense) are
// tried on Coulomb's conditions directly: the linear system with q = ±μp on the slipping contacts and Δs = 0 on the
// sticking ones (a Newton step on the fixed point, exact once the sets are right), accepted when every condition
// holds. Warm starts: each step's first pass starts from the previous step's sets and normal forces.
#include <functional>
#include <vector>

#include <Eigen/Core>

#include "contact/contact_problem.hpp"
#include "contact/torque_twist.hpp"

namespace sw {

/// ContactProblem (A, q, lambda: the normal part) with the tangential blocks and the friction coefficients.
struct FrictionalContactProblem : ContactProblem {
  Eigen::MatrixXd A_tn;                  ///< n × n (m/N): tangential displacement per unit normal force
  Eigen::MatrixXd A_tt;                  ///< n × n (m/N): tangential displacement per unit tangential force
  Eigen::VectorXd lambda_t;              ///< n (m): moment about the axis of a unit tangential force
  Eigen::VectorXd friction_coefficient;  ///< n: μ_i ≥ 0 (0: frictionless, e.g. a rolling generator station)
};

enum class ContactState { Open, Stick, Slip };

/// The state at the end of a load step (and the start of the next).
struct FrictionalStep {
  double torque_Nm = 0, twist_rad = 0;
  Eigen::VectorXd normal_force_N;      ///< p ≥ 0
  Eigen::VectorXd tangential_force_N;  ///< q, |q| ≤ μp
  Eigen::VectorXd gap_m;               ///< normal gap g ≥ 0 (to round-off), 0 where p > 0
  Eigen::VectorXd slip_m;              ///< tangential relative displacement s (equal to the previous step's: stick)
  std::vector<ContactState> state;
  double friction_work_J = 0;  ///< this step's Σ|q_i|·|Δs_i|
  int passes = 0;              ///< fixed-point passes (Tresca problems solved)
  int count(ContactState s) const;
};

/// The unloaded state: no force, ψ = 0, s = 0 (the reference of the slip), every contact open.
FrictionalStep unloaded_state(const FrictionalContactProblem& p);

/// One load step from `previous` to output torque T (N·m): Coulomb's law on the increment. T = 0 is carried only by a
/// state that holds it (preload, friction locking); a history stands for T = 0 by its limits ±kZeroTorqueLimit·T_R.
/// Preconditions: the block compliance symmetric positive definite; `previous` of this problem (the same contacts).
/// `near`: where the fixed point and the active sets start (a solution of a nearby problem from the same `previous`,
/// e.g. the last iterate of a caller's loop around the step; default `previous`): the solution is the same, its path
/// shorter. Throws InputError for μ_i < 0 (naming the contact and the value), when no contact can carry T (no normal
/// arm of T's sign to close, as solve_contact), and when the fixed point does not converge (μ too large for a unique
/// increment).
FrictionalStep solve_frictional_step(const FrictionalContactProblem& p, double torque_Nm,
                                     const FrictionalStep& previous, const FrictionalStep* near = nullptr);

/// A load step: the state at output torque T from the previous state. solve_frictional_step on a problem, or a
/// caller's own (one that also iterates a part of the problem per step, records what it needs).
using LoadStep = std::function<FrictionalStep(double torque_Nm, const FrictionalStep& previous)>;

/// solve_frictional_step on (a copy of) `p`.
LoadStep frictional_step_of(const FrictionalContactProblem& p);

/// The states of a torque history from `start`, one per torque. An InputError of a step is rethrown with the step's
/// index and torque in front.
std::vector<FrictionalStep> run_torque_history(const LoadStep& step, const FrictionalStep& start,
                                               const std::vector<double>& torques_Nm);

/// run_torque_history of solve_frictional_step on `p` from the unloaded state.
std::vector<FrictionalStep> solve_torque_history(const FrictionalContactProblem& p,
                                                 const std::vector<double>& torques_Nm);

/// The limits at zero torque stand at ±kZeroTorqueLimit·T_R (as the frictionless curve's); torques within
/// kZeroTorqueSnap·T_R of zero are read as T = 0 (a vertical step through a dead band).
constexpr double kZeroTorqueLimit = 1e-6, kZeroTorqueSnap = 1e-3;

/// The catalog's history: from the unloaded state up to +T_R, then `cycles` times +T_R → −T_R → +T_R, in steps of
/// T_R/steps_per_quarter, with both limits at zero on every crossing: ε, T_R/N, …, T_R, (N−1)T_R/N, …, T_R/N, ε, −ε,
/// −T_R/N, …, −T_R, …, −ε, ε, …, T_R (ε = kZeroTorqueLimit·T_R). Preconditions: T_R > 0, N ≥ 1, cycles ≥ 1.
std::vector<double> cycle_torque_history(double rated_torque_Nm, int steps_per_quarter, int cycles = 1);

/// What a load cycle's loop gives (torque_twist.hpp's readings of its branches, and the friction's work).
struct LoopFigures {
  double hysteresis_loss_rad = 0;      ///< the branches' gap at zero torque, each in its dead band's middle: friction's
  double rig_hysteresis_loss_rad = 0;  ///< what a rig reads there: the friction's gap and the dead bands crossed
  LoopWidth widest;                ///< the branches' largest gap and its torque (teeth with play: a lens, 0 at zero)
  double dissipated_energy_J = 0;  ///< the loop's area ∮T dψ
  double friction_work_J = 0;      ///< Σ over the cycle's steps and contacts of |q|·|Δs|
  double lost_motion_rad = 0;      ///< between ±4 % of T_R on the loop's middle line
  /// The dead bands the branches cross at zero torque, as a rig's reading holds them beside the friction's gap.
  double zero_torque_dead_band_rad() const { return rig_hysteresis_loss_rad - hysteresis_loss_rad; }
};

/// The readings of the last full cycle of a history (on the steps' twists; friction work summed over the cycle's
/// steps), with the loop they are read on.
struct LoopReading : LoopFigures {
  TorqueLoop loop;
};
LoopReading read_loop(const std::vector<FrictionalStep>& history, double rated_torque_Nm);

/// The catalog's history run until its loop is steady. A frictional system under a load cycle need not repeat its
/// first cycle: where normal and tangential forces are coupled (through A_tn, or through the output's equilibrium) it
/// can shake down to a steady cycle over several, the changes shrinking geometrically (Klarbring, Ciavarella & Barber,
/// "Shakedown in elastic contact problems with Coulomb friction", Int. J. Solids Struct. 44, 2007). A step's solution
/// depends on the previous state's slips and the torque alone, so a cycle that ends (at +T_R) in the state it started
/// from is repeated by every later one: cycles are added until the state at the last one's top differs from the one
/// before's by at most `rel_tol` (the slips over the largest slip, the twist over the twist), or `max_cycles` are run.
/// With play that is the first cycle. Preconditions as cycle_torque_history's.
struct SteadyLoop {
  std::vector<FrictionalStep> history;     ///< the first loading and every cycle
  int cycles = 0;
  double top_change_rel = 0;               ///< the state's change at the top over the last cycle
  LoopReading reading;                     ///< of the last cycle
};
SteadyLoop run_steady_loop(const LoadStep& step, const FrictionalStep& start, double rated_torque_Nm,
                           int steps_per_quarter, double rel_tol = 1e-6, int max_cycles = 10);

/// The steady loop as the steps per quarter double: first_steps, 2·first_steps, … (`levels` loops).
struct StepStudyLevel {
  int steps_per_quarter = 0;
  SteadyLoop loop;
};
std::vector<StepStudyLevel> loop_step_study(const LoadStep& step, const FrictionalStep& start, double rated_torque_Nm,
                                            int first_steps, int levels, double rel_tol = 1e-6, int max_cycles = 10);

/// The steps of the coarsest level from which every level's hysteresis loss is within `rel_tol` of the finest level's
/// (relative to it; the loss need not converge monotonically: a contact closing inside a step moves it either way).
int converged_steps_per_quarter(const std::vector<StepStudyLevel>& study, double rel_tol);

}  // namespace sw
