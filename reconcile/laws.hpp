#pragma once
// The model laws of the catalog's effects and signatures, as columns over an experiment's rows (what the fit
// multiplies by its linear coefficients) and as functions of torque (what the catalog figures read).
#include <Eigen/Dense>

#include "common/constants.hpp"
#include "reconcile/experiment.hpp"

namespace sw::reconcile {

/// cos(k angle), sin(k angle) (n x 2): a line of order k in an angle.
Eigen::MatrixXd harmonic_columns(const Eigen::VectorXd& angle_rad, int order);

/// Soft-start column of the catalog law: clamp(T, -T1, T1) in N*m (times the compliance step 1/K1 - 1/K2).
/// The whole three-segment law is twist = T/K3 + (1/K2 - 1/K3) clamp(T, T2) + (1/K1 - 1/K2) clamp(T, T1).
Eigen::VectorXd soft_start_column(const Eigen::VectorXd& torque_Nm, double t1_Nm);

/// Twist of the catalog's three-segment law at torque T (odd in T), rad.
double segment_law_twist(double torque_Nm, double k1, double k2, double k3, double t1_Nm, double t2_Nm);

/// The three-segment law with each corner rounded over width * T_b (tanh steps of the compliance): the integral of
/// 1/K3 + (1/K2 - 1/K3) s(x, T2) + (1/K1 - 1/K2) s(x, T1), s = (1 - tanh((x - T_b) / d)) / 2, d = width * T_b; odd in
/// T, rad. A breakpoint T2 that is not finite leaves two segments.
double rounded_segment_law_twist(double torque_Nm, double k1, double k2, double k3, double t1_Nm, double t2_Nm,
                                 double width);

/// Friction hysteresis column (Dahl-type branch transition): -dir * (1/2 - exp(-|T - T_reversal| / T_h)), unitless
/// (times the saturated branch gap h in rad). Loading branch below, unloading above.
Eigen::VectorXd hysteresis_column(const TorsionExperiment& t, double transition_Nm);

/// Branch gap at zero torque of a hysteresis with saturated gap h and transition T_h after reversals at +-A.
double hysteresis_loss_rad(double h_rad, double transition_Nm, double amplitude_Nm);

/// The middle line (mean of the branches) at torque T of a hysteresis with saturated gap h and transition T_h after
/// cycling to +-A, rad.
double hysteresis_middle_twist(double h_rad, double transition_Nm, double amplitude_Nm, double torque_Nm);

/// Branch gap as a function of torque (a loop whose width changes along the torque, e.g. flanks that close and open
/// under friction): columns -dir * hat_k(|T| / A) / 2, k = 0 .. intervals - 1, piecewise-linear hats on `intervals`
/// equal intervals of [0, A] (A the torque amplitude), the gap 0 at +-A where the branches meet; unitless (times the
/// gap at knot k in rad, so the gap at zero torque is the first coefficient). Loading branch below.
Eigen::MatrixXd gap_profile_columns(const TorsionExperiment& t, int intervals);

/// Bouc-Wen friction driven by the torque, per unit branch gap at zero torque: dz = dT (1 - (sgn(dT z) + 1) |z|^n / 2)
/// / T_h, the column -z / 2 divided by the gap (loading branch below). Run over the signal twice (the first pass sets
/// the history); the gap is read at the zero crossings after the first quarter. Throws InputError when the torque
/// does not cross zero both ways.
Eigen::VectorXd bouc_wen_column(const Eigen::VectorXd& torque_Nm, double transition_Nm, double exponent);

/// Lost-motion law: tanh(T / T_s) / 2 (times the width in rad).
double lost_motion_twist(double torque_Nm, double transition_Nm);
Eigen::VectorXd lost_motion_column(const Eigen::VectorXd& torque_Nm, double transition_Nm);

/// Legendre polynomials of orders from..to (n x (to - from + 1)) of the time normalised to [-1, 1]: a drift basis.
Eigen::MatrixXd legendre_columns(const Eigen::VectorXd& time, int from, int to);

}  // namespace sw::reconcile
