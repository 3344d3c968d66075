#include "contact/loaded_contact.hpp"

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
#include "contact/tooth_fem.hpp"
#include "fem/assembly.hpp"
#include "fem/loads.hpp"
#include "fem/post.hpp"
#include "mesh/flexspline.hpp"
#include "gear/tooth_stiffness.hpp"
#include "kinematics/neutral_curve.hpp"

namespace sw {
namespace {

constexpr double kPi = std::numbers::pi;

}  // namespace

std::vector<const BoundaryFace*> FlankLoads::rim(const TetMesh& mesh, double z_lo_m, double z_hi_m) {
  std::vector<const BoundaryFace*> faces;
  for (const BoundaryFace* f : select_faces(mesh, kSurfaceRimOuter)) {
    double z = 0;
    for (int k = 0; k < 3; ++k) z += mesh.nodes(f->nodes[k], 2) / 3;
    if (z >= z_lo_m && z <= z_hi_m) faces.push_back(f);
  }
  if (faces.empty()) throw InputError("contact: the flexspline mesh has no toothed rim surface" +
                                      std::string(std::isfinite(z_lo_m) ? " in an axial slice; refine mesh.size_mm" : ""));
  return faces;
}

FlankLoads::FlankLoads(const TetMesh& mesh, double pitch_rad, double z_lo_m, double z_hi_m)
    : mesh_(mesh), half_(pitch_rad), hats_(mesh, rim(mesh, z_lo_m, z_hi_m)) {}

Eigen::VectorXd FlankLoads::pattern(const std::vector<double>& stations, const Eigen::Vector2d& force_dir,
                                    double contact_radius_m) const {
  const auto radial_dir = [](double t) { return Eigen::Vector3d(std::cos(t), std::sin(t), 0); };
  const auto tangential_dir = [](double t) { return Eigen::Vector3d(-std::sin(t), std::cos(t), 0); };
  Eigen::VectorXd f = Eigen::VectorXd::Zero(3 * mesh_.n_nodes());
  for (std::size_t i = 0; i < stations.size(); ++i) {
    const double s = stations[i];
    const Eigen::VectorXd radial = hats_.load(s, half_, radial_dir), tangential = hats_.load(s, half_, tangential_dir),
                          outer = hats_.load(s + half_ / 2, half_ / 2, radial_dir),
                          inner = hats_.load(s - half_ / 2, half_ / 2, radial_dir);
    if (radial.size() == 0 || outer.size() == 0 || inner.size() == 0)
      throw InputError("contact: no rim faces under the tooth at " + std::to_string(s * 180 / kPi) +
                       " deg; refine mesh.size_mm");
    // The contact force at this station (turned by π at the partner) and its moment about the axis: the three
    // amplitudes reproduce both exactly. Every sum runs over the hats' nodes only (the radial hat's: the others lie
    // within it); the full vectors are the mesh's size.
    const Eigen::Vector2d F = i == 0 ? force_dir : Eigen::Vector2d(-force_dir);
    const Eigen::Vector2d P = contact_radius_m * Eigen::Vector2d(std::cos(s), std::sin(s));
    std::vector<Eigen::Index> nodes;
    for (Eigen::Index n = 0; n < static_cast<Eigen::Index>(mesh_.n_nodes()); ++n)
      if (radial.segment<3>(3 * n).any()) nodes.push_back(n);
    const auto k = static_cast<Eigen::Index>(nodes.size());
    Eigen::MatrixXd H(3 * k, 3);  // radial, tangential, couple (outer − inner) at those nodes
    Eigen::Matrix3d R = Eigen::Matrix3d::Zero();
    for (Eigen::Index j = 0; j < k; ++j) {
      const Eigen::Index n = nodes[j];
      H.block<3, 1>(3 * j, 0) = radial.segment<3>(3 * n);
      H.block<3, 1>(3 * j, 1) = tangential.segment<3>(3 * n);
      H.block<3, 1>(3 * j, 2) = outer.segment<3>(3 * n) - inner.segment<3>(3 * n);
      for (int c = 0; c < 3; ++c) {
        const double fx = H(3 * j, c), fy = H(3 * j + 1, c);
        R.col(c) += Eigen::Vector3d(fx, fy, mesh_.nodes(n, 0) * fy - mesh_.nodes(n, 1) * fx);
      }
    }
    const Eigen::Vector3d target(F.x(), F.y(), P.x() * F.y() - P.y() * F.x());
    const Eigen::VectorXd h = H * R.fullPivLu().solve(target);
    for (Eigen::Index j = 0; j < k; ++j) f.segment<3>(3 * nodes[j]) += h.segment<3>(3 * j);
  }
  return f;
}

namespace {

Eigen::SparseMatrix<double> sparse_columns(const std::vector<Eigen::VectorXd>& cols, const Eigen::SparseMatrix<double>& more) {
  std::vector<Eigen::Triplet<double>> t;
  for (std::size_t j = 0; j < cols.size(); ++j)
    for (Eigen::Index i = 0; i < cols[j].size(); ++i)
      if (cols[j][i] != 0.0) t.emplace_back(static_cast<int>(i), static_cast<int>(j), cols[j][i]);
  for (Eigen::Index j = 0; j < more.outerSize(); ++j)
    for (Eigen::SparseMatrix<double>::InnerIterator it(more, j); it; ++it)
      t.emplace_back(static_cast<int>(it.row()), static_cast<int>(cols.size() + j), it.value());
  Eigen::SparseMatrix<double> L(more.rows() ? more.rows() : (cols.empty() ? 0 : cols[0].size()),
                                static_cast<Eigen::Index>(cols.size()) + more.cols());
  L.setFromTriplets(t.begin(), t.end());
  return L;
}

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

ContactAnalysis analyse_within_reach(const FlexsplineModel& c, const TetMesh& mesh, const FlexsplineSystem& sys,
                                    const FlexsplineSolution& fem, const ContactOptions& opt, double reach_factor) {
  check_contact_model(c);
  if (!fem.neutral_curve) throw InputError("contact needs the FEM's generator-deformed neutral curve");
  if (!(opt.rated_torque_Nm > 0)) throw InputError("contact needs a rated torque > 0");
  const GearParams& g = *c.gear;
  const auto& w = *c.wave_generator;
  Stopwatch clock;
  ContactAnalysis out;
  out.rated_torque_Nm = opt.rated_torque_Nm;

  // The gear on the rim as the generator leaves it.
  const NeutralCurveSamples& nc = *fem.neutral_curve;
  const NeutralCurve curve = fit_neutral_curve(nc.radius_m, nc.phi_rad, nc.w_wg_m, nc.v_wg_m, nc.mu_wg_rad, "FEM");
  const BacklashModel model = make_backlash_model(g, curve);
  out.half_turn_pairs = g.teeth_flexspline % 2 == 0;
  const double n_teeth = out.half_turn_pairs ? 2.0 : 1.0;  // teeth per unknown

  // The face width in axial slices, each with the rim as the generator leaves it at the slice's centre (the FEM's
  // generator case read there: the cup's coning). One slice is the centre section's curve itself.
  const int n_slices = std::max(1, opt.face_slices);
  if (n_slices > 1 && fem.cases.empty())
    throw InputError("contact.face_slices = " + std::to_string(n_slices) +
                     " reads the FEM's rim at every slice, and a result read back (--fem) has only its centre section; "
                     "run contact without --fem (or face_slices = 1)");
  const double face = c.flexspline.rim_width_m;
  struct Slice {
    double z_lo, z_hi;
    NeutralCurve curve;
    BacklashModel model;
    std::vector<PairClearance> rest;
  };
  // Sections read from the FEM's generator case in one pass: the face's ends, then the slices' centres (if sliced).
  std::vector<double> z_read;
  if (!fem.cases.empty()) z_read = {nc.z_m - face / 2, nc.z_m + face / 2};
  for (int j = 0; j < n_slices && n_slices > 1; ++j) z_read.push_back(nc.z_m - face / 2 + face * (j + 0.5) / n_slices);
  std::vector<NeutralCurve> read;
  if (!z_read.empty())
    for (const NeutralCurveSamples& at : neutral_curves_at(c, mesh, fem.cases.front().u, z_read))
      read.push_back(fit_neutral_curve(at.radius_m, at.phi_rad, at.w_wg_m, at.v_wg_m, at.mu_wg_rad, "FEM"));
  std::vector<Slice> slices;
  for (int j = 0; j < n_slices; ++j) {
    const double z_lo = nc.z_m - face / 2 + face * j / n_slices, z_hi = z_lo + face / n_slices;
    const NeutralCurve& cj = n_slices > 1 ? read[2 + j] : curve;
    slices.push_back({z_lo, z_hi, cj, n_slices > 1 ? make_backlash_model(g, cj) : model, {}});
  }
  out.face_slices = n_slices;
  // The face's ends and centre at rest: how the coning moves the teeth's clearance across the face.
  if (!fem.cases.empty())
    for (const auto& [z, cz] : {std::pair<double, const NeutralCurve&>{nc.z_m - face / 2, read[0]}, {nc.z_m, curve},
                                {nc.z_m + face / 2, read[1]}})
      out.face_sections.push_back(section_at_rest(g, cz, z, opt.wg_angle_rad));

  // The flanks that can close: within reach of the first one on their side (over every slice).
  double first_closing[2] = {std::numeric_limits<double>::infinity(), std::numeric_limits<double>::infinity()};
  std::vector<PairClearance> rest(g.teeth_flexspline);
  for (int k = 0; k < g.teeth_flexspline; ++k) rest[k] = pair_clearance(model, tooth_material_angle(g, k, opt.wg_angle_rad), 0.0);
  for (Slice& sl : slices) {
    sl.rest.resize(g.teeth_flexspline);
    for (int k = 0; k < g.teeth_flexspline; ++k) {
      const double phi = tooth_material_angle(g, k, opt.wg_angle_rad);
      sl.rest[k] = n_slices == 1 ? rest[k] : pair_clearance(sl.model, phi, 0.0);
      if (!sl.rest[k].engaged) continue;
      for (const Flank side : {Flank::Ccw, Flank::Cw})
        first_closing[side == Flank::Cw] =
            std::min(first_closing[side == Flank::Cw], closing_angle_rad(sl.model, phi, 0.0, side));
    }
  }
  // Teeth within `pitches` of a change of engagement (the mesh zones' edges) at the centre section.
  const int zf = g.teeth_flexspline;
  auto near_edge_in = [&](const std::vector<PairClearance>& r, int k, int pitches) {
    for (int d = -pitches; d <= pitches; ++d)
      if (r[(k + d + zf) % zf].engaged != r[k].engaged) return true;
    return false;
  };
  auto near_edge = [&](int k, int pitches) { return near_edge_in(rest, k, pitches); };
  const double reach = reach_factor * std::abs(fem.compliance_rad_per_Nm) * opt.rated_torque_Nm;
  out.reach_rad = reach;
  std::vector<Eigen::VectorXd> columns;
  std::vector<double> q_flank;
  const FlankLoads loads(mesh, 2 * kPi / g.teeth_flexspline);
  for (int j = 0; j < n_slices; ++j) {
    const Slice& sl = slices[j];
    // One slice loads the whole face (the observers' patterns); more, each its own band of the rim's faces.
    std::optional<FlankLoads> band;
    if (n_slices > 1) band.emplace(mesh, 2 * kPi / g.teeth_flexspline, sl.z_lo, sl.z_hi);
    const FlankLoads& slice_loads = band ? *band : loads;
    for (int k = 0; k < g.teeth_flexspline; ++k) {
      const double phi = tooth_material_angle(g, k, opt.wg_angle_rad);
      if (out.half_turn_pairs && !(phi > -kPi / 2 && phi <= kPi / 2)) continue;
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
        if (!cand || (pc.engaged && cand->closing_angle_rad > first_closing[side == Flank::Cw] + reach)) continue;
        FlankContact& f = *cand;
        const FlankClearance& fc = side == Flank::Ccw ? pc.ccw : pc.cw;
        f.tooth = k;
        f.slice = j;
        f.compliance_m_per_N = opt.series.tooth_pair_m_per_N
                                   ? n_slices * opt.series.tooth_pair_m_per_N(f.contact_radius_m, f.contact_radius_c_m)
                                   : 0.0;
        const double s = std::atan2(fc.point_f.y(), fc.point_f.x());
        std::vector<double> stations{s};
        if (out.half_turn_pairs) stations.push_back(s + kPi);
        columns.push_back(slice_loads.pattern(stations, -fc.normal, fc.point_f.norm()));
        q_flank.push_back(n_teeth * std::abs(f.lever_m) * f.closing_angle_rad);
        out.flanks.push_back(f);
      }
    }
  }
  if (out.flanks.empty()) throw InputError("contact: no tooth flank in the mesh zone can close");
  out.min_closing_rad = std::min(first_closing[0], first_closing[1]);
  for (const auto& f : out.flanks) out.overlap_at_rest_m = std::max(out.overlap_at_rest_m, -std::abs(f.lever_m) * f.closing_angle_rad);
  const auto nf = static_cast<Eigen::Index>(out.flanks.size());

  // The zones' edges: the teeth within two pitches of a change of engagement. Whether such a tooth can touch at all is
  // its radial overlap, which the rim's radial motion under load changes: a radial observer pattern at its tip reads
  // that motion at every step (the tooth's own bending moves its tip along the pitch circle, not radially, and is
  // left out).
  std::vector<Eigen::VectorXd> observers;
  for (int k = 0; k < zf; ++k) {
    const double phi = tooth_material_angle(g, k, opt.wg_angle_rad);
    if (out.half_turn_pairs && !(phi > -kPi / 2 && phi <= kPi / 2)) continue;
    if (!near_edge(k, 3)) continue;
    const ToothPlacement place = place_tooth(curve, phi, 0.0);
    const Eigen::Vector2d tip = Eigen::Rotation2Dd(place.angle_rad) * Eigen::Vector2d(model.radii.tip_f, 0.0) + place.offset_m;
    const double s = std::atan2(tip.y(), tip.x());
    std::vector<double> stations{s};
    if (out.half_turn_pairs) stations.push_back(s + kPi);
    observers.push_back(loads.pattern(stations, Eigen::Vector2d(std::cos(s), std::sin(s)), tip.norm()) / n_teeth);
    EdgeTooth e;
    e.tooth = k;
    e.phi_rad = phi;
    e.engaged = rest[k].engaged;
    e.overlap_at_rest_m = e.overlap_min_m = e.overlap_max_m = rest[k].depth_m;
    e.candidate = std::any_of(out.flanks.begin(), out.flanks.end(), [&](const FlankContact& f) { return f.tooth == k; });
    out.edges.push_back(e);
  }
  const auto no = static_cast<Eigen::Index>(observers.size());

  // The generator's stations, and the influence coefficients of every pattern.
  const GeneratorStations gen = generator_stations(c, mesh);
  const bool unilateral = gen.unilateral;
  const Eigen::SparseMatrix<double> L = sparse_columns(columns, gen.stations.loads);
  const auto nb = gen.stations.loads.cols();
  out.setup_s = clock.lap();
  progress("contact: influence of " + std::to_string(nf) + " flank patterns, " + std::to_string(nb) +
           " generator stations and " + std::to_string(no) + " zone-edge observers");
  const Eigen::SparseMatrix<double> L_all = sparse_columns(observers, L);
  const Eigen::MatrixXd A_all = sys.influence(L_all);
  const Eigen::MatrixXd A_body = A_all.bottomRightCorner(nf + nb, nf + nb);
  const Eigen::MatrixXd R_edge = A_all.topRightCorner(no, nf + nb);  // radial motion at the edge teeth's tips
  out.influence_s = clock.lap();
  Eigen::VectorXd lambda(nf + nb);
  const std::vector<bool> all(mesh.n_nodes(), true);
  for (Eigen::Index j = 0; j < nf + nb; ++j) lambda[j] = -moment_about_z(mesh, Eigen::VectorXd(L.col(j)), all);

  // The contact problem. Unilateral generator: flanks and stations together, the stations' gaps against the
  // generator's surface, the flanks' gaps measured in the generator's state (p0). Force idealisation: the band held
  // radially (bilateral), eliminated.
  ContactProblem P;
  Eigen::VectorXd p0, obstacle;
  Eigen::MatrixXd band_solve;  // force idealisation: x_b = band_solve · x_f
  if (unilateral) {
    obstacle = fem.generator->obstacle_m;
    p0 = unilateral_contact(A_body.bottomRightCorner(nb, nb), obstacle).force_N;
    P.A = A_body;
    P.q.resize(nf + nb);
    P.q.head(nf) = Eigen::Map<const Eigen::VectorXd>(q_flank.data(), nf) - A_body.topRightCorner(nf, nb) * p0;
    P.q.tail(nb) = -obstacle;
    // A turn of the output leaves the stations' gaps alone: the flexspline turns on the generator's bearing while
    // the deformation wave stays with the cam. (In the linear model a rigid turn would also turn the wave, and a
    // non-circular cam would then hold the output back with a stiffness it does not have.) The stations' forces still
    // have a moment about the axis through the cam's tilted normal: the locked generator's share of the torque.
    P.lambda = lambda;
    P.lambda.tail(nb).setZero();
    out.generator_support = "the generator's contact (" + fem.generator->model + ", unilateral) in the same problem";
  } else {
    const Eigen::LDLT<Eigen::MatrixXd> bb(A_body.bottomRightCorner(nb, nb));
    band_solve = -bb.solve(A_body.bottomLeftCorner(nb, nf));
    P.A = A_body.topLeftCorner(nf, nf) + A_body.topRightCorner(nf, nb) * band_solve;
    P.A = 0.5 * (P.A + P.A.transpose()).eval();
    P.q = Eigen::Map<const Eigen::VectorXd>(q_flank.data(), nf);
    P.lambda = lambda.head(nf);
    out.generator_support = "the band held radially at the stations (the paper's given-force idealisation)";
  }
  const Eigen::MatrixXd A_noseries = P.A;
  for (Eigen::Index i = 0; i < nf; ++i) P.A(i, i) += n_teeth * out.flanks[i].compliance_m_per_N;
  out.unknowns = static_cast<int>(P.q.size());
  out.problem = P;

  // Bearing balls in series with the stations (unilateral generators): the secant of the Hertzian approach from the
  // generator's state, iterated to a fixed point.
  const bool bearing = unilateral && opt.series.bearing_approach_m && opt.series.bearing_balls > 0;
  const double ball_per_N = bearing ? 2 * kPi / (opt.series.bearing_balls * gen.stations.half_width_rad) : 0.0;
  auto approach = [&](double p) { return 2 * opt.series.bearing_approach_m(std::max(p, 0.0) * ball_per_N); };
  Eigen::VectorXd bearing_c = Eigen::VectorXd::Zero(nb);
  // The secant of the approach between the preload p and x; where the two are too close for a difference quotient to
  // be exact (near zero torque), the tangent at their midpoint: the same value to O(h²), without the round-off that
  // made the fixed point below cycle.
  auto secant = [&](double x, double p, double p_ref) {
    const double d = x - p, h = 1e-4 * std::max(std::abs(p), 1e-3 * p_ref);
    if (std::abs(d) > h) return (approach(x) - approach(p)) / d;
    const double m = 0.5 * (x + p);
    return (approach(m + h) - approach(m - h)) / (2 * h);
  };
  // One torque on a problem whose first n_fl unknowns are flanks and whose last nb are the generator's stations.
  auto solve_step = [&](const ContactProblem& base, Eigen::Index n_fl, double T, const Eigen::VectorXd* warm) {
    if (!bearing) return solve_contact(base, T, warm);
    ContactProblem Pb = base;
    const double p_ref = std::max(p0.maxCoeff(), 1.0);
    for (Eigen::Index k = 0; k < nb; ++k) bearing_c[k] = secant(p0[k], p0[k], p_ref);  // start: the tangent at the preload
    // The secants' fixed point, relaxed: where a station lifts off and lands again from one pass to the next the plain
    // iteration cycles between two states (size 17 at w0 + 14 %), so the step is halved whenever the residual does
    // not shrink. Converged when every station's secant reproduces its Hertzian approach to 1e-6 of the largest
    // preload's (picometres; round-off of the contact solve sits near 1e-7): the secant itself need not settle where a station carries (almost) nothing, as its Q^(2/3) law has
    // no finite slope at zero load, and a station that ends up unloaded carries nothing whatever its secant.
    const double tol_m = 1e-6 * approach(p_ref);
    ContactSolution s;
    double relax = 1.0, last = std::numeric_limits<double>::infinity();
    for (int it = 0;; ++it) {
      for (Eigen::Index k = 0; k < nb; ++k) {
        Pb.A(n_fl + k, n_fl + k) = base.A(n_fl + k, n_fl + k) + bearing_c[k];
        Pb.q[n_fl + k] = base.q[n_fl + k] - bearing_c[k] * p0[k];
      }
      s = solve_contact(Pb, T, it == 0 ? warm : &s.force_N);
      double residual = 0;
      Eigen::VectorXd c_new(nb);
      for (Eigen::Index k = 0; k < nb; ++k) {
        const double x = s.force_N[n_fl + k];
        c_new[k] = secant(x, p0[k], p_ref);
        residual = std::max(residual, std::abs(bearing_c[k] * (x - p0[k]) - (approach(x) - approach(p0[k]))));
      }
      if (residual <= tol_m) break;
      if (residual >= last) relax = std::max(relax / 2, 1.0 / 1024);
      last = residual;
      bearing_c += relax * (c_new - bearing_c);
      if (it == 400)
        throw InputError("contact: the generator bearing's Hertzian secant did not settle at T = " +
                         std::to_string(T) + " N·m (approach off by " + std::to_string(residual * 1e9) + " nm)");
    }
    return s;
  };

  // Torque steps from −rated to +rated, the two limits at zero (a drive with play jumps there).
  const int N = std::max(1, opt.steps);
  const double T_R = opt.rated_torque_Nm;
  std::vector<double> torques;
  for (int s = -N; s <= N; ++s) {
    if (s == 0) {
      torques.push_back(-1e-6 * T_R);
      torques.push_back(1e-6 * T_R);
    } else {
      torques.push_back(T_R * s / N);
    }
  }
  // The generator's preload has a moment about the axis only through the mesh's round-off (zero by symmetry: 1e-3 N·m
  // on a coarse size-17 cup); the output's torque is counted from it, so that the limits at zero stay either side of
  // the play instead of on the side the round-off picks.
  const double rest_moment_Nm = unilateral ? lambda.tail(nb).dot(p0) : 0.0;
  // The output's torque: the moments (`moments`, the stations' included) of the forces beyond the preload's.
  auto output_torque = [&](const Eigen::VectorXd& moments, const ContactSolution& s) {
    return moments.head(s.force_N.size()).dot(s.force_N) - rest_moment_Nm;
  };
  // The output's torque is what the flanks carry plus the locked generator's share (λ with the stations' moment arms)
  // beyond its moment at rest: find the flanks' torque that gives T. The share is about 1/ratio of it, so T_out is
  // nearly affine in T_flanks: secant steps. Returns the solution and the flanks' torque. `warm`: the forces of a
  // nearby solution of the same problem (the previous torque step), where the active set starts.
  auto solve_torque = [&](const ContactProblem& base, Eigen::Index n_fl, const Eigen::VectorXd& moments, double T,
                          const Eigen::VectorXd* warm) {
    ContactSolution s;
    double T_flanks = T, prev_flanks = 0, prev_out = 0;
    for (int it = 0;; ++it) {
      s = solve_step(base, n_fl, T_flanks, it == 0 ? warm : &s.force_N);
      const double T_out = output_torque(moments, s);
      if (std::abs(T_out - T) <= 1e-13 * std::abs(T)) break;
      const double slope = it == 0 || T_out == prev_out ? 1.0 : (T_flanks - prev_flanks) / (T_out - prev_out);
      if (it == 50) {
        if (std::abs(T_out - T) <= 1e-10 * T_R) break;  // round-off of the moments at a limit at zero
        throw InputError("contact: the flanks' share of T = " + std::to_string(T) +
                         " N·m did not settle (the output carries " + std::to_string(T_out) + " N·m)");
      }
      prev_flanks = T_flanks;
      prev_out = T_out;
      T_flanks += slope * (T - T_out);
    }
    return std::make_pair(s, T_flanks);
  };
  // The output's twist: the contact problem's plus the circular spline's torsion.
  auto twist_rad = [&](const ContactSolution& s, double T) { return s.twist_rad + opt.series.circular_spline_rad_per_Nm * T; };
  ContactSolution at_rated;
  double flanks_torque_at_rated = T_R;
  Eigen::VectorXd previous;  // the last step's forces: the next step starts from its contact set
  for (const double T : torques) {
    const auto [s, T_flanks] = solve_torque(P, nf, lambda, T, previous.size() ? &previous : nullptr);
    previous = s.force_N;
    TorqueStep st;
    st.torque_Nm = T;
    st.twist_rad = twist_rad(s, T);
    st.flank_force_N.assign(s.force_N.data(), s.force_N.data() + nf);
    if (unilateral) st.station_force_N.assign(s.force_N.data() + nf, s.force_N.data() + nf + nb);
    for (Eigen::Index i = 0; i < nf; ++i)
      if (s.force_N[i] > 0) {
        st.pairs_in_contact += static_cast<int>(n_teeth);
        st.max_pair_force_N = std::max(st.max_pair_force_N, s.force_N[i]);
      }
    // The edge teeth's radial overlap in this state (from the generator's state at rest).
    {
      Eigen::VectorXd dx(nf + nb);
      if (unilateral) dx << s.force_N.head(nf), s.force_N.tail(nb) - p0;
      else dx << s.force_N, band_solve * s.force_N;
      const Eigen::VectorXd du = R_edge * dx;
      for (Eigen::Index e = 0; e < no; ++e) {
        EdgeTooth& et = out.edges[e];
        const double overlap = et.overlap_at_rest_m + du[e];
        et.overlap_min_m = std::min(et.overlap_min_m, overlap);
        et.overlap_max_m = std::max(et.overlap_max_m, overlap);
        bool loaded = false;
        for (Eigen::Index i = 0; i < nf; ++i) loaded = loaded || (out.flanks[i].tooth == et.tooth && s.force_N[i] > 0);
        if (et.engaged && loaded && overlap < 0) et.slips = true;
        if (!et.candidate && overlap > 0) et.enters = true;
      }
    }
    st.balance_error_rel = std::abs(output_torque(lambda, s) - T) / std::abs(T);
    out.torque_balance_error_rel = std::max(out.torque_balance_error_rel, st.balance_error_rel);
    out.steps.push_back(st);
    out.curve.torque_Nm.push_back(st.torque_Nm);
    out.curve.twist_rad.push_back(st.twist_rad);
    if (T == torques.back()) {
      at_rated = s;
      flanks_torque_at_rated = T_flanks;
    }
  }
  // The limits at zero stand for T = 0 from either side.
  for (std::size_t i = 0; i < out.steps.size(); ++i)
    if (std::abs(out.steps[i].torque_Nm) < 1e-3 * T_R) out.curve.torque_Nm[i] = out.steps[i].torque_Nm = 0.0;
  out.contact_s = clock.lap();
  // Every flank left out must stay open: the twist never reaches its closing angle.
  const double twist_max = std::max(std::abs(out.curve.twist_rad.front()), std::abs(out.curve.twist_rad.back()));
  if (twist_max > std::min(first_closing[0], first_closing[1]) + reach) {
    progress("contact: the twist reaches flanks left out; again with twice the reach");
    return analyse_within_reach(c, mesh, sys, fem, opt, 2 * reach_factor);
  }
  for (const EdgeTooth& e : out.edges) out.zone_edges_hold = out.zone_edges_hold && !e.slips && !e.enters;
  out.play_rad = out.curve.twist_rad[N + 1] - out.curve.twist_rad[N];
  out.lost_motion_rad = lost_motion_rad(out.curve, T_R);
  out.catalog = opt.catalog_t1_Nm > 0 && opt.catalog_t2_Nm > opt.catalog_t1_Nm && opt.catalog_t2_Nm < T_R
                    ? segment_law(out.curve, opt.catalog_t1_Nm, opt.catalog_t2_Nm, T_R)
                    : fitted_segment_law(out.curve, T_R);

  // Split of the twist at rated torque: the tangent line there (active set fixed) by energy, the intercept is
  // engagement.
  {
    std::vector<Eigen::Index> S;
    for (Eigen::Index i = 0; i < at_rated.force_N.size(); ++i)
      if (at_rated.force_N[i] > 0) S.push_back(i);
    const auto n = static_cast<Eigen::Index>(S.size());
    Eigen::MatrixXd M(n, n), Mb(n, n);
    Eigen::VectorXd l(n), teeth(n), brg(n);
    for (Eigen::Index r = 0; r < n; ++r) {
      l[r] = P.lambda[S[r]];
      teeth[r] = S[r] < nf ? n_teeth * out.flanks[S[r]].compliance_m_per_N : 0.0;
      brg[r] = S[r] >= nf && bearing ? bearing_c[S[r] - nf] : 0.0;
      for (Eigen::Index q = 0; q < n; ++q) Mb(r, q) = A_noseries(S[r], S[q]);
    }
    M = Mb;
    M.diagonal() += teeth + brg;
    const Eigen::VectorXd Ml = M.ldlt().solve(l);
    const double C_t = 1.0 / l.dot(Ml);
    const Eigen::VectorXd dz = Ml * C_t;
    const double total = out.curve.twist_rad.back(), T_fl = flanks_torque_at_rated;
    out.split.body = dz.dot(Mb * dz) * T_fl / total;
    out.split.teeth = dz.cwiseProduct(teeth).dot(dz) * T_fl / total;
    out.split.generator = dz.cwiseProduct(brg).dot(dz) * T_fl / total;
    out.split.circular_spline = opt.series.circular_spline_rad_per_Nm * T_R / total;
    out.split.engagement =
        1.0 - out.split.body - out.split.teeth - out.split.generator - out.split.circular_spline;
  }

  // What the teeth at the zones' edges hold: their flanks' share of +rated torque, and the twist at +rated without them.
  // They are engaged a few µm deep or not at all at rest and touch at their tips; on sharp corners they can carry much
  // of the torque where a rounded tip would let them ride over, so the curve's stiffness should not rest on them
  // unseen. After the split: the re-solve moves the bearing's secants.
  {
    std::vector<Eigen::Index> keep;
    double edge_moment = 0;
    for (Eigen::Index i = 0; i < nf; ++i) {
      if (near_edge(out.flanks[i].tooth, 2)) edge_moment += lambda[i] * at_rated.force_N[i];
      else keep.push_back(i);
    }
    const auto kept_flanks = static_cast<Eigen::Index>(keep.size());
    for (Eigen::Index k = nf; k < P.q.size(); ++k) keep.push_back(k);
    out.edge_teeth_torque_share = edge_moment / T_R;
    out.twist_at_rated_without_edge_teeth_rad = out.curve.twist_rad.back();
    if (kept_flanks < nf) {
      ContactProblem Pe;
      Pe.A = P.A(keep, keep);
      Pe.q = P.q(keep);
      Pe.lambda = P.lambda(keep);
      const Eigen::VectorXd moments = lambda(keep);
      try {
        const ContactSolution s = solve_torque(Pe, kept_flanks, moments, T_R, nullptr).first;
        out.twist_at_rated_without_edge_teeth_rad = twist_rad(s, T_R);
      } catch (const InputError&) {
        out.twist_at_rated_without_edge_teeth_rad = std::numeric_limits<double>::infinity();  // nothing else carries it
      }
    }
  }
  out.contact_s += clock.lap();

  // Independent check at +rated: the contact forces as nodal loads on the FEM, the clamp's reaction moment.
  {
    Eigen::VectorXd x(nf + nb);
    if (unilateral) x = at_rated.force_N;  // the whole loaded state, the generator's preload included
    else x << at_rated.force_N, band_solve * at_rated.force_N;
    const Eigen::VectorXd f = L * x;
    const Eigen::VectorXd u = sys.solve(f).col(0);
    Eigen::VectorXd x_all = Eigen::VectorXd::Zero(no + nf + nb);  // the observers carry no force
    x_all.tail(nf + nb) = x;
    const Eigen::VectorXd d_direct = L_all.transpose() * u, d_influence = A_all * x_all;
    out.superposition_error_rel = (d_direct - d_influence).cwiseAbs().maxCoeff() / d_direct.cwiseAbs().maxCoeff();
    const Eigen::VectorXd reactions = internal_forces(mesh, c.material, u) - f;
    out.fem_reaction_torque_Nm = moment_about_z(mesh, reactions, sys.clamped);
  }
  out.check_s = clock.lap();
  progress("contact: " + std::to_string(torques.size()) + " torque steps on " + std::to_string(out.unknowns) +
           " contacts in " + std::to_string(out.contact_s) + " s");
  return out;
}

}  // namespace

std::function<double(double, double)> tooth_pair_compliance_of(const FlexsplineModel& c) {
  if (!c.gear) return {};
  const GearParams g = *c.gear;
  const Material m = c.material;
  const GearRadii radii = gear_radii(g);
  const double width = c.flexspline.rim_width_m, bore = c.flexspline.inner_radius_m;
  const FlexsplineToothFem tooth = flexspline_tooth_fem(g, m, bore, rim_outer_radius(c.flexspline, c.gear));
  progress("contact: the flexspline tooth from the explicit-tooth FEM at " + std::to_string(tooth.radius_m.size()) +
           " contact radii (two plane-strain slabs, " + std::to_string(tooth.nodes) + " nodes) in " +
           std::to_string(tooth.seconds) + " s");
  return [=](double r_f, double r_c) {
    const double rf = std::clamp(r_f, radii.form_f, radii.tip_f);
    const ToothPairCompliance p = tooth_pair_compliance(g, m, rf, kReferenceLineLoad_N_per_m, bore, r_c);
    return (tooth(rf) + p.bending_c + p.foundation_c + p.contact) / width;
  };
}

void check_contact_model(const FlexsplineModel& c) {
  if (!c.gear) throw InputError("contact needs a [gear] table (the teeth that carry the torque)");
  if (!c.wave_generator || !c.wave_generator->radial_deformation_m)
    throw InputError("contact needs [wave_generator] with radial_deformation_mm (the mesh zones' shape)");
  if (c.flexspline.teeth == TeethModel::Explicit)
    throw InputError("contact needs flexspline.teeth = \"ring\" or \"none\" (the teeth's own compliance is "
                              "added in series; explicit teeth would count it twice)");
  if (c.solver.method != SolverMethod::Tet10)
    throw InputError("contact solves on the TET10 model; solver.method = \"fourier\" has no factor to reuse "
                              "(use --solver tet10)");
}

ContactAnalysis analyse_contact(const FlexsplineModel& c, const TetMesh& mesh, const FlexsplineSystem& sys,
                                const FlexsplineSolution& fem, const ContactOptions& opt) {
  return analyse_within_reach(c, mesh, sys, fem, opt, opt.reach_factor);
}

}  // namespace sw
