#include "contact/loaded_contact.hpp"

#include "common/constants.hpp"
#include "contact/tooth_fem.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <string>

#include <Eigen/Cholesky>
#include <Eigen/Geometry>
#include <Eigen/SparseCore>

#include "common/error.hpp"
#include "common/progress.hpp"
#include "contact/contact_problem.hpp"
#include "contact/frictional_contact.hpp"
#include "contact/tet10_body.hpp"
#include "contact/tooth_fem.hpp"
#include "fem/assembly.hpp"
#include "fem/fourier_section.hpp"
#include "fem/loads.hpp"
#include "fem/post.hpp"
#include "mesh/flexspline.hpp"
#include "gear/tooth_stiffness.hpp"
#include "kinematics/neutral_curve.hpp"

namespace sw {
namespace {

/// The normal forces of a solution of either kind.
const Eigen::VectorXd& normal_forces(const ContactSolution& s) { return s.force_N; }
const Eigen::VectorXd& normal_forces(const FrictionalStep& s) { return s.normal_force_N; }

}  // namespace

std::optional<FlankContact> candidate_flank(const BacklashModel& model, const NeutralCurve& curve,
                                            const PairClearance& pc, double phi, Flank side, bool near_edge) {
  if (!pc.engaged && !near_edge) return std::nullopt;
  const FlankClearance& fc = side == Flank::Ccw ? pc.ccw : pc.cw;
  if (side == Flank::Ccw ? !(fc.lever_arm_m > 0) : !(fc.lever_arm_m < 0)) return std::nullopt;
  const double delta = closing_angle_rad(model, phi, 0.0, side);
  if (!std::isfinite(delta)) return std::nullopt;
  FlankContact f;
  f.phi_rad = phi;
  f.flank = side;
  f.closing_angle_rad = delta;
  f.lever_m = fc.lever_arm_m;
  f.part_f = fc.part_f;
  f.part_c = fc.part_c;
  f.beyond_tip_circle = !pc.engaged;
  const ToothPlacement place = place_tooth(curve, phi, 0.0);
  f.contact_radius_m = (Eigen::Rotation2Dd(-place.angle_rad) * (fc.point_f - place.offset_m)).norm();
  f.contact_radius_c_m = fc.point_c.norm();  // the circular spline is fixed: frame W is its own
  return f;
}

namespace {

/// The teeth at rest on the rim's curve at one section of the face: its deflection at the major axis, the engaged
/// flanks' first closing turn and their largest overlap (and where).
FaceSection section_at_rest(const GearParams& g, const NeutralCurve& curve, double z_m, double wg_angle_rad) {
  const BacklashModel model = make_backlash_model(g, curve);
  FaceSection fs;
  fs.z_m = z_m;
  fs.w_major_m = curve.at(0.0).w_m;
  fs.first_closing_rad = std::numeric_limits<double>::infinity();
  for (int k = 0; k < g.teeth_flexspline; ++k) {
    const double phi = tooth_material_angle(g, k, wg_angle_rad);
    const PairClearance pc = pair_clearance(model, phi, 0.0);
    if (!pc.engaged) continue;
    for (const Flank side : {Flank::Ccw, Flank::Cw}) {
      const double lever = (side == Flank::Ccw ? pc.ccw : pc.cw).lever_arm_m;
      if (side == Flank::Ccw ? !(lever > 0) : !(lever < 0)) continue;
      const double delta = closing_angle_rad(model, phi, 0.0, side);
      if (!std::isfinite(delta)) continue;
      fs.first_closing_rad = std::min(fs.first_closing_rad, delta);
      if (-std::abs(lever) * delta > fs.overlap_m) {
        fs.overlap_m = -std::abs(lever) * delta;
        fs.overlap_phi_rad = std::remainder(phi, kPi);
      }
    }
  }
  return fs;
}

/// One loaded-contact analysis with the flanks within `reach_factor` body twists at rated torque of the first one on
/// their side. run() is the pipeline; each step is one member function over the state the steps share.
class ContactAnalyser {
public:
  ContactAnalyser(const FlexsplineModel& c, const ContactBody& body, const FemReadout& fem, const ContactOptions& opt,
                  double reach_factor)
      : c_(c), g_(*c.gear), body_(body), fem_(fem), opt_(opt), reach_factor_(reach_factor) {}

  /// The analysis; empty when the twist reaches a flank left out (the caller widens the reach). The model has passed
  /// check_contact_model, the solution has its neutral curve, the rated torque is > 0.
  std::optional<ContactAnalysis> run() {
    read_rim_at_rest();
    select_flanks();
    watch_zone_edges();
    watch_ratchet_teeth();
    compute_influence();
    set_up_problem();
    step_through_torques();
    if (twist_reaches_flanks_left_out()) return std::nullopt;
    if (opt_.contact.friction_coefficient > 0) run_friction_loop();
    describe_curve();
    split_compliance();
    measure_zone_edge_teeth();
    find_ratcheting();
    out_.contact_s += clock_.lap();
    check_independently();
    out_.check_s = clock_.lap();
    progress("contact: " + std::to_string(torques_.size()) + " torque steps on " + std::to_string(out_.unknowns) +
             " contacts in " + std::to_string(out_.contact_s) + " s");
    return std::move(out_);
  }

private:
  struct Slice {
    double z_lo, z_hi;
    NeutralCurve curve;
    BacklashModel model;
    std::vector<PairClearance> rest;
  };

  double tooth_angle(int k) const { return tooth_material_angle(g_, k, opt_.contact.generator_angle_rad); }
  /// Teeth at θ and θ + π are one unknown: only the half turn around the major axis's first end is kept.
  bool on_other_half(double phi) const { return out_.half_turn_pairs && !(phi > -kPi / 2 && phi <= kPi / 2); }
  /// Within `pitches` of a change of engagement (a mesh zone's edge) among the clearances `r`.
  bool near_edge_in(const std::vector<PairClearance>& r, int k, int pitches) const {
    const int zf = g_.teeth_flexspline;
    for (int d = -pitches; d <= pitches; ++d)
      if (r[(k + d + zf) % zf].engaged != r[k].engaged) return true;
    return false;
  }
  bool near_edge(int k, int pitches) const { return near_edge_in(rest_, k, pitches); }
  /// A radial observer (unit outward, per tooth of the unknown) at the flexspline tip of the tooth at material angle
  /// phi on the rim at rest, and at its half-turn partner's: on the whole face (slice −1, the centre section's rim), or
  /// on face slice j's band (its section's rim).
  FlankPattern tip_observer(double phi, int slice = -1) const {
    const ToothPlacement place = place_tooth(slice < 0 ? curve_ : slices_[slice].curve, phi, 0.0);
    const Eigen::Vector2d tip =
        Eigen::Rotation2Dd(place.angle_rad) * Eigen::Vector2d(model_->radii.tip_f, 0.0) + place.offset_m;
    const double s = std::atan2(tip.y(), tip.x());
    std::vector<double> stations{s};
    if (out_.half_turn_pairs) stations.push_back(s + kPi);
    return {stations, Eigen::Vector2d(std::cos(s), std::sin(s)), tip.norm(), slice, 1 / n_teeth_, phi,
            Eigen::Vector2d(model_->radii.tip_f, 0.0)};
  }
  /// The change of the body's loads since rest for contact forces x (flanks, then stations when unilateral): the
  /// flanks' forces and the stations' change from the generator's state, or the band's reactions (band_solve per
  /// flank force: the curve's problem's, or the ramp's turned one) when it is held.
  Eigen::VectorXd load_change(const Eigen::VectorXd& x) const { return load_change(x, band_solve_); }
  Eigen::VectorXd load_change(const Eigen::VectorXd& x, const Eigen::MatrixXd& band_solve) const {
    Eigen::VectorXd dx(nf_ + nb_);
    if (unilateral_) dx << x.head(nf_), x.tail(nb_) - p0_;
    else dx << x, band_solve * x;
    return dx;
  }
  /// The problem at torque T with only the flanks `flanks` (and every station) taking part; empty when they cannot
  /// carry T. The forces come back in the full problem's order, zero for the flanks left out.
  std::optional<ContactSolution> solve_with_flanks(std::vector<Eigen::Index> flanks, double T) {
    return solve_with_flanks(P_, lambda_, std::move(flanks), T);
  }
  /// The same on the problem P whose output moments are `moments`.
  /// `warm`: the forces (in the full problem's order) of a nearby solution, where the active set starts.
  std::optional<ContactSolution> solve_with_flanks(const ContactProblem& P, const Eigen::VectorXd& moments,
                                                   std::vector<Eigen::Index> flanks, double T,
                                                   const Eigen::VectorXd* warm = nullptr);

  void read_rim_at_rest();
  void read_face_sections(std::vector<NeutralCurve>& read);
  void select_flanks();
  void add_flank(FlankContact f, const FlankClearance& fc, int k, int j);
  double deviation_gap(const FlankClearance& fc, int k, int j) const;
  void watch_zone_edges();
  void watch_ratchet_teeth();
  void compute_influence();
  void set_up_problem();
  ContactProblem body_problem(const Eigen::MatrixXd& A_body, const Eigen::VectorXd& q_flank,
                              const Eigen::VectorXd& lever, Eigen::MatrixXd& band_solve) const;
  void set_up_teeth();
  void add_series(ContactProblem& P, const Eigen::MatrixXd& A_cs) const;
  bool coupled_face() const {
    return n_slices_ > 1 && opt_.series.flexspline_tooth_m_per_N && opt_.series.face_shape;
  }
  /// A solve of the contact problem at one torque with the bearing's secants on its diagonal: frictionless
  /// (solve_contact) or with friction along a history (solve_frictional_step from the history's last state); called
  /// with the iterate before (null on the first).
  template <class Problem, class Solution>
  using InnerSolve = std::function<Solution(const Problem&, double T, const Solution* last)>;
  template <class Problem, class Solution>
  Solution solve_step(const Problem& base, Eigen::Index n_fl, double T, const InnerSolve<Problem, Solution>& inner);
  double approach(double p) const {
    return 2 * opt_.series.bearing_approach_m(std::max(p, 0.0) * ball_per_N_);
  }
  double secant(double x, double p, double p_ref) const;
  double output_torque(const Eigen::VectorXd& moments, const ContactSolution& s) const {
    return moments.head(s.force_N.size()).dot(s.force_N) - rest_moment_Nm_;
  }
  /// With friction the flanks' tangential forces carry their share too.
  double output_torque(const Eigen::VectorXd& moments, const FrictionalStep& s) const {
    return moments.head(s.normal_force_N.size()).dot(s.normal_force_N) + lambda_t_.dot(s.tangential_force_N) -
           rest_moment_Nm_;
  }
  template <class Problem, class Solution>
  std::pair<Solution, double> solve_torque(const Problem& base, Eigen::Index n_fl, const Eigen::VectorXd& moments,
                                           double T, const InnerSolve<Problem, Solution>& inner);
  std::pair<ContactSolution, double> solve_torque(const ContactProblem& base, Eigen::Index n_fl,
                                                  const Eigen::VectorXd& moments, double T, const Eigen::VectorXd* warm) {
    const InnerSolve<ContactProblem, ContactSolution> inner = [warm](const ContactProblem& p, double t,
                                                                     const ContactSolution* last) {
      return solve_contact(p, t, last ? &last->force_N : warm);
    };
    return solve_torque(base, n_fl, moments, T, inner);
  }
  void step_through_torques();
  FrictionalContactProblem frictional_problem() const;
  void run_friction_loop();
  TorqueStep torque_step(double T, const ContactSolution& s);
  void follow_edge_teeth(const ContactSolution& s);
  bool twist_reaches_flanks_left_out();
  void describe_curve();
  void split_compliance();
  void measure_zone_edge_teeth();
  void find_ratcheting();
  void check_independently();

  const FlexsplineModel& c_;
  const GearParams& g_;
  const ContactBody& body_;
  const FemReadout& fem_;
  const ContactOptions& opt_;
  const double reach_factor_;
  Stopwatch clock_;
  ContactAnalysis out_;
  double n_teeth_ = 1;  // teeth per unknown
  int n_slices_ = 1;
  // The gear on the rim as the generator leaves it: the centre section, and each slice of the face.
  NeutralCurve curve_;
  std::optional<BacklashModel> model_;
  std::vector<PairClearance> rest_;
  std::vector<Slice> slices_;
  double first_closing_[2] = {std::numeric_limits<double>::infinity(), std::numeric_limits<double>::infinity()};
  double reach_ = 0;
  // The patterns: flanks' columns and gaps, the edge teeth's radial observers.
  std::vector<FlankPattern> patterns_, observers_, tangential_;  // tangential_: with friction or the ramp
  std::vector<FlankPattern> cs_patterns_, cs_tangential_;  // the flanks' forces on the circular spline
  std::vector<double> q_flank_;
  Eigen::MatrixXd teeth_;        // the tooth pairs in series per unknown (set_up_teeth)
  Eigen::Index nf_ = 0, nb_ = 0, no_ = 0;
  // The ratcheting ramp: the teeth that can carry, radial observers at their tips on the rim and on the ring, and
  // which of them each flank belongs to.
  std::vector<RatchetTooth> ratchet_teeth_;
  std::vector<FlankPattern> ratchet_rim_, ratchet_ring_;
  std::vector<std::size_t> ratchet_tooth_of_flank_;
  Eigen::Index nr_ = 0;
  /// The ramp's climbing contacts: each flank's force turned in the transverse plane by β from its direction at rest
  /// (cos β along its normal pattern, sin β along its tangential one); the blocks that turn with it, over the normal
  /// patterns, the tangential ones and the stations (2 nf + nb).
  struct ClimbBlocks {
    Eigen::MatrixXd body, rim;      // the body's coefficients; the ramp's rim observers against them
    Eigen::MatrixXd cs, ring;       // the circular spline's (2 nf); its tip observers against them
    Eigen::VectorXd lever;
    std::vector<ClosedFlank> rest;  // each flank closed with its tooth as placed
    std::vector<Eigen::Vector2d> centre_line;  // its tooth's centre line at rest (unit, outward)
  };
  /// The problem with the flanks' forces turned by β, their levers scaled by lever_scale and their gaps moved by dq:
  /// its levers (the output's moments) and the band's reactions per flank force when the generator holds it.
  struct ClimbedProblem {
    ContactProblem P;
    Eigen::VectorXd moments;
    Eigen::VectorXd cos, sin;  // of each flank's β
    Eigen::MatrixXd band_solve;
    Eigen::VectorXd parts(const Eigen::VectorXd& dx) const;
  };
  ClimbBlocks climb_blocks() const;
  ClimbedProblem climbed_problem(const ClimbBlocks& b, const Eigen::VectorXd& beta, const Eigen::VectorXd& dq,
                                 const Eigen::VectorXd& lever_scale) const;
  /// One round's contacts: each flank of `keep` that the torque T closes met with its tooth parted by `parting` (its
  /// force's turn β, its lever's scale, its gap's move dq, the parts that touch; the others only open further and stay
  /// as at rest), and the teeth loaded in `last` that are parted so far that no rigid turn closes them (tips passing).
  struct Climb {
    Eigen::VectorXd beta, dq, scale;
    std::vector<std::string> where;
    std::vector<Eigen::Index> past_tips;
  };
  Climb climb(const ClimbBlocks& b, const std::vector<Eigen::Index>& keep, double T, const Eigen::VectorXd& parting,
              const RatchetState* last) const;
  /// The teeth after the climbed problem's solve s: the rim in and the ring out at each tooth's tip, the overlap
  /// left, and the flank that carries each tooth most (its normal's turn, where it touches).
  RatchetState ratchet_state(const ClimbBlocks& b, const ClimbedProblem& cp, const ContactSolution& s,
                             const Climb& c) const;
  /// The ramp's counts (its progress line) and the last round's forces, where the next solve's active set starts.
  struct RampCount {
    long solves = 0, rounds = 0;
    double geometry_s = 0, solve_s = 0;
    Eigen::VectorXd warm_forces;
  };
  /// The ramp's solve (RatchetSolve) at T with the teeth `carry`: the climb's rounds to a settled parting.
  std::optional<RatchetState> ratchet_solve(const ClimbBlocks& b, double T, const std::vector<bool>& carry,
                                            RampCount& n);
  // Influence coefficients.
  bool unilateral_ = false;
  BodyInfluence influence_;
  Eigen::MatrixXd A_body_, R_edge_;
  Eigen::MatrixXd A_tn_, A_tt_;  ///< with friction: the tangential patterns' rows against the body's, and their own
  Eigen::VectorXd lambda_;
  Eigen::VectorXd lambda_t_;  ///< the tangential forces' levers (flanks; 0 at the stations), with friction
  // The contact problem, its generator state and the bearing's secants.
  ContactProblem P_;
  Eigen::VectorXd p0_;
  Eigen::MatrixXd band_solve_, A_noseries_;
  CircularSplineBlock cs_;
  bool bearing_ = false;
  double ball_per_N_ = 0;
  Eigen::VectorXd bearing_c_;
  bool secants_from_last_ = false;  ///< solve_step starts from bearing_c_ as it stands (the ramp's rounds)
  // The torque steps.
  std::vector<double> torques_;
  int N_ = 1;
  double T_R_ = 0, rest_moment_Nm_ = 0;
  ContactSolution at_rated_;
  TorqueTwist middle_line_;  ///< with friction: the loop's middle line, on which the catalog's figures are read
  double flanks_torque_at_rated_ = 0;
};

void ContactAnalyser::read_rim_at_rest() {
  out_.rated_torque_Nm = opt_.rated_torque_Nm;
  const NeutralCurveSamples& nc = fem_.neutral_curve;
  curve_ = fem_neutral_curve(nc);
  model_.emplace(make_backlash_model(g_, curve_));
  out_.half_turn_pairs = g_.teeth_flexspline % 2 == 0;
  n_teeth_ = out_.half_turn_pairs ? 2.0 : 1.0;
  // The face width in axial slices, each with the rim as the generator leaves it at the slice's centre (the FEM's
  // generator case read there: the cup's coning). One slice is the centre section's curve itself.
  n_slices_ = std::max(1, opt_.contact.face_slices);
  std::vector<NeutralCurve> read;
  read_face_sections(read);
  if (n_slices_ > 1 && read.empty())
    throw InputError("contact.face_slices = " + std::to_string(n_slices_) +
                     " reads the FEM's rim at every slice, and a result read back (--fem) has only its centre section; "
                     "run contact without --fem (or face_slices = 1)");
  const double face = c_.flexspline.rim_width_m;
  for (int j = 0; j < n_slices_; ++j) {
    const FaceSlice f = face_slice(j, n_slices_);
    const double z_lo = nc.z_m - face / 2 + face * f.lo, z_hi = nc.z_m - face / 2 + face * f.hi;
    const NeutralCurve& cj = n_slices_ > 1 ? read[2 + j] : curve_;
    slices_.push_back({z_lo, z_hi, cj, n_slices_ > 1 ? make_backlash_model(g_, cj) : *model_, {}});
  }
  out_.face_slices = n_slices_;
  // The flanks that can close: within reach of the first one on their side (over every slice).
  rest_.resize(g_.teeth_flexspline);
  for (int k = 0; k < g_.teeth_flexspline; ++k) rest_[k] = pair_clearance(*model_, tooth_angle(k), 0.0);
  for (Slice& sl : slices_) {
    sl.rest.resize(g_.teeth_flexspline);
    for (int k = 0; k < g_.teeth_flexspline; ++k) {
      const double phi = tooth_angle(k);
      sl.rest[k] = n_slices_ == 1 ? rest_[k] : pair_clearance(sl.model, phi, 0.0);
      if (!sl.rest[k].engaged) continue;
      for (const Flank side : {Flank::Ccw, Flank::Cw})
        first_closing_[side == Flank::Cw] =
            std::min(first_closing_[side == Flank::Cw], closing_angle_rad(sl.model, phi, 0.0, side));
    }
  }
}

/// Sections read from the FEM's generator case in one pass: the face's ends, then the slices' centres (if sliced);
/// the face's ends and centre at rest: how the coning moves the teeth's clearance across the face.
void ContactAnalyser::read_face_sections(std::vector<NeutralCurve>& read) {
  const NeutralCurveSamples& nc = fem_.neutral_curve;
  const double face = c_.flexspline.rim_width_m;
  std::vector<double> z_read = {nc.z_m - face / 2, nc.z_m + face / 2};
  for (int j = 0; j < n_slices_ && n_slices_ > 1; ++j)
    z_read.push_back(face_section_z_m(nc.z_m, face, j, n_slices_));
  for (const NeutralCurveSamples& at : body_.generator_curves_at(z_read))
    read.push_back(fem_neutral_curve(at));
  if (!read.empty())
    for (const auto& [z, cz] : {std::pair<double, const NeutralCurve&>{nc.z_m - face / 2, read[0]}, {nc.z_m, curve_},
                                {nc.z_m + face / 2, read[1]}})
      out_.face_sections.push_back(section_at_rest(g_, cz, z, opt_.contact.generator_angle_rad));
}

void ContactAnalyser::select_flanks() {
  reach_ = reach_factor_ * std::abs(fem_.compliance_rad_per_Nm) * opt_.rated_torque_Nm;
  out_.reach_rad = reach_;
  for (int j = 0; j < n_slices_; ++j) {
    const Slice& sl = slices_[j];
    for (int k = 0; k < g_.teeth_flexspline; ++k) {
      const double phi = tooth_angle(k);
      if (on_other_half(phi)) continue;
      const PairClearance& pc = sl.rest[k];
      // The rim moves radially under load and the zones widen: the free teeth within two pitches of an edge take
      // part. Their gap is the exact rigid turn that closes the flank, as for the engaged teeth, and not the distance
      // of the closest points: near an edge those are the two tip corners, and a turn of the rim carries the tooth
      // along the wave, down past the other corner (seed: 3.7 µm apart, but a turn of 5.3e-3 rad to close, not
      // 2.3e-4), so the distance would let a turn close a flank that it cannot, and the gap would jump by 20× where
      // the tooth crosses the tip circle.
      const bool edge = near_edge_in(sl.rest, k, 2);
      for (const Flank side : {Flank::Ccw, Flank::Cw}) {
        std::optional<FlankContact> cand = candidate_flank(sl.model, sl.curve, pc, phi, side, edge);
        if (!cand || (pc.engaged && cand->closing_angle_rad > first_closing_[side == Flank::Cw] + reach_)) continue;
        add_flank(*cand, side == Flank::Ccw ? pc.ccw : pc.cw, k, j);
      }
    }
  }
  if (out_.flanks.empty()) throw InputError("contact: no tooth flank in the mesh zone can close");
  out_.min_closing_rad = std::min(first_closing_[0], first_closing_[1]);
  for (const double q : q_flank_) out_.overlap_at_rest_m = std::max(out_.overlap_at_rest_m, -q / n_teeth_);
  nf_ = static_cast<Eigen::Index>(out_.flanks.size());
}

/// The flank of tooth k in slice j: its pair's compliance in series, its load pattern and its gap.
void ContactAnalyser::add_flank(FlankContact f, const FlankClearance& fc, int k, int j) {
  f.tooth = k;
  f.slice = j;
  f.compliance_m_per_N = opt_.series.tooth_pair_m_per_N
                             ? opt_.series.tooth_pair_m_per_N(f.contact_radius_m, f.contact_radius_c_m) /
                                   face_slice(j, n_slices_).width()
                             : 0.0;
  const double s = std::atan2(fc.point_f.y(), fc.point_f.x());
  std::vector<double> stations{s};
  if (out_.half_turn_pairs) stations.push_back(s + kPi);
  // Where the load sits on the tooth itself, for a body with explicit teeth: the contact point taken back into the
  // tooth's own frame by the tooth's placement on the slice's rim.
  const ToothPlacement place = place_tooth(slices_[j].curve, f.phi_rad, 0.0);
  const Eigen::Vector2d on_tooth = Eigen::Rotation2Dd(-place.angle_rad) * (fc.point_f - place.offset_m);
  // One slice loads the whole face; more, each its own band of the rim.
  patterns_.push_back({stations, -fc.normal, fc.point_f.norm(), n_slices_ > 1 ? j : -1, 1, f.phi_rad, on_tooth});
  // With friction, the flank's tangential force: along the profile in the transverse plane (the normal turned by 90°);
  // for the ratcheting ramp, the part its force takes on as the contact climbs and the normal turns.
  if (opt_.contact.friction_coefficient > 0 || opt_.ratcheting_ceiling_Nm > 0)
    tangential_.push_back({stations, Eigen::Vector2d(fc.normal.y(), -fc.normal.x()), fc.point_f.norm(),
                           n_slices_ > 1 ? j : -1, 1, f.phi_rad, on_tooth});
  // Its force on the circular spline: the opposite, at the contact point on the circular spline's tooth.
  const double c = std::atan2(fc.point_c.y(), fc.point_c.x());
  std::vector<double> on_cs{c};
  if (out_.half_turn_pairs) on_cs.push_back(c + kPi);
  cs_patterns_.push_back({on_cs, fc.normal, fc.point_c.norm(), n_slices_ > 1 ? j : -1});
  if (opt_.ratcheting_ceiling_Nm > 0)  // the circular spline's side of the tangential pattern
    cs_tangential_.push_back({on_cs, Eigen::Vector2d(-fc.normal.y(), fc.normal.x()), fc.point_c.norm(),
                              n_slices_ > 1 ? j : -1});
  q_flank_.push_back(n_teeth_ * (std::abs(f.lever_m) * f.closing_angle_rad + deviation_gap(fc, k, j)));
  out_.flanks.push_back(f);
}

/// How tooth k's and its circular spline tooth's pitch deviations change the flank's gap (m): the flexspline's tooth
/// moved along the rim by e_f (an output turn of e_f/r_f: −lever·e_f/r_f), the circular spline's tooth turned about
/// the axis by e_c/r_c ((p_c × n)·e_c/r_c). The ccw flank touches the circular spline tooth ccw of the space the
/// tooth faces, the cw flank the one cw of it (tooth i of the circular spline lies between spaces i and i + 1).
double ContactAnalyser::deviation_gap(const FlankClearance& fc, int k, int j) const {
  const ToothDeviations& d = opt_.deviations;
  double gap = 0;
  if (!d.flexspline_m.empty())
    gap -= fc.lever_arm_m * d.flexspline_m[k] / (g_.module_m * g_.teeth_flexspline / 2);
  if (!d.circular_spline_m.empty()) {
    const int zc = g_.teeth_circular;
    const bool ccw = fc.lever_arm_m > 0;
    const int i = (((k + slices_[j].rest[k].space - (ccw ? 0 : 1)) % zc) + zc) % zc;
    const double cross = fc.point_c.x() * fc.normal.y() - fc.point_c.y() * fc.normal.x();
    gap += cross * d.circular_spline_m[i] / (g_.module_m * zc / 2);
  }
  return gap;
}

/// The zones' edges: the teeth within three pitches of a change of engagement. Whether such a tooth can touch at all
/// is its radial overlap, which the rim's radial motion under load changes: a radial observer pattern at its tip reads
/// that motion at every step (the tooth's own bending moves its tip along the pitch circle, not radially, and is left
/// out).
void ContactAnalyser::watch_zone_edges() {
  for (int k = 0; k < g_.teeth_flexspline; ++k) {
    const double phi = tooth_angle(k);
    if (on_other_half(phi) || !near_edge(k, 3)) continue;
    observers_.push_back(tip_observer(phi));
    EdgeTooth e;
    e.tooth = k;
    e.phi_rad = phi;
    e.engaged = rest_[k].engaged;
    e.overlap_at_rest_m = e.overlap_min_m = e.overlap_max_m = rest_[k].depth_m;
    e.candidate =
        std::any_of(out_.flanks.begin(), out_.flanks.end(), [&](const FlankContact& f) { return f.tooth == k; });
    out_.edges.push_back(e);
  }
  no_ = static_cast<Eigen::Index>(observers_.size());
}

/// For the ratcheting ramp: every tooth with a flank in the problem, in each section of the face where it has one
/// (straight teeth on a coned rim overlap differently at the face's ends, so each section lets go on its own): its
/// overlap at rest there and radial observers at its tip, on the rim over the section's band (as the zone edges', on
/// the whole face with one section) and on the circular spline's tip circle over the same band at the same angle.
void ContactAnalyser::watch_ratchet_teeth() {
  if (opt_.ratcheting_ceiling_Nm <= 0) return;
  for (const FlankContact& f : out_.flanks) {
    std::size_t t = 0;
    while (t < ratchet_teeth_.size() && !(ratchet_teeth_[t].tooth == f.tooth && ratchet_teeth_[t].slice == f.slice))
      ++t;
    ratchet_tooth_of_flank_.push_back(t);
    if (t < ratchet_teeth_.size()) continue;
    const int band = n_slices_ > 1 ? f.slice : -1;
    ratchet_teeth_.push_back({f.tooth, f.phi_rad, slices_[f.slice].rest[f.tooth].depth_m, f.slice});
    const FlankPattern rim = tip_observer(f.phi_rad, band);
    ratchet_rim_.push_back(rim);
    // The ring's at the same angle and along the same radial line, on the circular spline's tip circle.
    ratchet_ring_.push_back({rim.stations_rad, rim.force_dir, model_->radii.tip_c, band, 1 / n_teeth_});
  }
  nr_ = static_cast<Eigen::Index>(ratchet_teeth_.size());
}

/// The generator's stations, and the influence coefficients of every pattern.
void ContactAnalyser::compute_influence() {
  unilateral_ = body_.stations().unilateral;
  nb_ = static_cast<Eigen::Index>(body_.stations().angle_rad.size());
  out_.setup_s = clock_.lap();
  progress("contact: influence of " + std::to_string(nf_) + " flank patterns, " + std::to_string(nb_) +
           " generator stations and " + std::to_string(no_) + " zone-edge observers");
  std::vector<FlankPattern> all = observers_;
  all.insert(all.end(), ratchet_rim_.begin(), ratchet_rim_.end());
  all.insert(all.end(), patterns_.begin(), patterns_.end());
  all.insert(all.end(), tangential_.begin(), tangential_.end());
  influence_ = body_.influence(all, n_slices_);
  // Columns: observers (the zone edges', the ratcheting ramp's), flanks, tangential patterns (with friction or the ramp), stations.
  const Eigen::Index nt = static_cast<Eigen::Index>(tangential_.size()), n_obs = no_ + nr_;
  std::vector<Eigen::Index> body, obs, tan;
  for (Eigen::Index i = 0; i < no_; ++i) obs.push_back(i);
  for (Eigen::Index i = 0; i < nf_; ++i) body.push_back(n_obs + i);
  for (Eigen::Index i = 0; i < nt; ++i) tan.push_back(n_obs + nf_ + i);
  for (Eigen::Index i = 0; i < nb_; ++i) body.push_back(n_obs + nf_ + nt + i);
  A_body_ = influence_.A(body, body);
  R_edge_ = influence_.A(obs, body);  // radial motion at the edge teeth's tips
  A_tn_ = influence_.A(tan, body);
  A_tt_ = influence_.A(tan, tan);
  out_.influence_s = clock_.lap();
  lambda_ = influence_.lever(body);
  lambda_t_ = Eigen::VectorXd::Zero(nf_ + nb_);
  if (nt > 0) lambda_t_.head(nf_) = influence_.lever(tan);
}

/// The contact problem. Unilateral generator: flanks and stations together, the stations' gaps against the
/// generator's surface, the flanks' gaps measured in the generator's state (p0). Force idealisation: the band held
/// radially (bilateral), eliminated.
void ContactAnalyser::set_up_problem() {
  const Eigen::Index nf = nf_;
  if (unilateral_) {
    p0_ = unilateral_contact(A_body_.bottomRightCorner(nb_, nb_), fem_.generator_obstacle_m).force_N;
    out_.generator_support = "the generator's contact (" + fem_.generator_model + ", unilateral) in the same problem";
  } else {
    out_.generator_support = "the band held radially at the stations (the paper's given-force idealisation)";
  }
  P_ = body_problem(A_body_, Eigen::Map<const Eigen::VectorXd>(q_flank_.data(), nf), lambda_, band_solve_);
  A_noseries_ = P_.A;
  cs_.A = Eigen::MatrixXd::Zero(nf, nf);
  if (opt_.series.circular_spline) cs_ = opt_.series.circular_spline(cs_patterns_);
  set_up_teeth();
  add_series(P_, cs_.A);
  out_.unknowns = static_cast<int>(P_.q.size());
  out_.problem = P_;
  // Bearing balls in series with the stations (unilateral generators): the secant of the Hertzian approach from the
  // generator's state, iterated to a fixed point.
  bearing_ = unilateral_ && opt_.series.bearing_approach_m && opt_.series.bearing_balls > 0;
  ball_per_N_ = bearing_ ? 2 * kPi / (opt_.series.bearing_balls * body_.stations().half_width_rad) : 0.0;
  bearing_c_ = Eigen::VectorXd::Zero(nb_);
}

/// The problem on the body's coefficients A_body (flanks, then stations) with the flanks' gaps q_flank and the levers
/// (flanks, then stations), before the parts in series: with a unilateral generator the stations take part (their
/// gaps the generator's obstacle, the flanks' measured from its state p0, a turn of the output leaving the stations'
/// gaps alone); with the band held radially the stations are eliminated, their reactions per flank force in
/// band_solve.
ContactProblem ContactAnalyser::body_problem(const Eigen::MatrixXd& A_body, const Eigen::VectorXd& q_flank,
                                             const Eigen::VectorXd& lever, Eigen::MatrixXd& band_solve) const {
  const Eigen::Index nf = nf_, nb = nb_;
  ContactProblem P;
  if (unilateral_) {
    P.A = A_body;
    P.q.resize(nf + nb);
    P.q.head(nf) = q_flank - A_body.topRightCorner(nf, nb) * p0_;
    P.q.tail(nb) = -fem_.generator_obstacle_m;
    // A turn of the output leaves the stations' gaps alone: the flexspline turns on the generator's bearing while
    // the deformation wave stays with the cam. (In the linear model a rigid turn would also turn the wave, and a
    // non-circular cam would then hold the output back with a stiffness it does not have.) The stations' forces still
    // have a moment about the axis through the cam's tilted normal: the locked generator's share of the torque.
    P.lambda = lever;
    P.lambda.tail(nb).setZero();
  } else {
    const Eigen::LDLT<Eigen::MatrixXd> bb(A_body.bottomRightCorner(nb, nb));
    band_solve = -bb.solve(A_body.bottomLeftCorner(nb, nf));
    P.A = A_body.topLeftCorner(nf, nf) + A_body.topRightCorner(nf, nb) * band_solve;
    P.A = 0.5 * (P.A + P.A.transpose()).eval();
    P.q = q_flank;
    P.lambda = lever.head(nf);
  }
  return P;
}

/// The tooth pairs in series, per unknown: each flank's pair on the diagonal and, with the face coupled, a solid
/// flexspline tooth's flanks on one side sharing their loads across the face's sections. The flexspline tooth's part
/// t (m/N over the face) of flank i in section j and i' in j' couples as sqrt(t_i·t_i')·G(j, j') (G the face's shape,
/// contact/tooth_fem.hpp FaceCoupling), which for one contact radius is the slabs' own C; its diagonal replaces the
/// springs' t/w_j. Each flank's compliance_m_per_N becomes its diagonal.
void ContactAnalyser::set_up_teeth() {
  teeth_ = Eigen::MatrixXd::Zero(nf_, nf_);
  for (Eigen::Index i = 0; i < nf_; ++i) teeth_(i, i) = n_teeth_ * out_.flanks[i].compliance_m_per_N;
  if (!coupled_face()) return;
  const Eigen::MatrixXd G = opt_.series.face_shape(n_slices_);
  if (G.rows() != n_slices_ || G.cols() != n_slices_)
    throw std::invalid_argument("contact: the face's coupling is not one row and column per face section");
  Eigen::VectorXd t(nf_);  // each flank's flexspline tooth part over the face (m/N)
  for (Eigen::Index i = 0; i < nf_; ++i) t[i] = opt_.series.flexspline_tooth_m_per_N(out_.flanks[i].contact_radius_m);
  for (Eigen::Index i = 0; i < nf_; ++i)
    for (Eigen::Index k = 0; k < nf_; ++k) {
      const FlankContact &a = out_.flanks[i], &b = out_.flanks[k];
      if (a.tooth != b.tooth || a.flank != b.flank) continue;
      const double springs = a.slice == b.slice ? 1.0 / face_slice(a.slice, n_slices_).width() : 0.0;
      teeth_(i, k) += n_teeth_ * std::sqrt(t[i] * t[k]) * (G(a.slice, b.slice) - springs);
    }
  for (Eigen::Index i = 0; i < nf_; ++i) out_.flanks[i].compliance_m_per_N = teeth_(i, i) / n_teeth_;
}

/// The parts in series with the body: the circular spline's block on the flanks and the tooth pairs (set_up_teeth).
void ContactAnalyser::add_series(ContactProblem& P, const Eigen::MatrixXd& A_cs) const {
  P.A.topLeftCorner(nf_, nf_) += A_cs + teeth_;
}

/// The secant of the approach between the preload p and x; where the two are too close for a difference quotient to
/// be exact (near zero torque), the tangent at their midpoint: the same value to O(h²), without the round-off that
/// made the fixed point below cycle.
double ContactAnalyser::secant(double x, double p, double p_ref) const {
  const double d = x - p, h = 1e-4 * std::max(std::abs(p), 1e-3 * p_ref);
  if (std::abs(d) > h) return (approach(x) - approach(p)) / d;
  const double m = 0.5 * (x + p);
  return (approach(m + h) - approach(m - h)) / (2 * h);
}

/// One torque on a problem whose first n_fl unknowns are flanks and whose last nb are the generator's stations.
///
/// The bearing's secants are iterated to their fixed point, relaxed: where a station lifts off and lands again from
/// one pass to the next the plain iteration cycles between two states (size 17 at w0 + 14 %), so the step is halved
/// whenever the residual does not shrink. The residual is each station's Hertzian approach as the secant gives it less
/// the law's, a length. Converged at 1e-4 of the largest preload's approach (0.7 nm on a size-20 bearing whose balls
/// approach 7 µm): the twist it makes is below 1e-4 arcmin, while the races' roughness alone is some 50 nm. A station
/// that carries almost nothing is where the law Q^(2/3) has no finite slope and the iteration crawls; past the
/// iteration limit the best iterate stands when its residual is within 1e-2 of that approach (a twist below 0.01
/// arcmin), with a line saying so; beyond that the stage stops and says where.
template <class Problem, class Solution>
Solution ContactAnalyser::solve_step(const Problem& base, Eigen::Index n_fl, double T,
                                     const InnerSolve<Problem, Solution>& inner) {
  if (!bearing_) return inner(base, T, nullptr);
  constexpr int kIterations = 400;
  constexpr double kConverged = 1e-4, kAcceptable = 1e-2;  // of the largest preload's approach
  Problem Pb = base;
  const double p_ref = std::max(p0_.maxCoeff(), 1.0), approach_ref_m = approach(p_ref);
  if (!secants_from_last_)  // else the last solve's secants: a nearby state's (the ratcheting ramp's rounds)
    for (Eigen::Index k = 0; k < nb_; ++k) bearing_c_[k] = secant(p0_[k], p0_[k], p_ref);  // the tangent at the preload
  Solution s, best;
  double best_residual = std::numeric_limits<double>::infinity();
  Eigen::Index worst_station = 0;
  double relax = 1.0, last = std::numeric_limits<double>::infinity();
  for (int it = 0; it < kIterations; ++it) {
    for (Eigen::Index k = 0; k < nb_; ++k) {
      Pb.A(n_fl + k, n_fl + k) = base.A(n_fl + k, n_fl + k) + bearing_c_[k];
      Pb.q[n_fl + k] = base.q[n_fl + k] - bearing_c_[k] * p0_[k];
    }
    s = inner(Pb, T, it == 0 ? nullptr : &s);
    const Eigen::VectorXd& force = normal_forces(s);
    double residual = 0;
    Eigen::Index worst = 0;
    Eigen::VectorXd c_new(nb_);
    for (Eigen::Index k = 0; k < nb_; ++k) {
      const double x = force[n_fl + k];
      c_new[k] = secant(x, p0_[k], p_ref);
      const double r = std::abs(bearing_c_[k] * (x - p0_[k]) - (approach(x) - approach(p0_[k])));
      if (r > residual) residual = r, worst = k;
    }
    if (residual <= kConverged * approach_ref_m) return s;
    if (residual < best_residual) best = s, best_residual = residual, worst_station = worst;
    if (residual >= last) relax = std::max(relax / 2, 1.0 / 1024);
    last = residual;
    bearing_c_ += relax * (c_new - bearing_c_);
  }
  const std::string where = "at T = " + std::to_string(T) + " N·m the generator bearing's ball loads did not settle in " +
                            std::to_string(kIterations) + " relaxed secant iterations: the station at " +
                            std::to_string(body_.stations().angle_rad[worst_station] * 180 / kPi) + " deg (" +
                            std::to_string(normal_forces(best)[n_fl + worst_station]) + " N, at rest " +
                            std::to_string(p0_[worst_station]) + " N) is off its Hertzian approach by " +
                            std::to_string(best_residual * 1e9) + " nm";
  if (best_residual > kAcceptable * approach_ref_m)
    throw InputError("contact: " + where + ", more than 1 % of the largest ball approach (" +
                     std::to_string(approach_ref_m * 1e9) + " nm). That station lifts off and lands again between "
                     "iterations; a finer [mesh] or another generator fit (wave_generator.fit_um) moves it off that edge");
  progress("contact: " + where + " (under 1 % of the largest ball approach, " + std::to_string(approach_ref_m * 1e9) +
           " nm): the best iterate stands");
  return best;
}

/// The output's torque is what the flanks carry plus the locked generator's share (λ with the stations' moment arms)
/// beyond its moment at rest: find the flanks' torque that gives T. The share is about 1/ratio of it, so T_out is
/// nearly affine in T_flanks: secant steps. Returns the solution and the flanks' torque. `warm`: the forces of a nearby
/// solution of the same problem (the previous torque step), where the active set starts.
template <class Problem, class Solution>
std::pair<Solution, double> ContactAnalyser::solve_torque(const Problem& base, Eigen::Index n_fl,
                                                          const Eigen::VectorXd& moments, double T,
                                                          const InnerSolve<Problem, Solution>& inner) {
  Solution s;
  bool warm = false;  // after the first: each inner solve starts from the last one's contact set
  const InnerSolve<Problem, Solution> from_last = [&](const Problem& p, double t, const Solution* last) {
    return inner(p, t, last ? last : (warm ? &s : nullptr));
  };
  double T_flanks = T, prev_flanks = 0, prev_out = 0;
  for (int it = 0;; ++it) {
    s = solve_step(base, n_fl, T_flanks, from_last);
    warm = true;
    const double T_out = output_torque(moments, s);
    // Settled to 1e-13 of T, or to 1e-11 of the rated torque at the limits at zero, where the moments' round-off
    // is larger than 1e-13 of T.
    if (std::abs(T_out - T) <= std::max(1e-13 * std::abs(T), 1e-11 * T_R_)) break;
    const double slope = it == 0 || T_out == prev_out ? 1.0 : (T_flanks - prev_flanks) / (T_out - prev_out);
    if (it == 50)
      throw InputError("contact: the flanks' share of T = " + std::to_string(T) + " N·m did not settle in 50 secant "
                       "steps (the output carries " + std::to_string(T_out) + " N·m; the generator's locked share "
                       "jumps between steps: a finer [mesh] moves the stations off that edge)");
    prev_flanks = T_flanks;
    prev_out = T_out;
    T_flanks += slope * (T - T_out);
  }
  return {s, T_flanks};
}

/// Torque steps from −rated to +rated, the two limits at zero (a drive with play jumps there).
void ContactAnalyser::step_through_torques() {
  N_ = std::max(1, opt_.steps);
  T_R_ = opt_.rated_torque_Nm;
  flanks_torque_at_rated_ = T_R_;
  for (int s = -N_; s <= N_; ++s) {
    if (s == 0) {
      torques_.push_back(-1e-6 * T_R_);
      torques_.push_back(1e-6 * T_R_);
    } else {
      torques_.push_back(T_R_ * s / N_);
    }
  }
  // The generator's preload has a moment about the axis only through the mesh's round-off (zero by symmetry: 1e-3 N·m
  // on a coarse size-17 cup); the output's torque is counted from it, so that the limits at zero stay either side of
  // the play instead of on the side the round-off picks.
  rest_moment_Nm_ = unilateral_ ? lambda_.tail(nb_).dot(p0_) : 0.0;
  Eigen::VectorXd previous;  // the last step's forces: the next step starts from its contact set
  for (const double T : torques_) {
    const auto [s, T_flanks] = solve_torque(P_, nf_, lambda_, T, previous.size() ? &previous : nullptr);
    previous = s.force_N;
    const TorqueStep st = torque_step(T, s);
    out_.torque_balance_error_rel = std::max(out_.torque_balance_error_rel, st.balance_error_rel);
    out_.steps.push_back(st);
    out_.curve.torque_Nm.push_back(st.torque_Nm);
    out_.curve.twist_rad.push_back(st.twist_rad);
    if (T == torques_.back()) {
      at_rated_ = s;
      flanks_torque_at_rated_ = T_flanks;
    }
  }
  // The limits at zero stand for T = 0 from either side.
  for (std::size_t i = 0; i < out_.steps.size(); ++i)
    if (std::abs(out_.steps[i].torque_Nm) < 1e-3 * T_R_) out_.curve.torque_Nm[i] = out_.steps[i].torque_Nm = 0.0;
  out_.contact_s = clock_.lap();
}

/// The contact problem with the flanks' tangential forces: the tangential patterns' blocks (the band's stations
/// condensed out as in the normal problem when the generator holds the band radially), the friction coefficient on
/// the flanks; the generator's stations roll, frictionless. The tooth pairs' own compliance is on the normal diagonal
/// only (the teeth are rigid along the profile: an idealisation).
FrictionalContactProblem ContactAnalyser::frictional_problem() const {
  FrictionalContactProblem F;
  static_cast<ContactProblem&>(F) = P_;
  const Eigen::Index n = P_.q.size();
  F.A_tn = Eigen::MatrixXd::Zero(n, n);
  F.A_tt = Eigen::MatrixXd::Zero(n, n);
  if (unilateral_) {
    F.A_tn.topRows(nf_) = A_tn_;
    F.A_tt.topLeftCorner(nf_, nf_) = A_tt_;
  } else {
    const Eigen::MatrixXd A_ts = A_tn_.rightCols(nb_);
    F.A_tn = A_tn_.leftCols(nf_) + A_ts * band_solve_;
    F.A_tt = A_tt_ - A_ts * A_body_.bottomRightCorner(nb_, nb_).ldlt().solve(A_ts.transpose());
  }
  for (Eigen::Index k = nf_; k < n; ++k) F.A_tt(k, k) = A_tt_.diagonal().mean();  // keeps the block definite
  F.lambda_t = lambda_t_.head(n);
  F.friction_coefficient = Eigen::VectorXd::Zero(n);
  F.friction_coefficient.head(nf_).setConstant(opt_.contact.friction_coefficient);
  return F;
}

/// The catalog's load cycle with friction, each step settled like the frictionless curve's (the bearing's secants,
/// the flanks' share of the output torque), run until a cycle ends in the state it started from to 1e-4 (at most 4
/// cycles); the last cycle's loop and its readings.
void ContactAnalyser::run_friction_loop() {
  Stopwatch loop_clock;
  const FrictionalContactProblem F = frictional_problem();
  const LoadStep step = [&](double T, const FrictionalStep& previous) {
    const InnerSolve<FrictionalContactProblem, FrictionalStep> inner =
        [&previous](const FrictionalContactProblem& p, double t, const FrictionalStep* last) {
          return solve_frictional_step(p, t, previous, last);
        };
    FrictionalStep s = solve_torque(F, nf_, lambda_, T, inner).first;
    s.torque_Nm = T;  // the output's (the flanks carry T less the locked generator's share)
    return s;
  };
  const Eigen::VectorXd at_rated = bearing_c_;  // the frictionless curve's at +rated, which the split reads
  const int N = std::max(1, opt_.loop_steps_per_quarter);
  const SteadyLoop loop = run_steady_loop(step, unloaded_state(F), T_R_, N, 1e-4, 4);
  bearing_c_ = at_rated;
  FrictionLoop f;
  f.friction_coefficient = opt_.contact.friction_coefficient;
  f.steps_per_quarter = N;
  f.cycles = loop.cycles;
  static_cast<LoopFigures&>(f) = loop.reading;
  middle_line_ = middle_line(loop.reading.loop.loading, loop.reading.loop.unloading);
  std::vector<double> torques;
  for (const FrictionalStep& s : loop.history) torques.push_back(s.torque_Nm);
  const LoadCycle c = last_load_cycle(torques);
  auto add = [&](std::size_t i, const char* branch) {
    const FrictionalStep& s = loop.history[i];
    TorqueStep t;
    t.torque_Nm = std::abs(s.torque_Nm) < kZeroTorqueSnap * T_R_ ? 0.0 : s.torque_Nm;
    t.twist_rad = s.twist_rad;
    t.branch = branch;
    t.flank_force_N.assign(s.normal_force_N.data(), s.normal_force_N.data() + nf_);
    for (Eigen::Index k = 0; k < nf_; ++k)
      if (s.normal_force_N[k] > 0) {
        t.pairs_in_contact += static_cast<int>(n_teeth_);
        t.max_pair_force_N = std::max(t.max_pair_force_N, s.normal_force_N[k]);
      }
    f.steps.push_back(t);
  };
  for (std::size_t i = c.bottom; i <= c.end; ++i) add(i, "loading");
  for (std::size_t i = c.top; i <= c.bottom; ++i) add(i, "unloading");
  f.seconds = loop_clock.lap();
  out_.friction = std::move(f);
}

TorqueStep ContactAnalyser::torque_step(double T, const ContactSolution& s) {
  TorqueStep st;
  st.torque_Nm = T;
  st.twist_rad = s.twist_rad;
  st.flank_force_N.assign(s.force_N.data(), s.force_N.data() + nf_);
  if (unilateral_) st.station_force_N.assign(s.force_N.data() + nf_, s.force_N.data() + nf_ + nb_);
  for (Eigen::Index i = 0; i < nf_; ++i)
    if (s.force_N[i] > 0) {
      st.pairs_in_contact += static_cast<int>(n_teeth_);
      st.max_pair_force_N = std::max(st.max_pair_force_N, s.force_N[i]);
    }
  follow_edge_teeth(s);
  st.balance_error_rel = std::abs(output_torque(lambda_, s) - T) / std::abs(T);
  return st;
}

/// The edge teeth's radial overlap in the state `s` (from the generator's state at rest).
void ContactAnalyser::follow_edge_teeth(const ContactSolution& s) {
  const Eigen::VectorXd du = R_edge_ * load_change(s.force_N);
  for (Eigen::Index e = 0; e < no_; ++e) {
    EdgeTooth& et = out_.edges[e];
    const double overlap = et.overlap_at_rest_m + du[e];
    et.overlap_min_m = std::min(et.overlap_min_m, overlap);
    et.overlap_max_m = std::max(et.overlap_max_m, overlap);
    bool loaded = false;
    for (Eigen::Index i = 0; i < nf_; ++i) loaded = loaded || (out_.flanks[i].tooth == et.tooth && s.force_N[i] > 0);
    if (et.engaged && loaded && overlap < 0) et.slips = true;
    if (!et.candidate && overlap > 0) et.enters = true;
  }
}

/// Every flank left out must stay open: the twist never reaches its closing angle.
bool ContactAnalyser::twist_reaches_flanks_left_out() {
  const double twist_max = std::max(std::abs(out_.curve.twist_rad.front()), std::abs(out_.curve.twist_rad.back()));
  return twist_max > out_.min_closing_rad + reach_;
}

/// The curve in the catalog's terms: play, lost motion, the three-segment law.
void ContactAnalyser::describe_curve() {
  for (const EdgeTooth& e : out_.edges) out_.zone_edges_hold = out_.zone_edges_hold && !e.slips && !e.enters;
  out_.play_rad = out_.curve.twist_rad[N_ + 1] - out_.curve.twist_rad[N_];
  // With friction the catalog's figures are read on the loop's middle line, as a catalog reads its recordings.
  const TorqueTwist& line = out_.friction ? middle_line_ : out_.curve;
  out_.lost_motion_rad = lost_motion_rad(line, T_R_);
  out_.catalog = opt_.catalog_t1_Nm > 0 && opt_.catalog_t2_Nm > opt_.catalog_t1_Nm && opt_.catalog_t2_Nm < T_R_
                     ? segment_law(line, opt_.catalog_t1_Nm, opt_.catalog_t2_Nm, T_R_)
                     : fitted_segment_law(line, T_R_);
}

/// Split of the twist at rated torque: the tangent line there (active set fixed) by energy, the intercept is
/// engagement.
void ContactAnalyser::split_compliance() {
  std::vector<Eigen::Index> S;
  for (Eigen::Index i = 0; i < at_rated_.force_N.size(); ++i)
    if (at_rated_.force_N[i] > 0) S.push_back(i);
  const auto n = static_cast<Eigen::Index>(S.size());
  Eigen::MatrixXd M(n, n), Mb(n, n), Mc = Eigen::MatrixXd::Zero(n, n), Mt = Eigen::MatrixXd::Zero(n, n);
  Eigen::VectorXd l(n), brg(n);
  for (Eigen::Index r = 0; r < n; ++r) {
    l[r] = P_.lambda[S[r]];
    brg[r] = S[r] >= nf_ && bearing_ ? bearing_c_[S[r] - nf_] : 0.0;
    for (Eigen::Index q = 0; q < n; ++q) Mb(r, q) = A_noseries_(S[r], S[q]);
    for (Eigen::Index q = 0; q < n && S[r] < nf_; ++q) Mc(r, q) = S[q] < nf_ ? cs_.A(S[r], S[q]) : 0.0;
    for (Eigen::Index q = 0; q < n && S[r] < nf_; ++q) Mt(r, q) = S[q] < nf_ ? teeth_(S[r], S[q]) : 0.0;
  }
  M = Mb + Mc + Mt;
  M.diagonal() += brg;
  const Eigen::VectorXd Ml = M.ldlt().solve(l);
  const double C_t = 1.0 / l.dot(Ml);
  const Eigen::VectorXd dz = Ml * C_t;
  const double total = out_.curve.twist_rad.back(), T_fl = flanks_torque_at_rated_;
  ComplianceSplit& split = out_.split;
  split.body = dz.dot(Mb * dz) * T_fl / total;
  split.teeth = dz.dot(Mt * dz) * T_fl / total;
  split.generator = dz.cwiseProduct(brg).dot(dz) * T_fl / total;
  split.circular_spline = dz.dot(Mc * dz) * T_fl / total;
  split.engagement = 1.0 - split.body - split.teeth - split.generator - split.circular_spline;
  // The body's part by the regions of its mesh: the field of dz on the body (its columns of the influence: observers
  // and tangential patterns carry nothing), its strain energy per region, shared out of the body's part. A body with
  // no mesh (a closed form's) has no parts.
  if (!influence_.energy_by_region_J) return;
  const Eigen::Index n_obs = no_ + nr_, nt = static_cast<Eigen::Index>(tangential_.size());
  Eigen::VectorXd x = Eigen::VectorXd::Zero(influence_.A.cols());
  for (Eigen::Index r = 0; r < n; ++r) x[S[r] < nf_ ? n_obs + S[r] : n_obs + nt + S[r]] = dz[r];
  if (!unilateral_) x.segment(n_obs + nf_ + nt, nb_) = band_solve_ * x.segment(n_obs, nf_);  // the band's reactions
  const std::vector<double> U = influence_.energy_by_region_J(x);
  double sum = 0;
  for (const double u : U) sum += u;
  const auto part = [&](std::size_t region) { return region < U.size() && sum > 0 ? split.body * U[region] / sum : 0; };
  split.wall = part(0), split.rim = part(1) + part(kToothLayerRegion), split.diaphragm = part(2),
  split.boss = part(3);
}

/// What the teeth at the zones' edges hold: their flanks' share of +rated torque, and the twist at +rated without
/// them. They are engaged a few µm deep or not at all at rest and touch at their tips; on sharp corners they can carry
/// much of the torque where a rounded tip would let them ride over, so the curve's stiffness should not rest on them
/// unseen. After the split: the re-solve moves the bearing's secants.
void ContactAnalyser::measure_zone_edge_teeth() {
  std::vector<Eigen::Index> keep;
  double edge_moment = 0;
  for (Eigen::Index i = 0; i < nf_; ++i) {
    if (near_edge(out_.flanks[i].tooth, 2)) edge_moment += lambda_[i] * at_rated_.force_N[i];
    else keep.push_back(i);
  }
  out_.edge_teeth_torque_share = edge_moment / T_R_;
  out_.twist_at_rated_without_edge_teeth_rad = out_.curve.twist_rad.back();
  if (static_cast<Eigen::Index>(keep.size()) == nf_) return;
  const std::optional<ContactSolution> s = solve_with_flanks(keep, T_R_);
  out_.twist_at_rated_without_edge_teeth_rad =
      s ? s->twist_rad : std::numeric_limits<double>::infinity();  // nothing else carries it
}

std::optional<ContactSolution> ContactAnalyser::solve_with_flanks(const ContactProblem& P,
                                                                  const Eigen::VectorXd& moments,
                                                                  std::vector<Eigen::Index> keep, double T,
                                                                  const Eigen::VectorXd* warm) {
  const auto kept_flanks = static_cast<Eigen::Index>(keep.size());
  if (kept_flanks == 0) return std::nullopt;
  for (Eigen::Index k = nf_; k < P.q.size(); ++k) keep.push_back(k);
  ContactProblem Pr;
  Pr.A = P.A(keep, keep);
  Pr.q = P.q(keep);
  Pr.lambda = P.lambda(keep);
  ContactSolution s;
  try {
    const Eigen::VectorXd start = warm ? Eigen::VectorXd((*warm)(keep)) : Eigen::VectorXd();
    s = solve_torque(Pr, kept_flanks, moments(keep), T, warm ? &start : nullptr).first;
  } catch (const InputError&) {
    return std::nullopt;
  }
  Eigen::VectorXd x = Eigen::VectorXd::Zero(P.q.size());
  x(keep) = s.force_N;
  s.force_N = x;
  return s;
}

/// The blocks the ramp's climbing turns: the body's coefficients over the flanks' normal and tangential patterns and
/// the stations, the rim observers' rows against them, the circular spline's (normal, then tangential) and its tip
/// observers' rows; each flank as it closes at rest, and its tooth's centre line.
ContactAnalyser::ClimbBlocks ContactAnalyser::climb_blocks() const {
  const Eigen::Index nf = nf_, n_obs = no_ + nr_;
  std::vector<Eigen::Index> cols, ratchet;
  for (Eigen::Index i = 0; i < 2 * nf + nb_; ++i) cols.push_back(n_obs + i);  // normal, tangential, stations
  for (Eigen::Index i = 0; i < nr_; ++i) ratchet.push_back(no_ + i);
  ClimbBlocks b;
  b.body = influence_.A(cols, cols);
  b.rim = influence_.A(ratchet, cols);
  b.lever = influence_.lever(cols);
  b.cs = Eigen::MatrixXd::Zero(2 * nf, 2 * nf);
  b.ring = Eigen::MatrixXd::Zero(nr_, 2 * nf);
  if (opt_.series.circular_spline) {
    std::vector<FlankPattern> all = cs_patterns_;
    all.insert(all.end(), cs_tangential_.begin(), cs_tangential_.end());
    all.insert(all.end(), ratchet_ring_.begin(), ratchet_ring_.end());
    const Eigen::MatrixXd A = opt_.series.circular_spline(all).A;
    b.cs = A.topLeftCorner(2 * nf, 2 * nf);
    b.ring = A.bottomLeftCorner(nr_, 2 * nf);
  }
  for (const FlankContact& f : out_.flanks) {
    const Slice& sl = slices_[f.slice];
    b.rest.push_back(closed_flank(sl.model, f.phi_rad, 0.0, f.flank));
    b.centre_line.push_back(Eigen::Rotation2Dd(place_tooth(sl.curve, f.phi_rad, 0.0).angle_rad) *
                            Eigen::Vector2d(1.0, 0.0));
  }
  return b;
}

namespace {

/// The rows of B over (normal patterns, tangential patterns, the rest) turned: row i of the flanks is cos β_i times its
/// normal row plus sin β_i times its tangential row; the rest (the stations) as they are.
Eigen::MatrixXd turned_rows(const Eigen::MatrixXd& B, const Eigen::VectorXd& c, const Eigen::VectorXd& s) {
  const Eigen::Index nf = c.size(), rest = B.rows() - 2 * nf;
  Eigen::MatrixXd out(nf + rest, B.cols());
  out.topRows(nf) = c.asDiagonal() * B.topRows(nf) + s.asDiagonal() * B.middleRows(nf, nf);
  out.bottomRows(rest) = B.bottomRows(rest);
  return out;
}

}  // namespace

ContactAnalyser::ClimbedProblem ContactAnalyser::climbed_problem(const ClimbBlocks& b, const Eigen::VectorXd& beta,
                                                                 const Eigen::VectorXd& dq,
                                                                 const Eigen::VectorXd& lever_scale) const {
  ClimbedProblem c;
  c.cos = beta.array().cos();
  c.sin = beta.array().sin();
  const Eigen::MatrixXd half = turned_rows(b.body, c.cos, c.sin);
  Eigen::MatrixXd A_body = turned_rows(half.transpose(), c.cos, c.sin);
  A_body = 0.5 * (A_body + A_body.transpose()).eval();
  c.moments.resize(nf_ + nb_);
  c.moments << b.lever.head(nf_).cwiseProduct(lever_scale), b.lever.tail(nb_);
  const Eigen::VectorXd q = Eigen::Map<const Eigen::VectorXd>(q_flank_.data(), nf_) + dq;
  c.P = body_problem(A_body, q, c.moments, c.band_solve);
  add_series(c.P, turned_rows(turned_rows(b.cs, c.cos, c.sin).transpose(), c.cos, c.sin));
  return c;
}

/// The loads dx (flanks, then stations) as parts along the blocks' columns: each flank's along its normal and its
/// tangential pattern, the stations' as they are.
Eigen::VectorXd ContactAnalyser::ClimbedProblem::parts(const Eigen::VectorXd& dx) const {
  const Eigen::Index nf = cos.size(), rest = dx.size() - nf;
  Eigen::VectorXd p(2 * nf + rest);
  p << cos.cwiseProduct(dx.head(nf)), sin.cwiseProduct(dx.head(nf)), dx.tail(rest);
  return p;
}

ContactAnalyser::Climb ContactAnalyser::climb(const ClimbBlocks& b, const std::vector<Eigen::Index>& keep, double T,
                                              const Eigen::VectorXd& parting, const RatchetState* last) const {
  Climb c;
  c.beta = c.dq = Eigen::VectorXd::Zero(nf_);
  c.scale = Eigen::VectorXd::Ones(nf_);
  c.where.resize(static_cast<std::size_t>(nf_));
  for (const Eigen::Index i : keep) {
    if (!(b.lever[i] * T > 0)) continue;
    const Eigen::Index t = static_cast<Eigen::Index>(ratchet_tooth_of_flank_[i]);
    const FlankContact& f = out_.flanks[i];
    const ClosedFlank& rest = b.rest[i];
    const ClosedFlank at = parting[t] == 0 ? rest : closed_flank(slices_[f.slice].model, f.phi_rad, 0.0, f.flank,
                                                                 parting[t]);
    if (!std::isfinite(at.turn_rad) || !std::isfinite(rest.turn_rad) || rest.contact.lever_arm_m == 0) {
      if (last && last->loaded[t]) c.past_tips.push_back(t);
      continue;  // no rigid turn closes it there: left as at rest
    }
    // Its force along the climbed normal, read in the frame of the load's point at rest: the normal's turn less the
    // turn of the radial line through the contact point as it moves.
    const Eigen::Vector2d &n0 = rest.contact.normal, &n = at.contact.normal, &p0 = rest.contact.point_f,
                          &p = at.contact.point_f;
    c.beta[i] = std::atan2(n0.x() * n.y() - n0.y() * n.x(), n0.dot(n)) -
                std::atan2(p0.x() * p.y() - p0.y() * p.x(), p0.dot(p));
    // Its moment about the axis: the pattern's lever at rest times the climbed contact's over the contact's at rest
    // (the exact lever of the force at its climbed point); its gap: the rigid turn that closes it there at that
    // lever, less the parting's first-order share, which the turned coefficients add back.
    c.scale[i] = at.contact.lever_arm_m / rest.contact.lever_arm_m;
    c.dq[i] = std::abs(c.scale[i] * b.lever[i]) * at.turn_rad - std::abs(b.lever[i]) * rest.turn_rad -
              n_teeth_ * b.centre_line[i].dot(n) * parting[t];
    c.where[static_cast<std::size_t>(i)] = std::string(part_name(at.contact.part_f)) + " on " +
                                           part_name(at.contact.part_c);
  }
  return c;
}

RatchetState ContactAnalyser::ratchet_state(const ClimbBlocks& b, const ClimbedProblem& cp, const ContactSolution& s,
                                            const Climb& c) const {
  const Eigen::VectorXd& x = s.force_N;
  // The loads' change since rest along the turned directions: normal and tangential parts, the stations'.
  const Eigen::VectorXd parts = cp.parts(load_change(x, cp.band_solve));
  RatchetState st;
  st.rim_in_m = -(b.rim * parts);
  st.ring_out_m = b.ring * parts.head(2 * nf_);
  st.overlap_m.resize(nr_);
  st.loaded.assign(static_cast<std::size_t>(nr_), false);
  st.normal_turn_rad.assign(static_cast<std::size_t>(nr_), 0.0);
  st.contact.assign(static_cast<std::size_t>(nr_), std::string());
  std::vector<double> most(static_cast<std::size_t>(nr_), 0.0);
  for (Eigen::Index t = 0; t < nr_; ++t)
    st.overlap_m[t] = ratchet_teeth_[t].overlap_at_rest_m - st.rim_in_m[t] - st.ring_out_m[t];
  for (Eigen::Index i = 0; i < nf_; ++i) {
    const std::size_t t = ratchet_tooth_of_flank_[i];
    if (!(x[i] > most[t])) continue;
    most[t] = x[i];
    st.loaded[t] = true;
    st.normal_turn_rad[t] = c.beta[i];
    st.contact[t] = c.where[static_cast<std::size_t>(i)];
  }
  st.twist_rad = s.twist_rad;
  return st;
}

/// The ramp past rated torque to the ratcheting torque (contact/ratcheting.hpp), with only the teeth that still
/// overlap taking part and their contacts climbing. At a torque, from the teeth parted by nothing: each
/// flank the torque closes met where a rigid turn closes it with its tooth drawn in by its parting (closed_flank); its
/// force turned with that contact's normal, read in the frame of its load's point at rest (β); its lever the climbed
/// contact's; its gap the rigid turn that closes it there, less the parting's first-order share, which the turned
/// coefficients add back (so at no parting the problem is the curve's). The problem solved as at the curve's steps (the
/// bearing's secants from the round before), the parting read again (the rim's inward and the ring's outward motion at
/// each tooth's tip, from the change of the loads since rest) and relaxed (halved, to 1/8, while it does not settle)
/// until it moves by less than 0.1 µm (the tips of the designed size 17 part by tens of µm in the ramp; 0.1 µm is the
/// order of the wobble of two near-conformal flanks' nearest points from round to round). A loaded tooth whose
/// overlap is gone is handed back at once to be released. Rounds that stall (8 without a better one, or 60 in all) go
/// round a state they do not reach (a contact on a sharp corner has no one normal): the best of them stands, and the
/// loaded teeth whose overlap left is within its wobble are handed back to be released. So the teeth fail to hold T
/// only when those left cannot carry it (the cascade of releases). After the split, like the zone edges' re-solve.
std::optional<RatchetState> ContactAnalyser::ratchet_solve(const ClimbBlocks& b, double T,
                                                           const std::vector<bool>& carry, RampCount& n) {
  constexpr int kRounds = 60, kStalled = 8;
  constexpr double kSettled_m = 1e-7;  // of the parting: see above
  ++n.solves;
  std::vector<Eigen::Index> keep;
  for (Eigen::Index i = 0; i < nf_; ++i)
    if (carry[ratchet_tooth_of_flank_[i]]) keep.push_back(i);
  // From no parting, every time: the state is the least parting that holds T, whatever was solved before.
  Eigen::VectorXd parting = Eigen::VectorXd::Zero(nr_);
  std::optional<RatchetState> last, best;
  double relax = 1, last_residual = std::numeric_limits<double>::infinity(),
         best_residual = std::numeric_limits<double>::infinity();
  int best_round = 0;
  for (int round = 0; round < kRounds; ++round) {
    ++n.rounds;
    Stopwatch round_clock;
    const Climb c = climb(b, keep, T, parting, last ? &*last : nullptr);
    if (!c.past_tips.empty()) {  // a loaded tooth parted so far that its tips pass: handed back to be released
      for (const Eigen::Index t : c.past_tips) last->overlap_m[t] = std::min(last->overlap_m[t], 0.0);
      return last;
    }
    n.geometry_s += round_clock.lap();
    const ClimbedProblem cp = climbed_problem(b, c.beta, c.dq, c.scale);
    secants_from_last_ = round > 0;
    const std::optional<ContactSolution> s =
        solve_with_flanks(cp.P, cp.moments, keep, T, n.warm_forces.size() ? &n.warm_forces : nullptr);
    secants_from_last_ = false;
    n.solve_s += round_clock.lap();
    if (!s) return std::nullopt;  // those teeth cannot carry T
    n.warm_forces = s->force_N;
    RatchetState st = ratchet_state(b, cp, *s, c);
    const Eigen::VectorXd next = st.rim_in_m + st.ring_out_m;
    bool gone = false;
    for (Eigen::Index t = 0; t < nr_; ++t) gone = gone || (carry[t] && st.loaded[t] && st.overlap_m[t] <= 0);
    const double residual = (next - parting).cwiseAbs().maxCoeff();
    last = std::move(st);
    if (gone || residual <= kSettled_m) return last;
    if (residual < best_residual) best = last, best_residual = residual, best_round = round;
    if (round - best_round >= kStalled) break;  // the rounds go round a state they do not reach
    if (residual >= last_residual) relax = std::max(relax / 2, 1.0 / 8);
    last_residual = residual;
    parting += relax * (next - parting);
  }
  // Not settled: the rounds go round a state they do not reach (a contact on a sharp corner has no one normal).
  // The best round stands, and the loaded teeth whose overlap left its wobble could take let go.
  for (Eigen::Index t = 0; t < nr_; ++t)
    if (carry[t] && best->loaded[t] && best->overlap_m[t] <= best_residual)
      best->overlap_m[t] = std::min(best->overlap_m[t], 0.0);
  return best;
}

void ContactAnalyser::find_ratcheting() {
  if (nr_ == 0) return;
  Stopwatch ramp_clock;
  const ClimbBlocks b = climb_blocks();
  RampCount n;
  const RatchetSolve solve = [&](double T, const std::vector<bool>& carry) { return ratchet_solve(b, T, carry, n); };
  // From rated torque, which the curve carried with every flank; should the teeth not hold it with those out of
  // overlap released, the ramp starts at a thousandth of it, and a drive whose teeth do not hold even that ratchets
  // at once (0).
  const auto said = [&] {
    progress("contact: ratcheting ramp, " + std::to_string(n.solves) + " solves in " + std::to_string(n.rounds) +
             " rounds of the climbing contacts, " + std::to_string(ramp_clock.lap()) + " s (the contacts' geometry " +
             std::to_string(n.geometry_s) + " s, the problems " + std::to_string(n.solve_s) + " s)");
  };
  for (const double from : {T_R_, 1e-3 * T_R_}) {
    try {
      out_.ratcheting = ratcheting_torque(ratchet_teeth_, solve, from, opt_.ratcheting_ceiling_Nm);
      said();
      return;
    } catch (const InputError&) {
    }
  }
  said();
  Ratcheting at_once;
  at_once.torque_Nm = at_once.first_release_Nm = 0;
  at_once.ceiling_Nm = opt_.ratcheting_ceiling_Nm;
  out_.ratcheting = at_once;
}

/// Independent check at +rated: the contact forces as nodal loads on the FEM, the clamp's reaction moment, and the
/// contacts' displacements by a direct solve against the influence coefficients'.
void ContactAnalyser::check_independently() {
  Eigen::VectorXd x(nf_ + nb_);
  if (unilateral_) x = at_rated_.force_N;  // the whole loaded state, the generator's preload included
  else x << at_rated_.force_N, band_solve_ * at_rated_.force_N;
  // The observers (and the tangential patterns: the frictionless state at rated) carry no force.
  const Eigen::Index nt = static_cast<Eigen::Index>(tangential_.size());
  Eigen::VectorXd x_all = Eigen::VectorXd::Zero(no_ + nr_ + nf_ + nt + nb_);
  x_all.segment(no_ + nr_, nf_) = x.head(nf_);
  x_all.tail(nb_) = x.tail(nb_);
  const BodyCheck check = influence_.check(x_all);
  out_.superposition_error_rel = check.superposition_error_rel;
  out_.fem_reaction_torque_Nm = check.clamp_reaction_torque_Nm;
  if (cs_.mounting_torque_Nm) out_.circular_spline_torque_Nm = cs_.mounting_torque_Nm(at_rated_.force_N.head(nf_));
}

}  // namespace

ToothCompliances tooth_pair_compliance_of(const FlexsplineModel& c) {
  if (!c.gear) return {};
  const GearParams g = *c.gear;
  const Material m = c.material;
  const GearRadii radii = gear_radii(g);
  const double width = c.flexspline.rim_width_m, bore = c.flexspline.inner_radius_m;
  // With explicit teeth the body's own teeth carry the flexspline tooth's bending and foundation
  // (contact/tet10_body.hpp ExplicitToothLoads): in series only the circular spline's tooth and the pair's flattening.
  std::optional<FlexsplineToothFem> tooth;
  if (c.flexspline.teeth != TeethModel::Explicit) {
    tooth = flexspline_tooth_fem(g, m, bore, rim_outer_radius(c.flexspline, c.gear));
    progress("contact: the flexspline tooth from the explicit-tooth FEM at " + std::to_string(tooth->radius_m.size()) +
             " contact radii (two plane-strain slabs, " + std::to_string(tooth->nodes) + " nodes) in " +
             std::to_string(tooth->seconds) + " s");
  }
  ToothCompliances out;
  out.pair_m_per_N = [=](double r_f, double r_c) {
    const double rf = std::clamp(r_f, radii.form_f, radii.tip_f);
    const ToothPairCompliance p = tooth_pair_compliance(g, m, rf, kReferenceLineLoad_N_per_m, bore, r_c);
    return ((tooth ? (*tooth)(rf) : 0.0) + p.bending_c + p.foundation_c + p.contact) / width;
  };
  if (tooth) out.flexspline_tooth_m_per_N = [=](double r_f) { return (*tooth)(r_f) / width; };
  return out;
}

NeutralCurve fem_neutral_curve(const NeutralCurveSamples& s, const std::string& source) {
  return fit_neutral_curve(s.radius_m, s.phi_rad, s.w_wg_m, s.v_wg_m, s.mu_wg_rad, source);
}

FemReadout fem_readout(const FlexsplineSolution& s) {
  if (!s.neutral_curve) throw InputError("contact needs the FEM's generator-deformed neutral curve");
  FemReadout r;
  r.neutral_curve = *s.neutral_curve;
  r.compliance_rad_per_Nm = s.compliance_rad_per_Nm;
  if (s.generator) {
    r.generator_model = s.generator->model;
    r.generator_obstacle_m = s.generator->obstacle_m;
  }
  if (!s.cases.empty()) r.generator_u = &s.cases.front().u;
  return r;
}

std::optional<std::string> contact_model_gap(const FlexsplineModel& c) {
  if (!c.gear) return "contact needs a [gear] table (the teeth that carry the torque)";
  if (!c.wave_generator || !c.wave_generator->radial_deformation_m)
    return "contact needs [wave_generator] with radial_deformation_mm (the mesh zones' shape)";
  if (!(c.flexspline.rim_width_m > 0))
    return "contact needs a toothed face: flexspline.rim_width_mm > 0 (the width the teeth carry the torque over; a "
           "tube without teeth has none unless it is given)";
  return std::nullopt;
}

void check_contact_model(const FlexsplineModel& c) {
  if (const std::optional<std::string> gap = contact_model_gap(c)) throw InputError(*gap);
}

namespace {

/// One deviation per tooth of each gear (or none), finite, and a tooth's equal to its half-turn partner's when the
/// flexspline's teeth pair (an even z_f: the circular spline's z_c is then even too).
void check_deviations(const GearParams& g, const ToothDeviations& d) {
  const auto check = [&](const std::vector<double>& e, int z, const char* gear) {
    if (e.empty()) return;
    if (static_cast<int>(e.size()) != z)
      throw InputError(std::string("contact: ") + std::to_string(e.size()) + " pitch deviations of the " + gear +
                       "'s teeth; expected one per tooth (" + std::to_string(z) + ")");
    for (int k = 0; k < z; ++k) {
      if (!std::isfinite(e[k]))
        throw InputError(std::string("contact: the ") + gear + "'s tooth " + std::to_string(k) +
                         " has a pitch deviation that is not a number");
      if (g.teeth_flexspline % 2 == 0 && e[k] != e[(k + z / 2) % z])
        throw InputError(std::string("contact: the ") + gear + "'s tooth " + std::to_string(k) +
                         " deviates otherwise than its half-turn partner; the contact pairs them (an even z_f)");
    }
  };
  check(d.flexspline_m, g.teeth_flexspline, "flexspline");
  check(d.circular_spline_m, g.teeth_circular, "circular spline");
}

}  // namespace

ContactAnalysis analyse_contact(const FlexsplineModel& c, const TetMesh& mesh, const FlexsplineSystem& sys,
                                const FemReadout& fem, const ContactOptions& opt) {
  return analyse_contact(c, Tet10Body(c, mesh, sys, fem.generator_u), fem, opt);
}

ContactAnalysis analyse_contact(const FlexsplineModel& c, const ContactBody& body, const FemReadout& fem,
                                const ContactOptions& opt) {
  check_contact_model(c);
  if (!(opt.rated_torque_Nm > 0)) throw InputError("contact needs a rated torque > 0");
  check_deviations(*c.gear, opt.deviations);
  for (double reach_factor = opt.reach_factor;; reach_factor *= 2) {
    if (std::optional<ContactAnalysis> a = ContactAnalyser(c, body, fem, opt, reach_factor).run()) {
      a->solver = body.solver();
      return *a;
    }
    progress("contact: the twist reaches flanks left out; again with twice the reach");
  }
}

std::string generator_share_meaning(double generator_share) {
  return generator_share > 0 ? "its balls' Hertzian contacts; its races and the cam's plug rigid"
                             : "rigid: the case's generator has no bearing compliance";
}

}  // namespace sw
