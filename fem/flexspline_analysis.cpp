#include "fem/flexspline_analysis.hpp"

#include <algorithm>
#include <cmath>
#include <memory>
#include <numbers>
#include <optional>
#include <utility>
#include <vector>

#include "common/constants.hpp"
#include "common/error.hpp"
#include "common/progress.hpp"
#include "fem/assembly.hpp"
#include "fem/loads.hpp"
#include "mesh/flexspline.hpp"

namespace sw {
namespace {


/// A tube without teeth: the torque is the exact torsion shear on its open end, and φ₀ is read on that face.
bool is_plain_tube(const FlexsplineParams& f) {
  return f.shape == FlexsplineShape::Tube && f.teeth == TeethModel::None;
}

/// Scales a load so its moment about z equals `torque_Nm`.
Eigen::VectorXd torque_load(const TetMesh& mesh, const std::vector<const BoundaryFace*>& faces, double torque_Nm,
                            const std::string& where) {
  if (faces.empty()) throw InputError("no boundary faces to carry the torque on " + where + "; refine the mesh");
  const Eigen::VectorXd unit = traction_load(mesh, faces, [](const Eigen::Vector3d& x, const Eigen::Vector3d&) -> Eigen::Vector3d {
    return Eigen::Vector3d(-x[1], x[0], 0.0);  // r·e_θ: the exact torsion shear shape τ ∝ r
  });
  const std::vector<bool> all(mesh.n_nodes(), true);
  return unit * (torque_Nm / moment_about_z(mesh, unit, all));
}

/// A unit moment about z of tangential traction ∝ r·e_θ on the generator band's bore: its work-conjugate displacement
/// is the band's mean turn (exactly χ for a rigid turn χ).
Eigen::VectorXd band_turn_load(const FlexsplineModel& c, const TetMesh& mesh) {
  const auto& w = *c.wave_generator;
  const double z = c.flexspline.length_m - w.axial_position_m;
  return torque_load(mesh, select_faces(mesh, kSurfaceInner, [&](const Eigen::Vector3d& x) {
                       return std::abs(x[2] - z) <= 0.5 * w.band_width_m;
                     }), 1.0, "the generator band");
}

/// Unit-torque tangential traction on the rim, or the exact torsion shear on the open end of a plain tube.
Eigen::VectorXd unit_torque_load(const FlexsplineModel& c, const TetMesh& mesh) {
  const auto& f = c.flexspline;
  if (is_plain_tube(f))
    return torque_load(mesh, select_faces(mesh, kSurfaceOpenEnd), 1.0, "the open end");
  if (c.load.torque_loading == TorqueLoading::Uniform)
    return torque_load(mesh, select_faces(mesh, kSurfaceRimOuter), 1.0, "the rim");
  const double half = c.load.engagement_half_angle_rad;
  auto in_zone = [half](const Eigen::Vector3d& x) {
    const double t = theta_of(x);
    return std::abs(wrap_pi(t)) <= half || std::abs(wrap_pi(t - kPi)) <= half;
  };
  return torque_load(mesh, select_faces(mesh, kSurfaceRimOuter, in_zone), 1.0, "the rim's engagement zones");
}

struct Ring {
  RowMatrixX3d points;
};

Ring reading_ring(double radius, double z) {
  Ring r;
  r.points.resize(kRingSamples, 3);
  for (int k = 0; k < kRingSamples; ++k) {
    const double t = 2 * kPi * k / kRingSamples;
    r.points.row(k) << radius * std::cos(t), radius * std::sin(t), z;
  }
  return r;
}

RowMatrixX3d sample(const PointSampler& sampler, const Ring& ring, const Eigen::VectorXd& u) {
  RowMatrixX3d d(ring.points.rows(), 3);
  for (Eigen::Index k = 0; k < ring.points.rows(); ++k)
    d.row(k) = sampler.displacement(ring.points.row(k).transpose(), u).transpose();
  return d;
}

/// Radial and tangential displacement and tangent rotation along the ring.
void curve_of(const Ring& ring, const RowMatrixX3d& d, double radius, std::vector<double>& w, std::vector<double>& v,
              std::vector<double>& mu) {
  const int n = static_cast<int>(ring.points.rows());
  w.resize(n);
  v.resize(n);
  mu.resize(n);
  for (int k = 0; k < n; ++k) {
    const double t = 2 * kPi * k / n;
    w[k] = std::cos(t) * d(k, 0) + std::sin(t) * d(k, 1);
    v[k] = -std::sin(t) * d(k, 0) + std::cos(t) * d(k, 1);
  }
  const double dt = 2 * kPi / n;
  for (int k = 0; k < n; ++k) {
    const double dw = (w[(k + 1) % n] - w[(k + n - 1) % n]) / (2 * dt);
    mu[k] = (v[k] - dw) / radius;
  }
}

/// Where φ₀ is read: the open end face of a plain tube, else a ring at the rim's neutral radius and mid-width.
class RotationReader {
public:
  RotationReader(const FlexsplineModel& c, const TetMesh& mesh) : mesh_(mesh), sampler_(mesh) {
    const auto& f = c.flexspline;
    plain_tube_ = is_plain_tube(f);
    radius_ = neutral_radius(f);
    z_ = plain_tube_ ? f.length_m : f.length_m - 0.5 * f.rim_width_m;
    ring_ = reading_ring(radius_, z_);
    if (plain_tube_) {
      std::vector<bool> seen(mesh.n_nodes(), false);
      for (const auto* face : select_faces(mesh, kSurfaceOpenEnd))
        for (int v : face->nodes)
          if (!seen[v]) {
            seen[v] = true;
            end_nodes_.push_back(v);
          }
    }
  }
  double operator()(const Eigen::VectorXd& u) const {
    if (!plain_tube_) return rigid_rotation_z(ring_.points, sample(sampler_, ring_, u));
    RowMatrixX3d p(end_nodes_.size(), 3), d(end_nodes_.size(), 3);
    for (std::size_t k = 0; k < end_nodes_.size(); ++k) {
      p.row(k) = mesh_.nodes.row(end_nodes_[k]);
      d.row(k) = u.segment<3>(3 * end_nodes_[k]).transpose();
    }
    return rigid_rotation_z(p, d);
  }
  const PointSampler& sampler() const { return sampler_; }
  double radius() const { return radius_; }
  double z() const { return z_; }

private:
  const TetMesh& mesh_;
  PointSampler sampler_;
  bool plain_tube_ = false;
  double radius_ = 0, z_ = 0;
  Ring ring_;
  std::vector<int> end_nodes_;
};

}  // namespace

Eigen::VectorXd torque_load_vector(const FlexsplineModel& c, const TetMesh& mesh, double torque_Nm) {
  return unit_torque_load(c, mesh) * torque_Nm;
}

double reading_rotation(const FlexsplineModel& c, const TetMesh& mesh, const Eigen::VectorXd& u) {
  return RotationReader(c, mesh)(u);
}

double neutral_radius(const FlexsplineParams& f) {
  return f.inner_radius_m + 0.5 * (f.teeth == TeethModel::None ? f.wall_thickness_m : f.rim_thickness_m);
}

namespace {

Eigen::VectorXd contact_load(const BandStations& st, const Eigen::VectorXd& p) { return st.loads * p; }

/// Total radial force (N) of a full load vector: Σ f·e_r over the nodes.
double radial_total(const TetMesh& mesh, const Eigen::VectorXd& f) {
  double sum = 0;
  for (std::size_t i = 0; i < mesh.n_nodes(); ++i) {
    const double t = theta_of(mesh.nodes.row(i).transpose());
    sum += std::cos(t) * f[3 * i] + std::sin(t) * f[3 * i + 1];
  }
  return sum;
}

/// Radial displacement of the neutral circle at the rim mid-width at θ, mean of θ and θ + π.
double rim_w(const FlexsplineParams& f, const PointSampler& sampler, double radius, const Eigen::VectorXd& u,
             double t) {
  const double z = f.length_m - 0.5 * f.rim_width_m;
  double sum = 0;
  for (const double a : {t, t + kPi}) {
    const Eigen::Vector3d d = sampler.displacement({radius * std::cos(a), radius * std::sin(a), z}, u);
    sum += std::cos(a) * d[0] + std::sin(a) * d[1];
  }
  return 0.5 * sum;
}

/// Hoop stress extremes over the open half, the profile at the generator's plane and the nominal stress on it; with
/// the generator's w0 reached (`w_major_m`), the thin ring theory's bending stress for it.
HoopStressExtreme hoop_stress(const FlexsplineModel& c, const TetMesh& mesh, const PointSampler& sampler,
                              const LoadCaseSolution& lc, double reading_z, std::optional<double> w_major_m) {
  const auto& f = c.flexspline;
  HoopStressExtreme h;
  const CylindricalFields cyl = cylindrical_components(mesh, lc.u, lc.stress);
  const double z = c.wave_generator ? f.length_m - c.wave_generator->axial_position_m : reading_z;
  const double inset = 1e-3 * f.inner_radius_m;
  h.profile_z_m = z;
  h.inner_radius_m = f.inner_radius_m + inset;
  // The wall's outer surface: the body wall (no teeth), the ring's outer radius (teeth as a ring), the root circle
  // (explicit teeth or the tooth layer: the teeth carry little hoop stress).
  h.outer_radius_m = (f.teeth == TeethModel::None   ? f.inner_radius_m + f.wall_thickness_m
                      : f.teeth == TeethModel::Ring ? rim_outer_radius(f, c.gear)
                                                    : f.inner_radius_m + f.rim_thickness_m) -
                     inset;
  for (int k = 0; k < kRingSamples; ++k) {
    const double t = 2 * kPi * k / kRingSamples;
    for (const auto& [r, out] : {std::pair{h.inner_radius_m, &h.inner_Pa}, std::pair{h.outer_radius_m, &h.outer_Pa}})
      out->push_back(sampler.interpolate(Eigen::Vector3d(r * std::cos(t), r * std::sin(t), z), cyl.s_thetatheta)[0]);
  }
  h.max_tensile_Pa = -1e300;
  h.max_compressive_Pa = 1e300;
  for (std::size_t i = 0; i < mesh.n_nodes(); ++i) {
    if (mesh.nodes(i, 2) < 0.5 * f.length_m) continue;
    const double st = cyl.s_thetatheta[i];
    const double ang = std::fmod(theta_of(mesh.nodes.row(i).transpose()) * 180 / kPi + 360.0, 360.0);
    if (st > h.max_tensile_Pa) {
      h.max_tensile_Pa = st;
      h.max_tensile_angle_deg = ang;
      h.max_tensile_z_m = mesh.nodes(i, 2);
    }
    if (st < h.max_compressive_Pa) {
      h.max_compressive_Pa = st;
      h.max_compressive_angle_deg = ang;
      h.max_compressive_z_m = mesh.nodes(i, 2);
    }
  }
  const int k = static_cast<int>(std::lround(h.nominal_angle_deg));
  h.nominal_bending_Pa = 0.5 * (h.outer_Pa[k] - h.inner_Pa[k]);
  h.nominal_membrane_Pa = 0.5 * (h.outer_Pa[k] + h.inner_Pa[k]);
  if (w_major_m) {
    const double ri = f.inner_radius_m;
    const double t_wall = h.outer_radius_m + (h.inner_radius_m - ri) - ri;  // the profile's wall
    h.ring_theory_bending_Pa = ring_theory_bending_stress(*c.wave_generator, c.material.youngs_modulus_Pa,
                                                          ri + 0.5 * t_wall, t_wall, *w_major_m,
                                                          h.nominal_angle_deg * kPi / 180);
  }
  return h;
}

}  // namespace

CupTorsionTheory cup_torsion_theory(const FlexsplineParams& f, double rim_outer_radius_m, const Material& material,
                                    double torque_Nm, double reading_z_m) {
  CupTorsionTheory t;
  const double G = material.shear_modulus_Pa(), T = torque_Nm;
  auto J = [](double a, double b) { return kPi / 2 * (std::pow(b, 4) - std::pow(a, 4)); };
  const double ri = f.inner_radius_m, ro = ri + f.wall_thickness_m;
  const bool cup = f.shape == FlexsplineShape::Cup;
  const bool plain_tube = !cup && f.teeth == TeethModel::None;
  const double body_start = cup ? f.diaphragm_thickness_m : 0.0;
  const double rim_start = plain_tube ? reading_z_m : std::max(body_start, f.length_m - f.rim_width_m);
  if (cup) {
    t.diaphragm_inner_radius_m = f.boss_radius_m;
    t.diaphragm_outer_radius_m = 0.5 * (ri + ro);
    t.diaphragm_rad = T / (4 * kPi * G * f.diaphragm_thickness_m) *
                      (1 / std::pow(t.diaphragm_inner_radius_m, 2) - 1 / std::pow(t.diaphragm_outer_radius_m, 2));
  }
  t.body_length_m = rim_start - body_start;
  t.body_rad = T * t.body_length_m / (G * J(ri, ro));
  t.rim_outer_radius_m = rim_outer_radius_m;
  t.rim_length_m = std::max(0.0, reading_z_m - rim_start);
  if (t.rim_length_m > 0) t.rim_rad = T * t.rim_length_m / (G * J(ri, rim_outer_radius_m));
  return t;
}

double ring_theory_bending_stress(const WaveGeneratorParams& w, double youngs_modulus_Pa, double r_mid_m,
                                  double thickness_m, double w0_m, double at_rad) {
  double dkappa = 0;
  if (cam_of(w)) {
    dkappa = 3 * w0_m * std::cos(2 * at_rad) / (r_mid_m * r_mid_m);
  } else {
    // The forces as the FEM applies them, all harmonics n ≥ 2 (n = 0 stretches an inextensible ring not at all, n = 1
    // is a rigid shift): w ∝ Σ F cos n(θ−α)/(n²−1)², Δκ ∝ Σ F cos n(θ−α)/(n²−1)/r²; the tail beyond n = 4000 is
    // below 1e-4 of the sum.
    const std::vector<WaveGeneratorForce> forces = generator_forces(w);
    double w_at_0 = 0, k_at = 0;
    for (int n = 2; n <= 4000; ++n) {
      const double a = n * n - 1.0;
      for (const auto& f : forces) {
        w_at_0 += f.weight * std::cos(n * f.angle_rad) / (a * a);
        k_at += f.weight * std::cos(n * (at_rad - f.angle_rad)) / a;
      }
    }
    dkappa = w0_m / w_at_0 * k_at / (r_mid_m * r_mid_m);
  }
  return youngs_modulus_Pa * 0.5 * thickness_m * dkappa;
}

namespace {

// The steps of the analysis, in the order the driver below takes them.

/// The unit loads, solved together on the one factorisation: 1 N·m of the case's torque load and, with a generator,
/// its own pattern (a body that pushes: a unit moment on the band, conjugate to the band's turn; the force
/// idealisation: its unit forces).
struct UnitSolutions {
  Eigen::VectorXd torque_load, torque_u;        ///< 3·n_nodes
  Eigen::VectorXd generator_load, generator_u;  ///< 3·n_nodes; empty without a generator
};

UnitSolutions solve_unit_loads(const FlexsplineModel& c, const TetMesh& mesh, const FlexsplineSystem& eq,
                               const GeneratorStations* gen) {
  UnitSolutions unit;
  unit.torque_load = unit_torque_load(c, mesh);
  Eigen::MatrixXd loads(3 * mesh.n_nodes(), gen ? 2 : 1);
  loads.col(0) = unit.torque_load;
  if (gen) loads.col(1) = gen->unilateral ? band_turn_load(c, mesh) : gen->force_load;
  const Eigen::MatrixXd U = eq.solve(loads);
  unit.torque_u = U.col(0);
  if (gen) {
    unit.generator_load = loads.col(1);
    unit.generator_u = U.col(1);
  }
  return unit;
}

/// What the torque T_ref adds with the generator in place: displacements (3·n_nodes), the generator's forces on the
/// flexspline in that increment (its support; zero without a generator), and (T, φ₀/T) at several torques.
struct TorqueIncrement {
  Eigen::VectorXd u, f_support;
  std::vector<std::pair<double, double>> sweep;
};


/// The torque without a generator: linear, one compliance at every torque.
TorqueIncrement torque_alone(const TetMesh& mesh, const UnitSolutions& unit, const RotationReader& rotation,
                             double T_ref) {
  TorqueIncrement inc{unit.torque_u * T_ref, Eigen::VectorXd::Zero(3 * mesh.n_nodes()), {}};
  for (const double k : kSweep) inc.sweep.emplace_back(k * T_ref, rotation(inc.u) / T_ref);
  return inc;
}

/// The generator's load cases: the generator alone (displacements, its forces on the flexspline, the rim's net
/// rotation and the forces' resultant), the torque's increment with the generator in place, and the read-out.
struct GeneratorCases {
  Eigen::VectorXd u, f;
  double rim_rotation_rad = 0;
  Resultant resultant;
  TorqueIncrement torque;
  GeneratorReadout readout;
  double force_per_point_N = 0;  ///< the force idealisation: each point load after scaling
};

/// The generator's stations as the contact sees them: their influence matrix C (pairs × pairs, m/N) and their
/// displacement under the unit torque (per pair, m per N·m).
struct StationResponse {
  Eigen::MatrixXd C;
  Eigen::VectorXd u0_torque;
};

/// A generator that pushes and never pulls (cam, rollers): its contact alone, with T_ref and with the sweep's torques,
/// each a small problem on the stations' influence matrix; then one solve for the displacements of all their contact
/// loads.
GeneratorCases generator_contact_cases(const FlexsplineModel& c, const TetMesh& mesh, const FlexsplineSystem& eq,
                                       const GeneratorStations& gen, const StationResponse& response,
                                       const UnitSolutions& unit, const RotationReader& rotation, double T_ref) {
  const auto& w = *c.wave_generator;
  const Eigen::MatrixXd& C = response.C;
  GeneratorCases g;
  GeneratorReadout& gr = g.readout;
  Eigen::VectorXd obstacle = gen.obstacle_m;
  if (std::holds_alternative<Rollers>(w.model)) {
    // Set the rollers out so the major axis reaches w0: all four touch (symmetric), so the generator case is linear
    // in the rollers' standoff; one solve for the unit standoff gives the scale.
    const Eigen::VectorXd u_unit = eq.solve(contact_load(gen.stations, bilateral_support(C, obstacle).force_N)).col(0);
    obstacle *= rollers_setout(w, rim_w(c.flexspline, rotation.sampler(), rotation.radius(), u_unit, 0.0));
  }
  gr.obstacle_m = obstacle;
  // The wave stays with the generator (the gaps ignore the band's turn), and the bearing in series (a cam's).
  GeneratorContactModel model;
  const std::vector<bool> all(mesh.n_nodes(), true);
  model.turn_gap_m_per_rad.resize(C.rows());
  for (Eigen::Index k = 0; k < C.rows(); ++k)
    model.turn_gap_m_per_rad[k] = moment_about_z(mesh, Eigen::VectorXd(gen.stations.loads.col(k)), all);
  model.band_turn_rad_per_N = gen.stations.loads.transpose() * unit.generator_u;
  const double band_turn_per_T = unit.generator_load.dot(unit.torque_u);  // rad per N·m of the torque
  if (cam_of(w) && w.bearing)
    model.approach_m = bearing_pair_approach(*w.bearing, gen.stations.half_width_rad);
  auto contact = [&](double torque) {
    return generator_contact(C, obstacle - torque * response.u0_torque, torque * band_turn_per_T, model);
  };
  const StationForces p_gen = contact(0.0);
  gr.contact_iterations = p_gen.iterations;
  std::vector<double> sweep_T;
  for (const double k : kSweep) sweep_T.push_back(k * T_ref);
  Eigen::MatrixXd contact_loads(3 * mesh.n_nodes(), 2 + sweep_T.size());
  contact_loads.col(0) = contact_load(gen.stations, p_gen.force_N);
  const StationForces p_comb = contact(T_ref);
  contact_loads.col(1) = contact_load(gen.stations, p_comb.force_N);
  for (std::size_t k = 0; k < sweep_T.size(); ++k)
    contact_loads.col(2 + k) = contact_load(gen.stations, contact(sweep_T[k]).force_N);
  const Eigen::MatrixXd V = eq.solve(contact_loads);
  g.u = V.col(0);
  g.f = contact_loads.col(0);
  g.torque.u = V.col(1) - V.col(0) + unit.torque_u * T_ref;
  g.torque.f_support = contact_loads.col(1) - contact_loads.col(0);
  const double rot_gen = rotation(g.u);
  for (std::size_t k = 0; k < sweep_T.size(); ++k)
    g.torque.sweep.emplace_back(sweep_T[k],
                                (rotation(V.col(2 + k) + unit.torque_u * sweep_T[k]) - rot_gen) / sweep_T[k]);
  gr.force_wg_N.assign(p_gen.force_N.data(), p_gen.force_N.data() + p_gen.force_N.size());
  gr.force_comb_N.assign(p_comb.force_N.data(), p_comb.force_N.data() + p_comb.force_N.size());
  const double touching_gap = kTouchingGap * *w.radial_deformation_m;
  const double step = gen.stations.half_width_rad;  // the stations' spacing
  gr.zones_wg_deg = contact_zones_deg(gen.stations.angle_rad, touching(p_gen, touching_gap), step);
  gr.zones_comb_deg = contact_zones_deg(gen.stations.angle_rad, touching(p_comb, touching_gap), step);
  gr.min_contact_force_N = p_gen.force_N.minCoeff();
  if (model.approach_m) {
    const double p_max = std::max(p_gen.force_N.maxCoeff(), p_comb.force_N.maxCoeff());
    gr.bearing_max_ball_load_N = ball_load_N(*w.bearing, gen.stations.half_width_rad, p_max);
    gr.bearing_max_approach_m = 0.5 * model.approach_m(p_max);
  }
  return g;
}

/// The force idealisation: the unit forces scaled to w0 (or force_N); the torque case with the band held radially at
/// the stations (bilateral), so linear in the torque.
GeneratorCases generator_force_cases(const FlexsplineModel& c, const TetMesh& mesh, const FlexsplineSystem& eq,
                                     const GeneratorStations& gen, const StationResponse& response,
                                     const UnitSolutions& unit, const RotationReader& rotation, double T_ref) {
  const WaveGeneratorParams& w = *c.wave_generator;
  const double w_unit = rim_w(c.flexspline, rotation.sampler(), rotation.radius(), unit.generator_u, 0.0);
  if (!(w_unit > 0))
    throw InputError("wave_generator: the generator does not push the major axis outward (w = " +
                     std::to_string(w_unit) + " m per unit load); check the force angles");
  double total_at_end = 0;  // sum of weights near θ = 0 (one end of the major axis)
  for (const auto& force : generator_forces(w))
    if (std::abs(wrap_pi(force.angle_rad)) < kPi / 2) total_at_end += force.weight;
  const double scale =
      w.radial_deformation_m ? *w.radial_deformation_m / w_unit : w.force_N / std::max(total_at_end, 1e-300);
  GeneratorCases g;
  GeneratorReadout& gr = g.readout;
  g.force_per_point_N = scale * point_force_share(w.model);
  g.u = unit.generator_u * scale;
  g.f = gen.force_load * scale;
  const StationForces p_T = bilateral_support(response.C, -T_ref * response.u0_torque);
  g.torque.f_support = contact_load(gen.stations, p_T.force_N);
  g.torque.u = eq.solve(g.torque.f_support).col(0) + unit.torque_u * T_ref;
  for (const double k : kSweep) g.torque.sweep.emplace_back(k * T_ref, rotation(g.torque.u) / T_ref);
  gr.force_comb_N.assign(p_T.force_N.data(), p_T.force_N.data() + p_T.force_N.size());
  double fmin = 1e300;
  for (const auto& force : generator_forces(w)) fmin = std::min(fmin, force.weight * scale);
  gr.min_contact_force_N = fmin;
  for (const auto& force : generator_forces(w)) {
    const double a = wrap_pi(force.angle_rad) * 180 / kPi, h = kGeneratorPatchHalfAngle_rad * 180 / kPi;
    gr.zones_wg_deg.emplace_back(a - h, a + h);
  }
  return g;
}

/// The generator: the influence matrix of its stations, its contact (or forces) alone and under the torque, and what
/// it does to the flexspline at the torque T.
GeneratorCases solve_generator(const FlexsplineModel& c, const TetMesh& mesh, const FlexsplineSystem& eq,
                               const GeneratorStations& gen, const UnitSolutions& unit, const RotationReader& rotation,
                               double T, double T_ref) {
  progress("generator: influence of " + std::to_string(gen.stations.angle_rad.size()) + " contact station pairs");
  const StationResponse response{eq.influence(gen.stations.loads), gen.stations.loads.transpose() * unit.torque_u};
  GeneratorCases g = gen.unilateral ? generator_contact_cases(c, mesh, eq, gen, response, unit, rotation, T_ref)
                                    : generator_force_cases(c, mesh, eq, gen, response, unit, rotation, T_ref);
  GeneratorReadout& gr = g.readout;
  gr.model = model_name(c.wave_generator->model);
  gr.unilateral = gen.unilateral;
  gr.station_angle_rad = gen.stations.angle_rad;
  gr.total_radial_force_N = radial_total(mesh, g.f);
  const std::vector<bool> all(mesh.n_nodes(), true);
  gr.reaction_torque_Nm = moment_about_z(mesh, g.torque.f_support, all) * (T / T_ref);
  gr.w_major_m = rim_w(c.flexspline, rotation.sampler(), rotation.radius(), g.u, 0.0);
  gr.w_minor_m = rim_w(c.flexspline, rotation.sampler(), rotation.radius(), g.u, kPi / 2);
  g.resultant = load_resultant(mesh, g.f);
  g.rim_rotation_rad = rotation(g.u);
  return g;
}

/// The body wall's torsion alone, T·L/(G·J), L from where the body wall starts (the clamp of a tube, the diaphragm's
/// face of a cup) to the reading plane.
double body_wall_torsion_rad(const FlexsplineModel& c, double torque_Nm, double reading_z_m) {
  const auto& f = c.flexspline;
  const double G = c.material.shear_modulus_Pa();
  const double ri = f.inner_radius_m, ro = f.inner_radius_m + f.wall_thickness_m;
  const double J = kPi / 2 * (std::pow(ro, 4) - std::pow(ri, 4));
  const double body_start = f.shape == FlexsplineShape::Cup ? f.diaphragm_thickness_m : 0.0;
  return torque_Nm * (reading_z_m - body_start) / (G * J);
}

/// φ₀ and C_τ: the rim's rotation the torque adds with the generator in place, and the torque case at T
/// (3·n_nodes).
struct TorqueReadout {
  double compliance_rad_per_Nm = 0, phi0_rad = 0;
  Eigen::VectorXd u;
};

TorqueReadout read_torque(const RotationReader& rotation, const TorqueIncrement& inc, double T, double T_ref) {
  TorqueReadout r;
  r.compliance_rad_per_Nm = rotation(inc.u) / T_ref;
  r.phi0_rad = r.compliance_rad_per_Nm * T;
  r.u = inc.u * (T / T_ref);
  return r;
}

/// The checks: the torque case's balance (the applied moment vs the clamp's reaction plus the generator's), the
/// closed forms of the torsion at the reading plane, and the generator's self-equilibrium and net rim rotation.
FemChecks check(const FlexsplineModel& c, const TetMesh& mesh, const FlexsplineSystem& eq, const UnitSolutions& unit,
                const TorqueIncrement& inc, const GeneratorCases* gen, double T, double T_ref, double reading_z_m) {
  FemChecks k;
  const double to_T = T / T_ref;
  const std::vector<bool> all(mesh.n_nodes(), true);
  k.applied_torque_Nm = moment_about_z(mesh, unit.torque_load * T, all);
  const Eigen::VectorXd clamp_reactions =
      internal_forces(mesh, c.material, inc.u * to_T) - unit.torque_load * T - inc.f_support * to_T;
  k.reaction_torque_Nm =
      moment_about_z(mesh, clamp_reactions, eq.clamped) + moment_about_z(mesh, inc.f_support * to_T, all);
  k.phi0_theory_rad = body_wall_torsion_rad(c, T, reading_z_m);
  k.phi0_theory_cup =
      cup_torsion_theory(c.flexspline, rim_outer_radius(c.flexspline, c.gear), c.material, T, reading_z_m);
  if (gen) {
    k.generator_net_force = gen->resultant.force;
    k.generator_net_moment = gen->resultant.moment;
    k.generator_rotation_rad = gen->rim_rotation_rad;
  }
  return k;
}

/// The load cases: the generator alone, the torque (with the generator in place), both; or the torque alone.
std::vector<LoadCaseSolution> load_cases(const TorqueReadout& torque, const GeneratorCases* gen,
                                         const RotationReader& rotation) {
  if (!gen) return {{"torque", torque.u, RowMatrixX6d(), torque.phi0_rad}};
  const Eigen::VectorXd u_comb = gen->u + torque.u;
  return {{"generator", gen->u, RowMatrixX6d(), gen->rim_rotation_rad},
          {"torque", torque.u, RowMatrixX6d(), torque.phi0_rad},
          {"generator_torque", u_comb, RowMatrixX6d(), rotation(u_comb)}};
}

/// The deformed neutral curve at the rim mid-width for the generator case and the combined case.
/// The rim's curve of u_gen (the *_wg fields; with u_comb also the *_comb ones) on the neutral circle at z_m.
NeutralCurveSamples curve_at(const RotationReader& rotation, double z_m, const Eigen::VectorXd& u_gen,
                             const Eigen::VectorXd* u_comb = nullptr) {
  NeutralCurveSamples nc;
  nc.radius_m = rotation.radius();
  nc.z_m = z_m;
  const Ring ring = reading_ring(nc.radius_m, z_m);
  for (int k = 0; k < kRingSamples; ++k) nc.phi_rad.push_back(2 * kPi * k / kRingSamples);
  curve_of(ring, sample(rotation.sampler(), ring, u_gen), nc.radius_m, nc.w_wg_m, nc.v_wg_m, nc.mu_wg_rad);
  if (u_comb)
    curve_of(ring, sample(rotation.sampler(), ring, *u_comb), nc.radius_m, nc.w_comb_m, nc.v_comb_m, nc.mu_comb_rad);
  return nc;
}

NeutralCurveSamples neutral_curve(const FlexsplineParams& f, const RotationReader& rotation,
                                  const Eigen::VectorXd& u_gen, const Eigen::VectorXd& u_comb) {
  return curve_at(rotation, f.length_m - 0.5 * f.rim_width_m, u_gen, &u_comb);
}

/// φ₀ over the engagement zones: the mean tangential displacement of the torque case u_torque on the reading circle
/// there, over its radius (over the whole circle for a uniform torque loading).
double engaged_rotation(const FlexsplineModel& c, const RotationReader& rotation, const Eigen::VectorXd& u_torque) {
  const double half = c.load.torque_loading == TorqueLoading::Uniform ? kPi : c.load.engagement_half_angle_rad;
  const Ring ring = reading_ring(rotation.radius(), rotation.z());
  std::vector<double> w, v, mu;
  curve_of(ring, sample(rotation.sampler(), ring, u_torque), rotation.radius(), w, v, mu);
  double sum = 0;
  int n = 0;
  for (int k = 0; k < kRingSamples; ++k) {
    const double t = 2 * kPi * k / kRingSamples;
    if (std::abs(wrap_pi(t)) <= half + 1e-9 || std::abs(wrap_pi(t - kPi)) <= half + 1e-9) {
      sum += v[k];
      ++n;
    }
  }
  return sum / n / rotation.radius();
}

/// Fatigue over one generator revolution of the combined case's nodal stresses, at the rim and the diaphragm's fillet.
FatigueReadout rim_fatigue(const FlexsplineModel& c, const PointSampler& sampler, const RowMatrixX6d& stress) {
  const auto& f = c.flexspline;
  const auto& w = *c.wave_generator;
  return flexspline_fatigue(f, rim_outer_radius(f, c.gear), f.length_m - w.axial_position_m, w.band_width_m,
                            c.material, sampler, stress);
}

}  // namespace

std::vector<NeutralCurveSamples> neutral_curves_at(const FlexsplineModel& c, const TetMesh& mesh,
                                                   const Eigen::VectorXd& u, const std::vector<double>& z_m) {
  const RotationReader rotation(c, mesh);
  std::vector<NeutralCurveSamples> out;
  for (const double z : z_m) out.push_back(curve_at(rotation, z, u));
  return out;
}

FlexsplineSolution analyse_flexspline(const FlexsplineModel& c, const TetMesh& mesh) {
  return analyse_flexspline(c, mesh, assemble_and_factorise(c, mesh));
}

FlexsplineSolution analyse_flexspline(const FlexsplineModel& c, const TetMesh& mesh, const FlexsplineSystem& eq) {
  Stopwatch clock;
  const double T = c.load.torque_Nm, T_ref = T != 0.0 ? T : 1.0;  // compliance is read at T (or 1 N·m without torque)

  // Solves: the unit loads; the generator alone and under the torque; what the torque adds with it in place.
  const std::optional<GeneratorStations> stations =
      c.wave_generator ? std::optional(generator_stations(c, mesh)) : std::nullopt;
  const UnitSolutions unit = solve_unit_loads(c, mesh, eq, stations ? &*stations : nullptr);
  const RotationReader rotation(c, mesh);
  const std::optional<GeneratorCases> gen =
      stations ? std::optional(solve_generator(c, mesh, eq, *stations, unit, rotation, T, T_ref)) : std::nullopt;
  const TorqueIncrement inc = gen ? gen->torque : torque_alone(mesh, unit, rotation, T_ref);
  FlexsplineSolution s;
  s.timings = {eq.factor->stats(), eq.assemble_s, clock.lap()};

  // Read-outs: φ₀ and C_τ, the load cases, the generator and the neutral curve; the checks.
  const TorqueReadout torque = read_torque(rotation, inc, T, T_ref);
  s.torque_Nm = T;
  s.phi0_rad = torque.phi0_rad;
  s.compliance_rad_per_Nm = torque.compliance_rad_per_Nm;
  s.torque_sweep = inc.sweep;
  s.reading_radius_m = rotation.radius();
  s.reading_z_m = rotation.z();
  s.phi0_engaged_rad = is_plain_tube(c.flexspline) ? s.phi0_rad : engaged_rotation(c, rotation, torque.u);
  s.cases = load_cases(torque, gen ? &*gen : nullptr, rotation);
  if (gen) {
    s.generator = gen->readout;
    s.generator_force_N = gen->force_per_point_N;
    s.generator_w0_m = gen->readout.w_major_m;
    s.neutral_curve = neutral_curve(c.flexspline, rotation, s.cases.front().u, s.cases.back().u);
  }
  s.checks = check(c, mesh, eq, unit, inc, gen ? &*gen : nullptr, T, T_ref, s.reading_z_m);

  // Stresses of every case; the hoop stress of the generator case if any, else of the torque case; fatigue.
  for (auto& lc : s.cases) lc.stress = nodal_stress(mesh, c.material, lc.u);
  s.hoop = hoop_stress(c, mesh, rotation.sampler(), s.cases.front(), s.reading_z_m,
                       gen ? std::optional(gen->readout.w_major_m) : std::nullopt);
  if (gen) s.fatigue = rim_fatigue(c, rotation.sampler(), s.cases.back().stress);
  return s;
}

}  // namespace sw
