#pragma once
// The recorded experiment put side by side with the simulated one (the baseline): the response, the baseline's
// prediction of it, and the derived inputs each effect's model is built from (torque direction, reversal torques,
// angles). Everything is SI except backlash responses, which stay in micrometres as recorded.
#include <cmath>
#include <functional>
#include <string>
#include <utility>
#include <variant>
#include <vector>

#include <Eigen/Dense>

#include "reconcile/recording.hpp"

namespace sw::reconcile {

/// A change of the dynamics model that one catalog effect stands for (SI). All zero / negative: the baseline model.
struct DynamicsVariation {
  double stiffness_ratio = 0.0;        ///< mesh_stiffness_variation: Δk/k0 of k(t) = k0 + Δk·sin(ψ_mesh + phase)
  double stiffness_phase_rad = 0.0;
  double damping_Ns_per_m = -1.0;      ///< damping: contact damping coefficient (< 0: the model's own)
  double drag_coulomb_Nm = 0.0;        ///< drag_torque: output drag added to the model's
  double drag_viscous_Nms_per_rad = 0.0;
};

/// One run of the dynamics model on its own output grid (the recording columns plus the mesh phase ψ_mesh(t)).
struct DynamicsRun {
  std::vector<double> time_s, wg_speed_rpm, output_speed_rpm, mesh_force_N, mesh_phase_rad;
};

/// The drive's gear as the case or the recording's metadata give it (0: not given). The transmission baseline is its
/// ideal ratio; backlash's load torsion acts at its pitch radius.
struct DriveGear {
  int teeth_flexspline = 0;            ///< z_f
  int teeth_circular = 0;              ///< z_c (output = -wg * (z_c - z_f) / z_f)
  double pitch_radius_m = 0.0;         ///< flexspline pitch radius (load_torsion converts phi0 to um)
};

/// The torsion baseline: C_tau T of the flexspline body, or the drive's torque-twist curve.
struct TorsionPrediction {
  static constexpr Kind kind = Kind::Torsion;
  /// C_tau of the flexspline body (twist = C_tau * T); with `twist_rad` the curve's slope at its ends (the last
  /// segment's compliance, 1/K3 of the model), which the stiffness headlines are read against.
  double compliance_rad_per_Nm = 0.0;
  /// The baseline twist (rad) at a torque when it is a curve (the contact stage's torque-twist curve, its loop's
  /// middle line); empty: C_tau * T. May throw InputError for a torque beyond the curve.
  std::function<double(double torque_Nm)> twist_rad;
  /// With `twist_rad`: the curve's catalog breakpoints T1 < T2 (N*m; 0: none), where the catalog figures read K1, K2,
  /// K3 as segment secants when no stiffness effect replaces them.
  double curve_t1_Nm = 0.0, curve_t2_Nm = 0.0;
  /// A loop (the contact curve with friction in the teeth, cycled to +-loop_amplitude_Nm): the twist (rad) on its
  /// loading branch (direction > 0) or its unloading branch (direction < 0) at a torque; `twist_rad` is then the
  /// loop's middle line. Empty: one line, the same both ways.
  std::function<double(double torque_Nm, double direction)> branch_twist_rad;
  double loop_loss_rad = 0.0;        ///< the loop's branch gap at zero torque (its hysteresis loss)
};

/// The transmission baseline: the ideal ratio of the drive's teeth (DriveGear).
struct TransmissionPrediction {
  static constexpr Kind kind = Kind::Transmission;
};

/// The backlash baseline: the basic kinematic model.
struct BacklashPrediction {
  static constexpr Kind kind = Kind::Backlash;
  /// Backlash in um at a wave-generator angle in rad (phi0 = 0).
  std::function<double(double wg_angle_rad)> backlash_um;
};

/// The dynamics baseline: the dynamics model of the recording's conditions (constant mesh stiffness).
struct DynamicsPrediction {
  static constexpr Kind kind = Kind::Dynamics;
  /// Runs the model with a variation; supplied by the app (reconcile does not link the dynamics module).
  std::function<DynamicsRun(const DynamicsVariation&)> dynamics_run;
  double damping_Ns_per_m = 0.0;       ///< the model's contact damping c0
  double mesh_frequency_Hz = 0.0;      ///< f_m = z_f·|n_f − n_w|/60 at full speed
  double load_torque_Nm = 0.0;         ///< full load (sets the drag perturbation)
  double output_speed_rad_s = 0.0;     ///< steady output speed magnitude
  /// Rows before this time are not analysed (0: all rows). Moving tooth pairs separate and strike again in the run-up
  /// and at a load step, and there the meshing force responds to the model's parameters by the timing of those
  /// impacts, not smoothly: a drag of 1e-4 N*m moves it by up to 836 N (26/28 gear); in steady running the response
  /// is smooth (the same drag: 0.0076 N, the drag over the flanks' arm). Analysed: the steady window.
  double analysis_from_s = 0.0;
};

/// What the current simulation predicts for a recording: one model per kind.
using Prediction = std::variant<TorsionPrediction, TransmissionPrediction, BacklashPrediction, DynamicsPrediction>;

/// Case keys "table.key" and the values a model re-run sets them to (the case file's units).
using ModelKeyValues = std::vector<std::pair<std::string, double>>;

struct Baseline {
  /// What the baseline is ("fem": C_tau T of the flexspline body; "contact": the drive's torque-twist curve; other
  /// kinds: "ideal_ratio", "kinematic", "dynamics_model"; empty: the kind's default, see default_model_name()) and
  /// where it was read.
  std::string model, source;
  DriveGear gear;
  Prediction prediction;
  /// Re-runs the model the prediction came from with some case keys changed and returns its prediction, of the same
  /// kind (empty: the baseline cannot be re-run). Supplied by the app (reconcile does not link the stages); may throw
  /// InputError for values the case refuses.
  std::function<Prediction(const ModelKeyValues& key_values)> model_run;
  Kind kind() const;
};

/// The same dynamics baseline with its runs remembered: a run is a deterministic function of its variation, so a
/// variation seen before (the sensitivity and calibration runs of every recording of one model, the synthesis of many
/// noise seeds) returns the stored run instead of integrating again. Copies share the store; not thread-safe.
DynamicsPrediction with_remembered_runs(DynamicsPrediction prediction);

/// The name of a baseline without one of its own: torsion "fem" for C_tau T, "curve" for a torque-twist curve;
/// "ideal_ratio", "kinematic", "dynamics_model".
std::string default_model_name(const Prediction& prediction);

/// Torsion: the applied torque and the loop's branches.
struct TorsionExperiment {
  static constexpr Kind kind = Kind::Torsion;
  TorsionPrediction model;           ///< the baseline
  Eigen::VectorXd torque_Nm;
  Eigen::VectorXd direction;         ///< +1 while torque rises, -1 while it falls
  Eigen::VectorXd since_reversal_Nm; ///< |T - T at the last reversal|
  double torque_amplitude_Nm = 0.0;  ///< median |T| at reversals (or max |T|)
  int drive_size = 0;                ///< metadata `size` (catalog size number), 0 when absent
  double rated_torque_Nm = 0.0;      ///< metadata `rated_torque_Nm`, 0 when absent
};

/// Transmission: the wave-generator angle and the ideal output angle.
struct TransmissionExperiment {
  static constexpr Kind kind = Kind::Transmission;
  Eigen::VectorXd wg_angle_rad;
  Eigen::VectorXd output_angle_rad;  ///< ideal output angle (noise free, from the ratio)
};

/// Backlash: the wave-generator angle and the torque of each row.
struct BacklashExperiment {
  static constexpr Kind kind = Kind::Backlash;
  BacklashPrediction model;          ///< the baseline
  double pitch_radius_m = 0.0;       ///< the drive's (DriveGear)
  Eigen::VectorXd wg_angle_rad;
  Eigen::VectorXd torque_Nm;
};

/// Dynamics: the baseline run's mesh phase and the responses of the model to each effect's parameters.
struct DynamicsExperiment {
  static constexpr Kind kind = Kind::Dynamics;
  DynamicsPrediction model;          ///< the baseline
  Eigen::VectorXd wg_angle_rad;      ///< of the baseline run (for plots in wave-generator orders)
  Eigen::VectorXd mesh_phase_rad;    ///< ψ_mesh(t) of the baseline run (2π per tooth passing)
  /// Sensitivity columns of the response (mesh_force_N) from perturbed runs, per unit parameter:
  /// 0,1: Δk/k0 at phase 0 and π/2 (their part locked to the mesh, see stiffness_unlocked); 2: damping (per N·s/m);
  /// 3: Coulomb drag (per N·m); 4: viscous drag (per N·m·s/rad)
  Eigen::MatrixXd sensitivity;
  /// The k(t) sensitivity columns' part not locked to the mesh (n x 2; columns 0, 1 hold the locked part).
  Eigen::MatrixXd stiffness_unlocked;
  /// Calibration curve of the nonlinear k(t) response, from runs at a few Δk/k0 (ascending): the magnitude of the
  /// coefficients of the two k(t) sensitivity columns (least squares) against Δk/k0.
  std::vector<double> calib_ratio, calib_stiffness_beta;
  /// The damping coefficients of a table (ascending, N·s/m) and the response to each (n x table size: meshing force
  /// of the run minus the baseline's; zero at the model's own c0).
  std::vector<double> damping_table_Ns_per_m;
  Eigen::MatrixXd damping_response;
};

struct Experiment {
  int n = 0;
  Eigen::VectorXd time;              ///< time_s, or the row index when the recording has none
  bool has_time = false;
  Eigen::VectorXd measured;          ///< the response column (twist_rad, output_angle_rad, backlash_um, mesh_force_N)
  Eigen::VectorXd baseline;          ///< the baseline's prediction of it
  std::string baseline_model;        ///< Baseline::model, or the kind's default_model_name()
  std::string baseline_source;       ///< Baseline::source
  std::string response_name;         ///< column name of the response
  std::string response_unit;         ///< "rad", "um" or "N"
  /// What the kind's effects are built from.
  std::variant<TorsionExperiment, TransmissionExperiment, BacklashExperiment, DynamicsExperiment> data;
  Kind kind() const;
  Eigen::VectorXd residual() const { return measured - baseline; }
};

/// The experiment's data of kind K (TorsionExperiment, ...). Precondition: the experiment is of that kind (the catalog
/// rows of a kind see only its experiments); otherwise throws std::bad_variant_access.
template <class K>
const K& as(const Experiment& e) {
  return std::get<K>(e.data);
}
inline const TorsionExperiment& torsion(const Experiment& e) { return as<TorsionExperiment>(e); }
inline const DynamicsExperiment& dynamics(const Experiment& e) { return as<DynamicsExperiment>(e); }

/// The root mean square of v's entries; 0 for an empty v.
inline double rms(const Eigen::VectorXd& v) { return v.size() ? std::sqrt(v.squaredNorm() / v.size()) : 0.0; }

/// The response a prediction gives on the experiment's rows (n), as make_experiment reads the baseline's: torsion the
/// twist at each row's torque, backlash the backlash at each row's wave-generator angle. Throws InputError when the
/// prediction is of another kind than the experiment or the kind has no row-wise response (transmission, dynamics).
Eigen::VectorXd predicted_response(const Experiment& e, const Prediction& prediction);

/// Builds the experiment from a recording and the baseline of its kind. Throws InputError when the kinds differ, the
/// baseline lacks what the kind needs (e.g. C_tau <= 0 for torsion) or the recording is too short (< kMinSamples
/// rows) or degenerate.
Experiment make_experiment(const Recording& recording, const Baseline& baseline);

/// The rows of a recording from time_s = from_s on (all of them when from_s <= 0 or there is no time_s). Throws
/// InputError when fewer than kMinSamples remain.
Recording rows_from(const Recording& recording, double from_s);

/// Linear interpolation of y(t) (t ascending) at `at`; constant beyond the ends.
Eigen::VectorXd resample(const std::vector<double>& t, const std::vector<double>& y, const Eigen::VectorXd& at);

/// cos/sin(k ψ_mesh) for k = 1 .. orders (n x 2 orders), the mesh-frequency line and its harmonics.
Eigen::MatrixXd mesh_harmonics(const DynamicsExperiment& d, int orders);
/// Mesh orders the k(t) sensitivity columns keep.
inline constexpr int kMeshHarmonics = 4;
/// mesh_harmonics(d, 2), the mesh-frequency line and its harmonic.
Eigen::MatrixXd mesh_lines(const DynamicsExperiment& d);

/// Steps of the damping table each side of c0 (ratio 2^(1/4): c0/8 to 8 c0).
inline constexpr int kDampingTableSteps = 12;

/// The secant (n rows, N per N·s/m) of the response to the damping coefficient from the model's c0 to c: the response
/// at c, a cubic through the table's runs around c (c clamped to the table), over c - c0; within 1e-3 c0 of c0 the
/// interpolant's slope there.
Eigen::VectorXd damping_secant(const DynamicsExperiment& d, double c_Ns_per_m);

/// Inverse of a calibration curve y(x) given at ascending x: the x whose y is `y`, searched on the segments nearest
/// x_ref first (the curve may fold back far away); linear extrapolation beyond the ends.
double invert_calibration(const std::vector<double>& x, const std::vector<double>& y, double x_ref, double value);

/// The fewest rows reconcile analyses (AR order 8 estimation, a held-out block and the signature tests need them).
inline constexpr int kMinSamples = 100;

/// Direction (+1/-1) of each sample and the index of the turning point that started its branch. A reversal is
/// declared when the signal moves back from its running extreme by more than `threshold` (same units as x), so noise
/// smaller than that never splits a branch.
struct Branches {
  Eigen::VectorXd direction;
  std::vector<int> branch_start;  ///< per sample: index of the turning point (0 for the first branch)
  std::vector<int> reversals;     ///< indices of the turning points
};
Branches find_branches(const Eigen::VectorXd& x, double threshold);

}  // namespace sw::reconcile
