#pragma once
// The mesh as the teeth travel through it: every flexspline tooth's angle relative to the wave generator follows the
// generator's rotation, so pairs enter the engagement zones, carry load and leave.
//
// Generator angle relative to the flexspline σ = θ_w − θ_f (rad); tooth k sits at the material angle
// φ_k = 2πk/z_f − σ from the major axis (kinematics/backlash.hpp, tooth_material_angle with σ = wg·z_c/z_f).
// Each flank unknown i (both teeth of a half-turn pair when z_f is even, as in contact/) has, as functions of σ:
//   gap at zero mesh deflection q_i (m, × teeth per unknown), moment arm λ_i (m, × teeth per unknown): the flank's
//   approach is λ_i·e − q_i for a mesh deflection e (contact/README.md's g = q − λψ + A·x with ψ = e);
//   the tooth pair's own compliance c_i (m/N, × teeth per unknown) from gear/tooth_stiffness at the contact radius;
//   the flanks' sliding s_i (m/rad, × teeth per unknown): their relative velocity along the profile per unit σ̇ when the
//   mesh follows the kinematics, and the arm t_i (m, × teeth per unknown) of that direction about the axis: a flank
//   slides at (s_i·σ̇ + t_i·ė) per tooth (dynamics/README.md, "Friction").
// These come from a table over φ (the backlash module's exact closing angle and lever arm of both flanks, on the
// neutral curve the table was built on), sampled every pitch/(phases·table_per_phase) and interpolated by monotone
// cubic Hermite segments (C¹: no kink at the grid points, which all teeth cross at once).
//
// Coupling through the rim (optional): the loaded-contact problem's body compliance A (flanks and the generator's
// stations, contact/loaded_contact.hpp's ContactAnalysis::problem) at `phases` generator phases over one tooth pitch.
// Between phases every entry of A and each flank's gap correction (the generator's own state) is interpolated by a
// cubic Hermite segment whose slopes (central differences over the neighbouring phases) are shared across the phase
// boundaries; where that segment would leave positive definiteness the phase's slope of A is reduced (at worst to zero,
// the segment then a convex blend of the two phases' matrices). Linear segments made the forces jump at every boundary:
// the damping acts on the gap's rate, and the teeth's travel torque ½xᵀ(∂A/∂σ)x on A's slope; each jump cut the
// integrator's step. A shift by one pitch renames tooth k as tooth k − 1, so the phases cover every angle. The same
// flank must be in both neighbouring phases, else it is left out over that sub-interval (it is then beyond the
// problem's reach: far from closing).
#include <functional>
#include <string>
#include <vector>

#include <Eigen/Core>

namespace sw {

/// The flank geometry over φ, one row per grid angle φ_j = phi_start + j·step; NaN where the flank cannot close.
struct FlankTable {
  double phi_start_rad = 0, step_rad = 0;
  std::vector<double> q_m[2], lambda_m[2], compliance_m_per_N[2];  ///< [side: 0 ccw (λ > 0), 1 cw (λ < 0)][j]
  std::vector<double> sliding_m_per_rad[2], tangent_arm_m[2];       ///< s and t (see above), [side][j]
  std::vector<double> q_slope[2], lambda_slope[2], compliance_slope[2];  ///< the interpolant's slopes at the grid
  std::vector<double> sliding_slope[2], tangent_arm_slope[2];
  int size() const { return static_cast<int>(q_m[0].size()); }
};

/// One flank of one tooth at one material angle, as the kinematics sees it (one tooth, not × teeth per unknown).
struct FlankSample {
  double q_m = 0;                   ///< gap at zero mesh deflection
  double lever_m = 0;               ///< signed moment arm of the flank normal
  double contact_radius_f_m = 0;    ///< contact radius on the flexspline tooth (its compliance is taken there)
  double contact_radius_c_m = 0;    ///< contact radius on the circular spline's tooth
  double sliding_m_per_rad = 0;     ///< relative sliding along the profile per unit σ̇ (kinematic motion)
  double tangent_arm_m = 0;         ///< moment arm about the axis of the profile's direction at the contact
};

/// The loaded-contact problem at one generator phase (flank unknowns, then stations).
struct MeshPhase {
  double shift_rad = 0;          ///< σ of this phase, in [0, pitch)
  std::vector<int> key, side;    ///< per flank: tooth index (mod teeth per period), side 0 ccw / 1 cw
  std::vector<double> phi_rad;   ///< per flank: material angle at shift_rad
  std::vector<int> next;         ///< per flank: the same flank's index in the next phase (−1: not there)
  Eigen::MatrixXd A_body;        ///< body compliance (m/N, series parts excluded), flanks then stations
  Eigen::VectorXd q_correction;  ///< per flank: the problem's gap minus the table's (the generator's own state)
  /// Over [shift_rad, the next phase's shift): the body compliance of the flanks that go on into the next phase
  /// (`continuing`, indices into key) and the stations as a cubic in a = (σ − shift_rad)/h, h = pitch/phases:
  /// A = A_cubic[0] + a·A_cubic[1] + a²·A_cubic[2] + a³·A_cubic[3] (m/N). Gathered once by prepare_intervals() so
  /// that every instant combines contiguous memory.
  std::vector<int> continuing;
  Eigen::MatrixXd A_cubic[4];
  /// Per continuing flank: d(q_correction)/dσ at shift_rad and at the next phase's shift (m/rad), the same value on
  /// both sides of a phase boundary, so that the gap's rate has no jump there (see prepare_intervals()).
  std::vector<double> q_slope_start, q_slope_end;
};

struct MovingMesh {
  int teeth_flexspline = 0;
  int teeth_per_unknown = 1;     ///< 2 when z_f is even (the half-turn symmetry), as in contact/
  double pitch_rad = 0;          ///< 2π/z_f
  FlankTable table;
  std::vector<MeshPhase> phases;  ///< empty: a rigid rim (independent pairs)
  Eigen::VectorXd station_q;      ///< gaps of the generator's unilateral stations (constant in the generator frame)
  std::string source;             ///< for reports: where the clearances and the compliance come from
  int reduced_phases = 0;         ///< phases whose slope of A is reduced to keep the intervals positive definite
  bool coupled() const { return !phases.empty(); }
  int key_period() const { return teeth_flexspline / teeth_per_unknown; }
};

/// The flank problem at one generator angle σ relative to the flexspline.
struct MeshInstant {
  std::vector<int> tooth, side;       ///< per flank: tooth index (mod key_period), side
  Eigen::VectorXd q, dq, lambda, dlambda, compliance, dcompliance;  ///< per flank; d/dσ
  Eigen::VectorXd sliding, tangent_arm;  ///< per flank: s (m/rad) and t (m), × teeth per unknown (when asked for)
  /// Coupled: the body compliance A (flanks then stations) at σ is the phase's cubic in a = (σ − shift)/h over the
  /// rows/columns `rows` of it (empty: all), plus `series` on the flanks' diagonal (the tooth pairs, set by the
  /// caller). Its columns are formed on demand (column()): the contact problem needs only the loaded contacts'.
  const Eigen::MatrixXd* cubic = nullptr;
  std::vector<int> rows;
  double a = 0, h = 1;
  Eigen::VectorXd series;
  int flanks() const { return static_cast<int>(q.size()); }
  int unknowns() const { return cubic ? flanks() + stations : flanks(); }
  /// Column j of A + diag(series) (formed once per instant).
  const double* column(int j);

  int stations = 0;
  Eigen::MatrixXd A;           ///< the columns formed so far (at least unknowns() rows; the first unknowns() used)
  std::vector<char> formed;
};

/// ½·xᵀ(∂A/∂σ)x at the instant for contact forces x (N): the body's share of the teeth's travel torque (N·m), summed
/// over the loaded contacts only (x ≠ 0), without forming ∂A/∂σ.
double body_travel_torque_Nm(const MeshInstant& in, const Eigen::VectorXd& x);

/// Flank geometry over φ from the kinematics' flanks sampled on a grid of `step_rad` from phi_start_rad to
/// phi_end_rad. `flank(phi, side, sample)` returns false where the flank cannot close; the tooth pair's compliance is
/// taken at the sample's two contact radii. Gaps, arms, compliances and sliding are scaled by teeth_per_unknown.
FlankTable make_flank_table(double phi_start_rad, double phi_end_rad, double step_rad, int teeth_per_unknown,
                            const std::function<bool(double, int, FlankSample&)>& flank,
                            const std::function<double(double, double)>& tooth_compliance_m_per_N);

/// Fills every phase's continuing flanks, A_cubic and the gap correction's slopes from the phases' A_body,
/// q_correction and next (a coupled mesh). An interval whose cubic (with each flank's tooth pair at its least compliance
/// there) is not positive definite gets its phases' slopes of A halved in the rows and columns that carry the failure
/// until it is (at worst zero: the convex blend of its two phases); reduced_phases counts the phases touched. Throws
/// InputError if a phase's own matrix is not positive definite.
void prepare_intervals(MovingMesh& m);

/// The problem at σ (rad), with the flanks' sliding and tangent arms when `with_sliding` (the flanks' friction; else
/// they are left empty). Fills `out` (reused between calls).
void mesh_instant(const MovingMesh& m, double sigma_rad, MeshInstant& out, bool with_sliding = false);

/// Linear complementarity x ≥ 0, w = A·x + b ≥ 0, x·w = 0 for symmetric positive definite A: block principal pivoting
/// (Júdice and Pires 1994) with Murty's single pivot as the safeguard, started from `active` (updated). Written here
/// because it is one small dense problem per right-hand side with a warm start, which no Debian library offers.
/// A is given by its columns (`column(j)` points at A(:, j)); only those of the active contacts are asked for.
/// Returns the iterations; throws InputError when it does not converge.
int solve_lcp(const std::function<const double*(int)>& column, const Eigen::VectorXd& b, Eigen::VectorXd& x,
              std::vector<char>& active);
int solve_lcp(const Eigen::MatrixXd& A, const Eigen::VectorXd& b, Eigen::VectorXd& x, std::vector<char>& active);

}  // namespace sw
