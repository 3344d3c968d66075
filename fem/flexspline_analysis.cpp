#include "fem/flexspline_analysis.hpp"

#include <cmath>
#include <numbers>

#include "common/error.hpp"
#include "common/progress.hpp"
#include "fem/assembly.hpp"
#include "fem/loads.hpp"

namespace sw {
namespace {

constexpr double kPi = std::numbers::pi;
constexpr int kRingSamples = 360;                     // 1° steps around the reading circle
constexpr double kPatchHalfAngle = 3.0 * kPi / 180;   // half-width of a generator force patch

double wrap_pi(double a) { return std::remainder(a, 2 * kPi); }
double theta_of(const Eigen::Vector3d& x) { return std::atan2(x[1], x[0]); }

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

/// Unit-torque tangential traction on the rim, or the exact torsion shear on the open end of a plain tube.
Eigen::VectorXd unit_torque_load(const Case& c, const TetMesh& mesh) {
  const auto& f = c.flexspline;
  if (f.teeth == TeethModel::None && f.shape == FlexsplineShape::Tube)
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

/// Angles (from the major axis) and weights of the generator's point forces.
std::vector<WaveGeneratorForce> generator_forces(const WaveGeneratorParams& w) {
  switch (w.model) {
    case WaveGeneratorModel::FourForce:
      return {{w.beta_rad, 0.5}, {-w.beta_rad, 0.5}, {kPi + w.beta_rad, 0.5}, {kPi - w.beta_rad, 0.5}};
    case WaveGeneratorModel::TwoForce:
      return {{0.0, 1.0}, {kPi, 1.0}};
    case WaveGeneratorModel::Forces:
      return w.forces;
    case WaveGeneratorModel::Cam:
      break;
  }
  throw std::logic_error("generator_forces: a cam prescribes a shape, it has no forces");
}

/// Radial outward patch loads on the inner wall, one per force, each of magnitude weight (N) as the integral of the
/// pressure over its patch.
Eigen::VectorXd generator_load(const Case& c, const TetMesh& mesh) {
  const auto& w = *c.wave_generator;
  const double z_wg = c.flexspline.length_m - w.axial_position_m;
  Eigen::VectorXd f = Eigen::VectorXd::Zero(3 * mesh.n_nodes());
  for (const auto& force : generator_forces(w)) {
    auto in_patch = [&](const Eigen::Vector3d& x) {
      return std::abs(wrap_pi(theta_of(x) - force.angle_rad)) <= kPatchHalfAngle &&
             std::abs(x[2] - z_wg) <= 0.5 * w.band_width_m;
    };
    const auto faces = select_faces(mesh, kSurfaceInner, in_patch);
    if (faces.empty())
      throw InputError("wave_generator: no inner-wall faces under the force at " +
                       std::to_string(force.angle_rad * 180 / kPi) + " deg, z = " + std::to_string(z_wg * 1e3) +
                       " mm; check wave_generator.axial_position_mm / band_width_mm or refine mesh.size_mm");
    const double area = faces_area(mesh, faces);
    f += traction_load(mesh, faces, [&](const Eigen::Vector3d& x, const Eigen::Vector3d&) -> Eigen::Vector3d {
      const double r = std::hypot(x[0], x[1]);
      return Eigen::Vector3d(x[0] / r, x[1] / r, 0.0) * (force.weight / area);
    });
  }
  return f;
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
  RotationReader(const Case& c, const TetMesh& mesh) : mesh_(mesh), sampler_(mesh) {
    const auto& f = c.flexspline;
    plain_tube_ = f.shape == FlexsplineShape::Tube && f.teeth == TeethModel::None;
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

Eigen::VectorXd torque_load_vector(const Case& c, const TetMesh& mesh, double torque_Nm) {
  return unit_torque_load(c, mesh) * torque_Nm;
}

double reading_rotation(const Case& c, const TetMesh& mesh, const Eigen::VectorXd& u) {
  return RotationReader(c, mesh)(u);
}

std::vector<bool> clamped_nodes(const TetMesh& mesh) {
  std::vector<bool> fixed(mesh.n_nodes(), false);
  for (const auto& f : mesh.faces)
    if (f.marker == kSurfaceClamped)
      for (int v : f.nodes) fixed[v] = true;
  return fixed;
}

double neutral_radius(const FlexsplineParams& f) {
  return f.inner_radius_m + 0.5 * (f.teeth == TeethModel::None ? f.wall_thickness_m : f.rim_thickness_m);
}

FlexsplineSolution analyse_flexspline(const Case& c, const TetMesh& mesh) {
  FlexsplineSolution s;
  const auto& f = c.flexspline;

  // Supports: the clamped faces; under a cam also the radial dof of the inner wall over the generator's band, in a
  // cylindrical frame at each of those nodes. The same supports serve every load case, so one factorisation does.
  const bool cam = c.wave_generator && c.wave_generator->model == WaveGeneratorModel::Cam;
  const std::vector<bool> fixed_node = clamped_nodes(mesh);
  std::vector<bool> fixed(3 * mesh.n_nodes());
  for (std::size_t i = 0; i < mesh.n_nodes(); ++i) fixed[3 * i] = fixed[3 * i + 1] = fixed[3 * i + 2] = fixed_node[i];
  NodeFrames frames;
  Eigen::VectorXd cam_shape = Eigen::VectorXd::Zero(3 * mesh.n_nodes());  // local radial values w0·cos2θ
  std::vector<bool> band_node(mesh.n_nodes(), false);
  if (cam) {
    const auto& w = *c.wave_generator;
    const double z_wg = f.length_m - w.axial_position_m;
    const auto band = select_faces(mesh, kSurfaceInner, [&](const Eigen::Vector3d& x) {
      return std::abs(x[2] - z_wg) <= 0.5 * w.band_width_m;
    });
    if (band.empty())
      throw InputError("wave_generator: no inner-wall faces in the cam's band at z = " + std::to_string(z_wg * 1e3) +
                       " mm; check wave_generator.axial_position_mm / band_width_mm");
    frames.frame_of_node.assign(mesh.n_nodes(), -1);
    for (const auto* face : band)
      for (int v : face->nodes) {
        if (band_node[v] || fixed_node[v]) continue;
        band_node[v] = true;
        const double t = theta_of(mesh.nodes.row(v).transpose());
        Eigen::Matrix3d R;
        R << std::cos(t), -std::sin(t), 0, std::sin(t), std::cos(t), 0, 0, 0, 1;  // columns e_r, e_θ, e_z
        frames.frame_of_node[v] = static_cast<int>(frames.rotations.size());
        frames.rotations.push_back(R);
        fixed[3 * v] = true;  // local radial component
        cam_shape[3 * v] = *w.radial_deformation_m * std::cos(2 * t);
      }
  }
  const DofMap dofs = make_dof_map(fixed);
  Stopwatch clock;
  progress("assemble: " + std::to_string(dofs.n_equations) + " equations");
  const SymmetricCsc K = assemble_stiffness(mesh, c.material, dofs, frames);
  s.assemble_s = clock.lap();
  progress("factorise: nnz(K) = " + std::to_string(K.nnz()));
  const CholmodFactor factor(K, equation_nodes(dofs));
  s.factor = factor.stats();
  progress("factorised: nnz(L) = " + std::to_string(static_cast<long long>(s.factor.factor_nnz)) + ", " +
           std::to_string(s.factor.factor_gflop) + " GF in " + std::to_string(s.factor.factor_s) + " s");
  clock.lap();

  // Right-hand sides: unit torque, and the unit generator (forces) or the cam's prescribed shape; solved together.
  s.torque_Nm = c.load.torque_Nm;
  const bool has_torque = s.torque_Nm != 0.0;
  const bool has_generator = c.wave_generator.has_value();
  const Eigen::VectorXd f_torque = unit_torque_load(c, mesh);
  Eigen::VectorXd f_gen;
  Eigen::MatrixXd B(dofs.n_equations, has_generator ? 2 : 1);
  B.col(0) = restrict_to_free(dofs, to_local(frames, f_torque));
  if (has_generator) {
    if (cam) {
      B.col(1) = dirichlet_lift(mesh, c.material, dofs, cam_shape, frames);
    } else {
      f_gen = generator_load(c, mesh);
      B.col(1) = restrict_to_free(dofs, f_gen);
    }
  }
  const Eigen::MatrixXd X = factor.solve(B);
  const Eigen::VectorXd zeros = Eigen::VectorXd::Zero(3 * mesh.n_nodes());
  const Eigen::VectorXd u_unit_torque = to_global(frames, expand_to_full(dofs, X.col(0), zeros));
  s.solve_s = clock.lap();

  const RotationReader rotation(c, mesh);
  const PointSampler& sampler = rotation.sampler();
  s.reading_radius_m = rotation.radius();
  s.reading_z_m = rotation.z();

  const double unit_rotation = rotation(u_unit_torque);
  s.compliance_rad_per_Nm = unit_rotation;
  s.phi0_rad = unit_rotation * s.torque_Nm;
  // Theory: T·L/(G·J) of the body wall, L from where the body wall starts (the clamp of a tube, the diaphragm's face
  // of a cup) to the reading plane.
  const double G = c.material.shear_modulus_Pa();
  const double ri = f.inner_radius_m, ro = f.inner_radius_m + f.wall_thickness_m;
  const double J = kPi / 2 * (std::pow(ro, 4) - std::pow(ri, 4));
  const double body_start = f.shape == FlexsplineShape::Cup ? f.diaphragm_thickness_m : 0.0;
  s.phi0_theory_rad = s.torque_Nm * (s.reading_z_m - body_start) / (G * J);

  // Torque balance: applied moment vs the reaction moment of the clamp (a cam's radial supports carry no moment).
  const Eigen::VectorXd u_torque = u_unit_torque * s.torque_Nm;
  s.applied_torque_Nm = moment_about_z(mesh, f_torque * s.torque_Nm, std::vector<bool>(mesh.n_nodes(), true));
  const Eigen::VectorXd reactions = internal_forces(mesh, c.material, u_torque) - f_torque * s.torque_Nm;
  s.reaction_torque_Nm = moment_about_z(mesh, reactions, fixed_node);

  Eigen::VectorXd u_gen;
  if (has_generator) {
    const auto& w = *c.wave_generator;
    const Eigen::VectorXd u_unit_gen = to_global(frames, expand_to_full(dofs, X.col(1), cam ? cam_shape : zeros));
    // Major-axis radial displacement of the neutral circle at the rim mid-width.
    const double z_mid = f.length_m - 0.5 * f.rim_width_m;
    const Eigen::Vector3d a(s.reading_radius_m, 0, z_mid), b(-s.reading_radius_m, 0, z_mid);
    const double w_unit = 0.5 * (sampler.displacement(a, u_unit_gen)[0] - sampler.displacement(b, u_unit_gen)[0]);
    if (!(w_unit > 0))
      throw InputError("wave_generator: the generator does not push the major axis outward (w = " +
                       std::to_string(w_unit) + " m per unit load); check the force angles");
    double scale = 1.0;  // a cam prescribes its shape: no scaling
    if (!cam) {
      double total_at_end = 0;  // sum of weights near θ = 0 (one end of the major axis)
      for (const auto& force : generator_forces(w))
        if (std::abs(wrap_pi(force.angle_rad)) < kPi / 2) total_at_end += force.weight;
      scale = w.radial_deformation_m ? *w.radial_deformation_m / w_unit : w.force_N / std::max(total_at_end, 1e-300);
      s.generator_force_N = scale * (w.model == WaveGeneratorModel::FourForce ? 0.5 : 1.0);
    }
    u_gen = u_unit_gen * scale;
    if (cam) {
      // The cam's contact forces on the flexspline: the reactions at the band nodes.
      const Eigen::VectorXd r = internal_forces(mesh, c.material, u_gen);
      f_gen = Eigen::VectorXd::Zero(3 * mesh.n_nodes());
      for (std::size_t i = 0; i < mesh.n_nodes(); ++i)
        if (band_node[i]) f_gen.segment<3>(3 * i) = r.segment<3>(3 * i);
    } else {
      f_gen *= scale;
    }
    s.generator_w0_m = w_unit * scale;
    const Resultant res = load_resultant(mesh, f_gen);
    s.generator_net_force = res.force;
    s.generator_net_moment = res.moment;
    s.generator_rotation_rad = rotation(u_gen);
  }

  s.cases.push_back({"torque", u_torque, RowMatrixX6d(), s.phi0_rad});
  if (has_generator) {
    s.cases.insert(s.cases.begin(), {"generator", u_gen, RowMatrixX6d(), s.generator_rotation_rad});
    const Eigen::VectorXd u_comb = u_gen + u_torque;
    s.cases.push_back({"generator_torque", u_comb, RowMatrixX6d(), rotation(u_comb)});
    // Torque sweep on the combined case: (φ(gen + T) − φ(gen)) / T must be constant (linearity).
    for (const double factor_T : {0.25, 0.5, 1.0, 2.0}) {
      const double T = factor_T * (has_torque ? s.torque_Nm : 1.0);
      s.torque_sweep.emplace_back(T, (rotation(u_gen + u_unit_torque * T) - s.generator_rotation_rad) / T);
    }
    // The deformed neutral curve at the rim mid-width for the generator and the combined case.
    NeutralCurveSamples nc;
    nc.radius_m = s.reading_radius_m;
    nc.z_m = f.length_m - 0.5 * f.rim_width_m;
    const Ring mid = reading_ring(nc.radius_m, nc.z_m);
    for (int k = 0; k < kRingSamples; ++k) nc.phi_rad.push_back(2 * kPi * k / kRingSamples);
    curve_of(mid, sample(sampler, mid, u_gen), nc.radius_m, nc.w_wg_m, nc.v_wg_m, nc.mu_wg_rad);
    curve_of(mid, sample(sampler, mid, u_comb), nc.radius_m, nc.w_comb_m, nc.v_comb_m, nc.mu_comb_rad);
    s.neutral_curve = nc;
  }

  // Stresses of every case; hoop extremes over the open half of the flexspline (away from the clamp's singularity).
  for (auto& lc : s.cases) lc.stress = nodal_stress(mesh, c.material, lc.u);
  const LoadCaseSolution& hoop_case = s.cases.front();
  const CylindricalFields cyl = cylindrical_components(mesh, hoop_case.u, hoop_case.stress);
  {
    // Hoop profile at the generator plane (or the rim's mid-width), just inside both walls of the rim base.
    const double z = c.wave_generator ? f.length_m - c.wave_generator->axial_position_m : s.reading_z_m;
    const double inset = 1e-3 * f.inner_radius_m;
    s.hoop.profile_z_m = z;
    s.hoop.inner_radius_m = f.inner_radius_m + inset;
    s.hoop.outer_radius_m = (f.teeth == TeethModel::None ? f.inner_radius_m + f.wall_thickness_m
                                                         : f.inner_radius_m + f.rim_thickness_m) - inset;
    for (int k = 0; k < kRingSamples; ++k) {
      const double t = 2 * kPi * k / kRingSamples;
      for (const auto& [r, out] : {std::pair{s.hoop.inner_radius_m, &s.hoop.inner_Pa},
                                   std::pair{s.hoop.outer_radius_m, &s.hoop.outer_Pa}})
        out->push_back(sampler.interpolate(Eigen::Vector3d(r * std::cos(t), r * std::sin(t), z),
                                           cyl.s_thetatheta)[0]);
    }
  }
  s.hoop.max_tensile_Pa = -1e300;
  s.hoop.max_compressive_Pa = 1e300;
  for (std::size_t i = 0; i < mesh.n_nodes(); ++i) {
    if (mesh.nodes(i, 2) < 0.5 * f.length_m) continue;
    const double st = cyl.s_thetatheta[i];
    const double ang = std::fmod(theta_of(mesh.nodes.row(i).transpose()) * 180 / kPi + 360.0, 360.0);
    if (st > s.hoop.max_tensile_Pa) {
      s.hoop.max_tensile_Pa = st;
      s.hoop.max_tensile_angle_deg = ang;
      s.hoop.max_tensile_z_m = mesh.nodes(i, 2);
    }
    if (st < s.hoop.max_compressive_Pa) {
      s.hoop.max_compressive_Pa = st;
      s.hoop.max_compressive_angle_deg = ang;
      s.hoop.max_compressive_z_m = mesh.nodes(i, 2);
    }
  }
  return s;
}

}  // namespace sw
