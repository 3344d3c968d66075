#pragma once
// Least squares on re-runs of the model: parameters whose effect is the model itself run at other values (a case key,
// a change of the dynamics model) are fitted by bounded Levenberg-Marquardt on fresh runs, re-linearised by finite
// differences at each iterate, with the columns of everything else fitted linearly beside them (variable projection)
// under the AR noise model. Selection reads such parameters through columns from runs at one point; a large or
// nonlinear effect outgrows them, and the estimate is biased by the curvature. The refit's estimate is the model's own.
#include <functional>

#include <Eigen/Dense>

#include "reconcile/experiment.hpp"
#include "reconcile/stats.hpp"

namespace sw::reconcile {

/// What the refit fits: the model's response on the experiment's rows at given values (n, the recording's units; may
/// throw InputError when the model cannot be run there), the bounds it may be run within, each parameter's
/// difference step at given values, and the fixed columns fitted linearly at every iterate.
struct RerunProblem {
  const Experiment& e;
  const ArModel& ar;
  std::function<Eigen::VectorXd(const Eigen::VectorXd& values)> response;
  Eigen::VectorXd lo, hi;
  std::function<double(const Eigen::VectorXd& values, int parameter)> step;
  Eigen::MatrixXd linear;  ///< n x m (m may be 0)
  int rows = 0;            ///< the first rows are fitted; 0: all
  /// Forward differences (the iterate's own run reused: one run per parameter) instead of central ones (two), for a
  /// model whose runs are dear (the dynamics model coupled through the FEM body).
  bool forward = false;
  /// The values have converged when every move (as run, inside the bounds) is below this fraction of the parameter's
  /// difference step and below a tenth of its standard error; a least-damped proposal that small ends the fit without
  /// a run to confirm it.
  double converged = 1e-3;
  int max_iterations = 12;
  /// No step moves a parameter by more than this many of its difference steps (a trust region: nearly collinear
  /// parameters, a drag's Coulomb and viscous parts at one speed, would otherwise take a long step along the direction
  /// the data do not see, where the model is dear or cannot be run at all).
  double max_step_in_steps = INFINITY;
};

/// The refit: the values, the model's response there, the linear part's coefficients, the whitened residual sum of
/// squares over the fitted rows, the Jacobian d response / d values at the values (n x k) and what it took.
struct RerunFit {
  Eigen::VectorXd values, response, linear_beta;
  double rss = INFINITY;
  Eigen::MatrixXd jacobian;
  Eigen::VectorXd start_response;  ///< the model's response at the start
  int iterations = 0, runs = 0;
};

/// Bounded Levenberg-Marquardt (projected steps: the model is never run outside the bounds) from `start`. A trial
/// point where the model cannot be run (InputError) rejects that step like a worse one; a start where it cannot be
/// run throws that error.
RerunFit refit_on_reruns(const RerunProblem& p, const Eigen::VectorXd& start);

/// The whitened Jacobian with the linear part projected out, and the whitened residual likewise, over the fitted rows.
std::pair<Eigen::MatrixXd, Eigen::VectorXd> projected_system(const RerunProblem& p, const Eigen::VectorXd& response,
                                                             const Eigen::MatrixXd& jacobian);

/// A direction of the values is unseen by the data where the Gram matrix of the Jacobian's unit columns has an
/// eigenvalue below this (the response along it below 3e-7 of a column's): columns that are the same to rounding, a
/// drag's Coulomb and viscous parts in a model that answers only their sum at speed.
constexpr double kUnseenDirection = 1e-13;
/// A headline the data do not read: its gradient's part along the unseen directions above this share of it (in the
/// unit columns' values). Not zero: the columns are forward differences over their own steps, so a headline the data
/// do read (a drag's sum at speed, whose parts the model answers only together) has a part there of the order of the
/// model's curvature over a step, a few per cent; a part alone has most of its gradient there.
constexpr double kUnseenShare = 0.1;

/// The 95 % half-widths of g_q^T values at the fit, one for each column g_q of G (k x q), from its Jacobian under the
/// noise model, all from one projection: with the calibration of the noise on the same whitened rows (stats.hpp), the
/// variance at the level measured where the influence v = Jp (Jp^T Jp)^+ g lies with Student's t (as
/// headline_with_ci); otherwise Wald's, s^2 g^T (Jp^T Jp)^+ g. Infinite where g has a part along a direction the data
/// do not see (kUnseenDirection, kUnseenShare): the pseudo-inverse would drop that part and give a headline the data
/// cannot read an interval of zero width.
Eigen::VectorXd rerun_half_widths(const RerunProblem& p, const RerunFit& f, const Eigen::MatrixXd& G,
                                  const SpectralCalibration& cal);

/// The range of a headline linear in the values, value + g^T (x - values), over the box lo <= x <= hi: what the
/// headline can be at all (a drag's part or its sum at speed is not negative). A 95 % interval intersected with it
/// keeps its coverage, since the truth lies inside it. Exact for a headline linear in the values (a part, a sum at
/// speed, a change of a coefficient); the linearisation otherwise, as the delta method's interval itself is. An end is
/// infinite where g has a part along an unbounded side.
std::pair<double, double> range_within_bounds(const Eigen::VectorXd& lo, const Eigen::VectorXd& hi,
                                              const Eigen::VectorXd& values, double value, const Eigen::VectorXd& g);

}  // namespace sw::reconcile
