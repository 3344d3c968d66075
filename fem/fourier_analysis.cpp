#include "fem/fourier_analysis.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <functional>
#include <map>
#include <memory>
#include <optional>
#include <numbers>
#include <string>

#include <Eigen/LU>
#include <Eigen/Geometry>
#include <Eigen/Sparse>

#include "common/constants.hpp"
#include "common/error.hpp"
#include "common/progress.hpp"
#include "generator/cam_profile.hpp"
#include "fem/flexspline_system.hpp"
#include "fem/fourier_loads.hpp"
#include "fem/post.hpp"
#include "mesh/flexspline.hpp"

namespace sw {
namespace {

using namespace fourier;

constexpr double kPatchHalfAngle = kGeneratorPatchHalfAngle_rad;  // as the tet10 path
// A harmonic whose loads are below this fraction of the largest harmonic load is zero by the load's symmetry (e.g.
// the odd harmonics of a generator symmetric about both axes: the sum is exactly 0, the computed one round-off).
constexpr double kNoLoad = 1e-12;

/// The harmonic analysis of a case on its section (analyse_section_fourier) as the steps of run(): supports, loads,
/// the harmonics solved, the load cases built from them (the generator's contact or forces, the torque case) and the
/// figures read from them. The members are what one step hands to the next.
class SectionAnalyser {
public:
  SectionAnalyser(const FlexsplineModel& c, SectionMesh section, const BandRequest& request)
      : c_(c), f_(c.flexspline), N_(c.solver.harmonics), request_(request),
        plain_tube_(f_.shape == FlexsplineShape::Tube && f_.teeth == TeethModel::None),
        has_generator_(c.wave_generator.has_value()),
        z_wg_(c.wave_generator ? f_.length_m - c.wave_generator->axial_position_m : 0.0),
        z_mid_(f_.length_m - 0.5 * f_.rim_width_m), T_(c.load.torque_Nm), T_ref_(T_ != 0.0 ? T_ : 1.0) {
    out_.section = std::move(section);
    out_.harmonics_kept = N_;
    nn_ = sec_.n_nodes();
  }
  SectionAnalyser(const SectionAnalyser&) = delete;
  SectionAnalyser& operator=(const SectionAnalyser&) = delete;

  /// The solution; called once.
  FourierSolution run() {
    progress("fourier: section of " + std::to_string(nn_) + " nodes, " + std::to_string(sec_.triangles.size()) +
             " quadratic triangles, harmonics 0.." + std::to_string(N_));
    set_supports();
    set_torque_load();
    if (has_generator_) set_generator_loads();
    set_band_loads();
    solve_harmonics();
    set_reading_ring();
    read_torsion_theory();
    // Load cases (as the tet10 path, fem/flexspline_analysis.cpp). gen: the generator alone; inc: what the torque
    // T_ref adds with the generator in place.
    if (has_generator_) {
      read_generator();
    } else {
      inc_ = torque_ * T_ref_;
      sweep_linear_torque();
    }
    read_compliance();
    check_torque_balance();
    if (has_generator_) read_neutral_curve();
    read_phi0_engaged();
    out_.torque_unit = torque_;
    out_.torque_with_generator = inc_ * (1 / T_ref_);
    out_.generator = gen_;
    read_hoop_stress();
    read_load_cases();
    keep_for_contact();
    return std::move(out_);
  }

private:
  Eigen::MatrixXd zeros() const { return Eigen::MatrixXd::Zero(static_cast<Eigen::Index>(nn_), 3); }

  /// What the loaded contact reads: the stations with their band's responses, the bands', the clamp.
  void keep_for_contact() {
    out_.clamped = clamped_;
    if (stations_) {
      out_.stations = *stations_;
      out_.station_band = {stations_->S, Ur_, Ut_};
    }
  }

  /// The requested bands' spatial vectors S_i = ∫ N_i r ds (InputError for a band no edge lies in).
  void set_band_loads() {
    for (const SurfaceBand& b : request_.bands) {
      const auto edges = band_edges(sec_, b);
      if (edges.empty())
        throw InputError("no edge of the flexspline's section lies in the band z = " + std::to_string(b.z_lo_m * 1e3) +
                         " .. " + std::to_string(b.z_hi_m * 1e3) + " mm of its surface; refine [mesh] size_mm");
      BandResponse r;
      r.S = band_vector(sec_, edges);
      r.Ur.assign(N_ + 1, {});
      r.Ut.assign(N_ + 1, {});
      out_.bands.push_back(std::move(r));
    }
  }

  /// Harmonic n is solved when a load case has it, or a band is asked for (the odd ones only when asked).
  bool solve_harmonic_n(int n) const {
    return norm_[n] > kNoLoad * max_norm_ || (!request_.bands.empty() && (n % 2 == 0 || request_.odd_harmonics));
  }

  /// Supports: the clamp, and the axis conditions.
  void set_supports() {
    clamped_.assign(nn_, false);
    axis_ = axis_nodes(sec_);
    for (const auto& e : sec_.edges)
      if (e.marker == kSurfaceClamped)
        for (int v : e.nodes) clamped_[v] = true;
    fixed_.assign(3 * nn_, false);
    for (std::size_t i = 0; i < nn_; ++i) fixed_[3 * i] = fixed_[3 * i + 1] = fixed_[3 * i + 2] = clamped_[i];
  }

  /// Loads: unit torque (N·m) on the rim's outer surface over the engagement zones or all round (the plain tube: its
  /// open end).
  void set_torque_load() {
    const bool all_round = plain_tube_ || c_.load.torque_loading == TorqueLoading::Uniform;
    const int marker = plain_tube_ ? kSurfaceOpenEnd : kSurfaceRimOuter;
    const auto edges = select_edges(sec_, marker);
    if (edges.empty()) throw InputError("no boundary of the section carries the torque; check the flexspline keys");
    const double h = c_.load.engagement_half_angle_rad;
    std::vector<Window> windows = {{0.0, 2 * kPi, 1.0}};
    if (!all_round) windows = {{-h, h, 1.0}, {kPi - h, kPi + h, 1.0}};
    torque_terms_.push_back(unit_moment_term(sec_, edges, std::move(windows)));
  }

  /// The generator's stations on the band's inner wall and, for the force models, the unit generator (forces of
  /// total weight 1 N per unit weight); for the contact models the band's unit turn moment.
  void set_generator_loads() {
    auto in_band = [&](const Eigen::Vector2d& x) {
      return std::abs(x[1] - z_wg_) <= 0.5 * c_.wave_generator->band_width_m;
    };
    const auto edges = select_edges(sec_, kSurfaceInner, in_band);
    if (edges.empty())
      throw InputError("wave_generator: no inner wall in the generator's band at z = " + std::to_string(z_wg_ * 1e3) +
                       " mm; check wave_generator.axial_position_mm / band_width_mm");
    const Eigen::MatrixXd unit =
        edge_integral(sec_, edges, [](const Eigen::Vector2d&) { return Eigen::Vector3d(1, 0, 0); });
    stations_ = harmonic_stations(c_, unit.col(0), N_);
    if (stations_->unilateral) {
      // A unit moment about z of tangential traction ∝ r·e_θ on the band (harmonic 0): its work-conjugate displacement
      // is the band's mean turn (as the tet10 path's band_turn_load).
      const LoadTerm t = unit_moment_term(sec_, edges, {{0.0, 2 * kPi, 1.0}});
      Eigen::MatrixXd sym0 = zeros();
      turn_load_anti0_ = sym0;
      harmonic_loads({t}, 0, sym0, turn_load_anti0_);
    } else {
      const double area = 2 * kPatchHalfAngle * unit.col(0).sum();  // Σ_i ∫ N_i r ds = ∫ r ds
      for (const auto& force : generator_forces(*c_.wave_generator)) {
        LoadTerm t;
        t.windows = {{force.angle_rad - kPatchHalfAngle, force.angle_rad + kPatchHalfAngle, force.weight / area}};
        t.spatial = unit;
        gen_terms_.push_back(t);
      }
    }
  }

  /// Per harmonic: loads, then (when loaded) numbering, assembly, factor, solve of the columns torque sym, torque
  /// anti, generator forces sym, anti, and the two station vectors E_r, E_θ (HarmonicStations).
  void solve_harmonics() {
    for (auto* h : {&torque_, &force_gen_}) {
      h->sym.assign(N_ + 1, {});
      h->anti.assign(N_ + 1, {});
    }
    Ur_.resize(N_ + 1);
    Ut_.resize(N_ + 1);
    expand_loads();
    Stopwatch solve_clock;
    poly_ = element_polynomials(sec_, c_.material);
    for (int n = 0; n <= N_; ++n) {
      if (!solve_harmonic_n(n)) continue;
      const CholmodFactor& factor = factor_harmonic(n);
      solve_loads(n, numbering_[std::min(n, 2)]->dofs, factor);
    }
    fs_.timings.solve_s = solve_clock.lap();
    progress("fourier: " + std::to_string(out_.harmonics.size()) + " harmonics solved, " +
             std::to_string(fs_.timings.factor.factor_gflop) + " GF, " + std::to_string(fs_.timings.solve_s) +
             " s (assembly " + std::to_string(fs_.timings.assemble_s) + " s, factor " +
             std::to_string(fs_.timings.factor.analyse_s + fs_.timings.factor.factor_s) + " s)");
  }

  /// The generalised loads of every harmonic and each harmonic's largest (the stations' included).
  void expand_loads() {
    loads_.resize(N_ + 1);
    norm_.assign(N_ + 1, 0.0);
    max_norm_ = 0;
    for (int n = 0; n <= N_; ++n) {
      for (auto& m : loads_[n]) m = zeros();
      harmonic_loads(torque_terms_, n, loads_[n][0], loads_[n][1]);
      harmonic_loads(gen_terms_, n, loads_[n][2], loads_[n][3]);
      for (const auto& m : loads_[n]) norm_[n] = std::max(norm_[n], m.cwiseAbs().maxCoeff());
      if (stations_) norm_[n] = std::max(norm_[n], stations_->load_norm(n));
      max_norm_ = std::max(max_norm_, norm_[n]);
    }
  }

  /// Harmonic n's matrix on its numbering (assembled at the numbering's first harmonic), factorised.
  const CholmodFactor& factor_harmonic(int n) {
    Stopwatch hc;
    auto& g = numbering_[std::min(n, 2)];
    if (!g) g = assemble_polynomial(sec_, poly_, number_dofs(nn_, n, fixed_, axis_));
    const HarmonicDofs& d = g->dofs;
    const SymmetricCsc K = g->at(n);
    fs_.timings.assemble_s += hc.lap();
    auto& analysed = factors_[std::min(n, 2)];
    const bool fresh = !analysed;
    if (fresh) analysed = std::make_unique<CholmodFactor>(K, d.node_of_eq);
    else analysed->refactorise(K);
    record_factor(n, d, K, *analysed, fresh);
    return *analysed;
  }

  /// Harmonic n's statistics, and its part of the factor's timings.
  void record_factor(int n, const HarmonicDofs& d, const SymmetricCsc& K, const CholmodFactor& factor, bool fresh) {
    HarmonicStats st;
    st.n = n;
    st.equations = d.n_eq;
    st.factor_nnz = factor.stats().factor_nnz;
    st.factor_gflop = factor.stats().factor_gflop;
    const double analyse_s = fresh ? factor.stats().analyse_s : 0.0;
    st.factor_s = analyse_s + factor.stats().factor_s;
    st.load_norm = norm_[n];
    fs_.timings.factor.equations = std::max(fs_.timings.factor.equations, d.n_eq);
    fs_.timings.factor.matrix_nnz += static_cast<std::int64_t>(K.nnz());
    fs_.timings.factor.factor_nnz += st.factor_nnz;
    fs_.timings.factor.factor_gflop += st.factor_gflop;
    fs_.timings.factor.analyse_s += analyse_s;
    fs_.timings.factor.factor_s += factor.stats().factor_s;
    fs_.timings.factor.ordering = factor.stats().ordering;
    out_.harmonics.push_back(st);
  }

  /// Harmonic n's amplitudes of every load column, one solve.
  void solve_loads(int n, const HarmonicDofs& d, const CholmodFactor& factor) {
    const bool turn = n == 0 && turn_load_anti0_.size() != 0;
    const int cols = stations_ ? (turn ? 7 : 6) : 4;
    const Eigen::Index bands = static_cast<Eigen::Index>(out_.bands.size());
    Eigen::MatrixXd B(d.n_eq, cols + 2 * bands);
    for (int col = 0; col < 4; ++col) B.col(col) = to_equations(d, loads_[n][col]);
    if (stations_) {
      B.col(4) = to_equations(d, stations_->unit(0));
      B.col(5) = to_equations(d, stations_->unit(1));
    }
    if (turn) B.col(6) = to_equations(d, turn_load_anti0_);
    B.rightCols(2 * bands) = band_load_columns(d, out_.bands, static_cast<Eigen::Index>(nn_));
    const Eigen::MatrixXd X = factor.solve(B);
    const Eigen::MatrixXd zero = zeros();
    Eigen::MatrixXd* targets[7] = {&torque_.sym[n], &torque_.anti[n], &force_gen_.sym[n], &force_gen_.anti[n],
                                   &Ur_[n],         &Ut_[n],          &turn_anti0_};
    for (int col = 0; col < cols; ++col) *targets[col] = to_nodes(d, X.col(col), zero);
    store_band_responses(out_.bands, n, d, X, cols);
  }

  /// Internal forces K·u of harmonic n (0 or 1) of one family's amplitudes.
  Eigen::MatrixXd internal(int n, const Eigen::MatrixXd& U) const {
    Eigen::MatrixXd R = zeros();
    if (U.size() == 0) return R;
    for (std::size_t e = 0; e < sec_.triangles.size(); ++e) {
      const auto& t = sec_.triangles[e];
      Eigen::Matrix<double, 18, 1> ue;
      for (int a = 0; a < 6; ++a) ue.segment<3>(3 * a) = U.row(t[a]).transpose();
      const Eigen::Matrix<double, 18, 1> fe = poly_[e].at(n) * ue;
      for (int a = 0; a < 6; ++a) R.row(t[a]) += fe.segment<3>(3 * a).transpose();
    }
    return R;
  }

  /// φ₀: the rigid rotation of the reading ring (rim neutral circle at mid-width, or the plain tube's end face).
  void set_reading_ring() {
    fs_.reading_radius_m = neutral_radius(f_);
    fs_.reading_z_m = plain_tube_ ? f_.length_m : f_.length_m - 0.5 * f_.rim_width_m;
    if (plain_tube_) {
      std::vector<bool> seen(nn_, false);
      for (const auto* e : select_edges(sec_, kSurfaceOpenEnd))
        for (int v : e->nodes)
          if (!seen[v]) {
            seen[v] = true;
            ring_probes_.emplace_back(probe_node(v), sec_.nodes(v, 0));
          }
    } else {
      ring_probes_.emplace_back(probe_at(sec_, {fs_.reading_radius_m, fs_.reading_z_m}), fs_.reading_radius_m);
    }
  }

  /// The rigid rotation about z of the reading ring in field u.
  double rotation(const HarmonicField& u) const {
    RowMatrixX3d P(ring_probes_.size() * kRingSamples, 3), D(ring_probes_.size() * kRingSamples, 3);
    Eigen::Index row = 0;
    for (const auto& [p, r] : ring_probes_)
      for (int k = 0; k < kRingSamples; ++k, ++row) {
        const double t = 2 * kPi * k / kRingSamples;
        P.row(row) << r * std::cos(t), r * std::sin(t), 0.0;
        D.row(row) = to_cartesian(displacement_at(u, p, t), t).transpose();
      }
    return rigid_rotation_z(P, D);
  }

  /// The torque, and φ₀ of the body wall's torsion theory and of the cup's.
  void read_torsion_theory() {
    const double G = c_.material.shear_modulus_Pa();
    const double ri = f_.inner_radius_m, ro = f_.inner_radius_m + f_.wall_thickness_m;
    const double J = kPi / 2 * (std::pow(ro, 4) - std::pow(ri, 4));
    const double body_start = f_.shape == FlexsplineShape::Cup ? f_.diaphragm_thickness_m : 0.0;
    fs_.torque_Nm = T_;
    fs_.checks.phi0_theory_rad = T_ * (fs_.reading_z_m - body_start) / (G * J);
    fs_.checks.phi0_theory_cup =
        cup_torsion_theory(f_, rim_outer_radius(f_, c_.gear), c_.material, T_, fs_.reading_z_m);
  }

  /// Radial displacement of the neutral circle at the rim mid-width at θ, mean of θ and θ + π (as the tet10 path).
  double rim_w(const HarmonicField& u, double t) const {
    return 0.5 * (displacement_at(u, mid_, t)[0] + displacement_at(u, mid_, t + kPi)[0]);
  }

  /// The field of station forces p (one per pair).
  HarmonicField station_field(const Eigen::VectorXd& p) const { return stations_->field(p, Ur_, Ut_); }

  /// Moment about z of station forces p on the flexspline.
  double station_moment_z(const Eigen::VectorXd& p) const {
    Eigen::MatrixXd ls = zeros(), la = ls;
    stations_->loads(p, 0, ls, la);
    return moment_z(sec_, la);
  }

  /// The generator's case gen and the torque's increment inc with the generator in place (its support: the
  /// generator's forces on the flexspline in that increment), by the model's contact or its given forces.
  void read_generator() {
    mid_ = probe_at(sec_, {fs_.reading_radius_m, z_mid_});
    const auto& w = *c_.wave_generator;
    const HarmonicStations& hs = *stations_;
    GeneratorReadout gr;
    gr.model = model_name(w.model);
    gr.unilateral = hs.unilateral;
    gr.station_angle_rad = hs.angle_rad;
    C_ = hs.influence(Ur_, Ut_);
    u0_torque_ = hs.project(torque_);
    if (hs.unilateral) solve_generator_contact(gr);
    else scale_generator_forces(gr);
    inc_ = station_field(p_support_inc_);
    inc_ += torque_ * T_ref_;
    if (!hs.unilateral) sweep_linear_torque();
    read_generator_resultants(gr);
    fs_.generator = gr;
  }

  /// Without contact the torque's rotation is linear in the torque: the sweep repeats C_τ.
  void sweep_linear_torque() {
    for (const double k : kSweep) fs_.torque_sweep.emplace_back(k * T_ref_, rotation(inc_) / T_ref_);
  }

  /// Contact of the generator alone, with T_ref and with the sweep's torques: each a small problem on C.
  void solve_generator_contact(GeneratorReadout& gr) {
    const auto& w = *c_.wave_generator;
    const HarmonicStations& hs = *stations_;
    Eigen::VectorXd obstacle = hs.obstacle_m;
    if (std::holds_alternative<Rollers>(w.model)) {
      // Set the rollers out so the major axis reaches w0 (all four touch: linear in the standoff).
      obstacle *= rollers_setout(w, rim_w(station_field(bilateral_support(C_, obstacle).force_N), 0.0));
    }
    gr.obstacle_m = obstacle;
    const GeneratorContactModel model = generator_contact_model();
    const double band_turn_per_T = (turn_load_anti0_.array() * torque_.anti[0].array()).sum();
    auto contact = [&](double torque_Nm) {
      return generator_contact(C_, obstacle - torque_Nm * u0_torque_, torque_Nm * band_turn_per_T, model);
    };
    const StationForces s_gen = contact(0.0);
    const StationForces s_comb = contact(T_ref_);
    gr.contact_iterations = s_gen.iterations;
    p_gen_ = s_gen.force_N;
    gen_ = station_field(p_gen_);
    p_support_inc_ = s_comb.force_N - s_gen.force_N;
    const double rot_gen = rotation(gen_);
    for (const double k : kSweep) {
      const double Tk = k * T_ref_;
      HarmonicField u = station_field(contact(Tk).force_N);
      u += torque_ * Tk;
      fs_.torque_sweep.emplace_back(Tk, (rotation(u) - rot_gen) / Tk);
    }
    gr.force_wg_N.assign(s_gen.force_N.data(), s_gen.force_N.data() + s_gen.force_N.size());
    gr.force_comb_N.assign(s_comb.force_N.data(), s_comb.force_N.data() + s_comb.force_N.size());
    const double touching_gap = kTouchingGap * *w.radial_deformation_m;
    gr.zones_wg_deg = contact_zones_deg(gr.station_angle_rad, touching(s_gen, touching_gap), hs.half_width_rad);
    gr.zones_comb_deg = contact_zones_deg(gr.station_angle_rad, touching(s_comb, touching_gap), hs.half_width_rad);
    gr.min_contact_force_N = s_gen.force_N.minCoeff();
  }

  /// As the tet10 path: the wave stays with the generator (the gaps ignore the band's turn), and the bearing in
  /// series (a cam's).
  GeneratorContactModel generator_contact_model() const {
    const auto& w = *c_.wave_generator;
    const HarmonicStations& hs = *stations_;
    GeneratorContactModel model;
    const Eigen::Index pairs = C_.rows();
    model.turn_gap_m_per_rad.resize(pairs);
    for (Eigen::Index j = 0; j < pairs; ++j)
      model.turn_gap_m_per_rad[j] = station_moment_z(Eigen::VectorXd::Unit(pairs, j));
    HarmonicField turn_field;
    turn_field.sym.assign(N_ + 1, {});
    turn_field.anti.assign(N_ + 1, {});
    turn_field.sym[0] = zeros();
    turn_field.anti[0] = turn_anti0_;
    model.band_turn_rad_per_N = hs.project(turn_field);
    if (cam_of(w) && w.bearing)
      model.approach_m = bearing_pair_approach(*w.bearing, hs.half_width_rad);
    return model;
  }

  /// Force idealisation: scale to w0 (or force_N); the torque case with the band held radially at the stations.
  void scale_generator_forces(GeneratorReadout& gr) {
    const auto& w = *c_.wave_generator;
    const double w_unit = rim_w(force_gen_, 0.0);
    if (!(w_unit > 0))
      throw InputError("wave_generator: the generator does not push the major axis outward (w = " +
                       std::to_string(w_unit) + " m per unit load); check the force angles");
    double total_at_end = 0;
    for (const auto& force : generator_forces(w))
      if (std::abs(std::remainder(force.angle_rad, 2 * kPi)) < kPi / 2) total_at_end += force.weight;
    const double scale =
        w.radial_deformation_m ? *w.radial_deformation_m / w_unit : w.force_N / std::max(total_at_end, 1e-300);
    fs_.generator_force_N = scale * point_force_share(w.model);
    gen_ = force_gen_ * scale;
    for (int n = 0; n <= N_; ++n) {
      loads_[n][2] *= scale;
      loads_[n][3] *= scale;
    }
    const StationForces s_T = bilateral_support(C_, -T_ref_ * u0_torque_);
    p_support_inc_ = s_T.force_N;
    gr.force_comb_N.assign(s_T.force_N.data(), s_T.force_N.data() + s_T.force_N.size());
    double fmin = 1e300;
    for (const auto& force : generator_forces(w)) {
      fmin = std::min(fmin, force.weight * scale);
      const double a = std::remainder(force.angle_rad, 2 * kPi) * 180 / kPi, h = kPatchHalfAngle * 180 / kPi;
      gr.zones_wg_deg.emplace_back(a - h, a + h);
    }
    gr.min_contact_force_N = fmin;
  }

  /// The generator's loads on the flexspline of harmonics 0 and 1 (resultants, total radial force), the torque it
  /// takes, and the rim's radial displacement at the axes.
  void read_generator_resultants(GeneratorReadout& gr) {
    const HarmonicStations& hs = *stations_;
    std::array<Eigen::MatrixXd, 2> Fs, Fa;
    for (int n = 0; n <= 1; ++n) {
      Fs[n] = Fa[n] = zeros();
      if (n > N_) continue;
      if (hs.unilateral) hs.loads(p_gen_, n, Fs[n], Fa[n]);
      else {
        Fs[n] = loads_[n][2];
        Fa[n] = loads_[n][3];
      }
    }
    gr.total_radial_force_N = Fs[0].col(0).sum();  // Σ_i ∫∫ t_r N_i r dθ ds = ∫ t_r dA
    gr.reaction_torque_Nm = station_moment_z(p_support_inc_) * (T_ / T_ref_);
    gr.w_major_m = rim_w(gen_, 0.0);
    gr.w_minor_m = rim_w(gen_, kPi / 2);
    fs_.generator_w0_m = gr.w_major_m;
    const Eigen::VectorXd r = sec_.nodes.col(0), z = sec_.nodes.col(1);
    const Eigen::MatrixXd &Fs0 = Fs[0], &Fs1 = Fs[1], &Fa1 = Fa[1];
    const double Fx = (Fs1.col(0) - Fs1.col(1)).sum(), Fy = (Fa1.col(0) - Fa1.col(1)).sum(), Fz = Fs0.col(2).sum();
    fs_.checks.generator_net_force = Eigen::Vector3d(Fx, Fy, Fz);
    fs_.checks.generator_net_moment = Eigen::Vector3d(r.dot(Fa1.col(2)) - z.dot(Fa1.col(0) - Fa1.col(1)),
                                                      z.dot(Fs1.col(0) - Fs1.col(1)) - r.dot(Fs1.col(2)), 0.0);
    fs_.checks.generator_rotation_rad = rotation(gen_);
  }

  /// φ₀ and C_τ: the rotation the torque adds with the generator in place; the torque case at T.
  void read_compliance() {
    fs_.compliance_rad_per_Nm = rotation(inc_) / T_ref_;
    fs_.phi0_rad = fs_.compliance_rad_per_Nm * T_;
    torque_case_ = inc_ * (T_ / T_ref_);
  }

  /// Torque balance of the torque case: applied moment vs the clamp's reaction plus the generator's.
  void check_torque_balance() {
    fs_.checks.applied_torque_Nm = moment_z(sec_, loads_[0][1]) * T_;
    Eigen::MatrixXd support = zeros(), support_sym = support;
    if (stations_) stations_->loads(p_support_inc_ * (T_ / T_ref_), 0, support_sym, support);
    Eigen::MatrixXd R = internal(0, torque_case_.anti[0]) - loads_[0][1] * T_ - support;
    for (std::size_t i = 0; i < nn_; ++i)
      if (!clamped_[i]) R.row(static_cast<Eigen::Index>(i)).setZero();
    fs_.checks.reaction_torque_Nm = moment_z(sec_, R) + moment_z(sec_, support);
  }

  /// The generator's case with the torque case added.
  HarmonicField combined() const {
    HarmonicField comb = gen_;
    comb += torque_case_;
    return comb;
  }

  /// The neutral curve at the rim's mid-width, of the generator alone and with the torque.
  void read_neutral_curve() {
    NeutralCurveSamples nc;
    nc.radius_m = fs_.reading_radius_m;
    nc.z_m = z_mid_;
    for (int k = 0; k < kRingSamples; ++k) nc.phi_rad.push_back(2 * kPi * k / kRingSamples);
    ring_curve(gen_, mid_, nc.radius_m, nc.w_wg_m, nc.v_wg_m, nc.mu_wg_rad);
    ring_curve(combined(), mid_, nc.radius_m, nc.w_comb_m, nc.v_comb_m, nc.mu_comb_rad);
    fs_.neutral_curve = nc;
  }

  /// φ₀ over the engagement zones: the mean tangential displacement of the torque case on the neutral circle there.
  void read_phi0_engaged() {
    if (plain_tube_) {
      fs_.phi0_engaged_rad = fs_.phi0_rad;
      return;
    }
    const double half = c_.load.torque_loading == TorqueLoading::Uniform ? kPi : c_.load.engagement_half_angle_rad;
    const Probe ring = probe_at(sec_, {fs_.reading_radius_m, fs_.reading_z_m});
    double sum = 0;
    int count = 0;
    for (int k = 0; k < kRingSamples; ++k) {
      const double t = 2 * kPi * k / kRingSamples;
      if (std::abs(std::remainder(t, 2 * kPi)) <= half + 1e-9 ||
          std::abs(std::remainder(t - kPi, 2 * kPi)) <= half + 1e-9) {
        sum += displacement_at(torque_case_, ring, t)[1];
        ++count;
      }
    }
    fs_.phi0_engaged_rad = sum / count / fs_.reading_radius_m;
  }

  /// Stresses: nodal amplitudes; hoop profile and extremes of the generator case (else the torque case).
  void read_hoop_stress() {
    std::vector<Eigen::MatrixXd> hs, ha;
    nodal_stress(sec_, c_.material, has_generator_ ? gen_ : torque_case_, hs, ha);
    read_hoop_profile(hs, ha);
    read_nominal_hoop();
    read_hoop_extremes(hs, ha);
  }

  /// The hoop stress around the wall's inner and outer surface (a hair inside), in the generator's plane (else the
  /// reading ring's).
  void read_hoop_profile(const std::vector<Eigen::MatrixXd>& hs, const std::vector<Eigen::MatrixXd>& ha) {
    const double z = has_generator_ ? z_wg_ : fs_.reading_z_m;
    const double inset = 1e-3 * f_.inner_radius_m;
    fs_.hoop.profile_z_m = z;
    fs_.hoop.inner_radius_m = f_.inner_radius_m + inset;
    fs_.hoop.outer_radius_m =
        (f_.teeth == TeethModel::None ? f_.inner_radius_m + f_.wall_thickness_m : rim_outer_radius(f_, c_.gear)) -
        inset;
    const Probe pin = probe_at(sec_, {fs_.hoop.inner_radius_m, z}), pout = probe_at(sec_, {fs_.hoop.outer_radius_m, z});
    for (int k = 0; k < kRingSamples; ++k) {
      const double t = 2 * kPi * k / kRingSamples;
      const Trig trig(t, hs.size());
      fs_.hoop.inner_Pa.push_back(hoop_at(hs, ha, pin, trig));
      fs_.hoop.outer_Pa.push_back(hoop_at(hs, ha, pout, trig));
    }
  }

  /// The profile's bending and membrane parts at the nominal angle, and ring theory's bending there.
  void read_nominal_hoop() {
    const int k = static_cast<int>(std::lround(fs_.hoop.nominal_angle_deg));
    fs_.hoop.nominal_bending_Pa = 0.5 * (fs_.hoop.outer_Pa[k] - fs_.hoop.inner_Pa[k]);
    fs_.hoop.nominal_membrane_Pa = 0.5 * (fs_.hoop.outer_Pa[k] + fs_.hoop.inner_Pa[k]);
    if (has_generator_) {
      const double ri = f_.inner_radius_m;
      const double t_wall = fs_.hoop.outer_radius_m + (fs_.hoop.inner_radius_m - ri) - ri;  // the profile's wall
      fs_.hoop.ring_theory_bending_Pa =
          ring_theory_bending_stress(*c_.wave_generator, c_.material.youngs_modulus_Pa, ri + 0.5 * t_wall, t_wall,
                                     fs_.generator->w_major_m, fs_.hoop.nominal_angle_deg * kPi / 180);
    }
  }

  /// The largest tensile and compressive hoop stress over the nodes of the open end's half of the length.
  void read_hoop_extremes(const std::vector<Eigen::MatrixXd>& hs, const std::vector<Eigen::MatrixXd>& ha) {
    fs_.hoop.max_tensile_Pa = -1e300;
    fs_.hoop.max_compressive_Pa = 1e300;
    const int angles = 4 * kRingSamples;  // 0.25°: finer than any grid the extremes could be read on
    std::vector<Trig> trigs;
    for (int k = 0; k < angles; ++k) trigs.emplace_back(2 * kPi * k / angles, hs.size());
    for (std::size_t i = 0; i < nn_; ++i) {
      if (sec_.nodes(static_cast<Eigen::Index>(i), 1) < 0.5 * f_.length_m) continue;
      const Probe p = probe_node(static_cast<int>(i));
      for (int k = 0; k < angles; ++k) {
        const double st = hoop_at(hs, ha, p, trigs[k]);
        if (st > fs_.hoop.max_tensile_Pa) {
          fs_.hoop.max_tensile_Pa = st;
          fs_.hoop.max_tensile_angle_deg = 360.0 * k / angles;
          fs_.hoop.max_tensile_z_m = sec_.nodes(static_cast<Eigen::Index>(i), 1);
        }
        if (st < fs_.hoop.max_compressive_Pa) {
          fs_.hoop.max_compressive_Pa = st;
          fs_.hoop.max_compressive_angle_deg = 360.0 * k / angles;
          fs_.hoop.max_compressive_z_m = sec_.nodes(static_cast<Eigen::Index>(i), 1);
        }
      }
    }
  }

  /// Load cases (as the tet10 path: generator, torque, generator + torque): their names and rotations; their fields
  /// on a grid are revolved_load_cases'.
  void read_load_cases() {
    if (has_generator_) fs_.cases.push_back({"generator", {}, {}, rotation(gen_)});
    fs_.cases.push_back({"torque", {}, {}, rotation(torque_case_)});
    if (has_generator_) fs_.cases.push_back({"generator_torque", {}, {}, rotation(combined())});
  }

  const FlexsplineModel& c_;
  const FlexsplineParams& f_;
  const int N_;  ///< the harmonics kept, 0..N
  const BandRequest& request_;
  const bool plain_tube_, has_generator_;
  const double z_wg_;   ///< the generator band's mid-plane
  const double z_mid_;  ///< the rim's mid-width
  const double T_, T_ref_;  ///< compliance is read at T (or 1 N·m without torque)
  FourierSolution out_;
  const SectionMesh& sec_ = out_.section;
  FlexsplineSolution& fs_ = out_.figures;
  std::size_t nn_ = 0;

  std::vector<bool> clamped_, axis_, fixed_;  ///< per node; fixed_: per dof
  std::vector<LoadTerm> torque_terms_, gen_terms_;
  std::optional<HarmonicStations> stations_;
  Eigen::MatrixXd turn_load_anti0_;  ///< the band's unit turn moment, harmonic 0 (contact models)
  std::vector<std::array<Eigen::MatrixXd, 4>> loads_;  ///< per harmonic: torque sym, anti, generator forces sym, anti
  std::vector<double> norm_;
  double max_norm_ = 0;

  std::vector<ElementPolynomial> poly_;
  std::array<std::optional<GlobalPolynomial>, 3> numbering_;  ///< n = 0, n = 1, n ≥ 2 (the axis conditions)
  // One analysis (ordering, supernodes) per numbering: every n ≥ 2 has the same pattern, so its factor is only
  // refactorised numerically.
  std::array<std::unique_ptr<CholmodFactor>, 3> factors_;
  HarmonicField torque_, force_gen_;  ///< unit torque; the force models' unit generator
  std::vector<Eigen::MatrixXd> Ur_, Ut_;  ///< per harmonic: K_n⁻¹E_r, K_n⁻¹E_θ (HarmonicStations)
  Eigen::MatrixXd turn_anti0_;  ///< amplitudes of the band's unit turn moment (harmonic 0, antisymmetric family)

  std::vector<std::pair<Probe, double>> ring_probes_;  ///< (probe, radius)
  Probe mid_;  ///< the neutral circle at the rim's mid-width (with a generator)
  Eigen::MatrixXd C_;           ///< the stations' influence matrix
  Eigen::VectorXd u0_torque_;   ///< per pair, unit torque
  HarmonicField gen_, inc_, torque_case_;  ///< the generator alone; what T_ref adds with it in place; inc_ at T
  Eigen::VectorXd p_support_inc_;  ///< station forces of inc_'s support (empty: none)
  Eigen::VectorXd p_gen_;          ///< station forces of the generator case (contact models)
};

}  // namespace

namespace {

/// One field's displacement and stress at every node of revolve_section(s, sectors)'s grid, the series summed at all
/// stations at once (SeriesTerms::at).
LoadCaseSolution revolved_case(const SectionMesh& s, const Material& m, const HarmonicField& field, int sectors) {
  const Eigen::Index ns = static_cast<Eigen::Index>(s.n_nodes());
  std::vector<double> theta;
  for (int k = 0; k < 2 * sectors; ++k) theta.push_back(kPi * k / sectors);
  const Eigen::Index gn = static_cast<Eigen::Index>(theta.size()) * ns;
  std::vector<Eigen::MatrixXd> ss, sa;
  nodal_stress(s, m, field, ss, sa);
  const Eigen::MatrixXd values = series_terms(ns, field, ss, sa).at(theta);
  LoadCaseSolution r;
  r.u.resize(3 * gn);
  r.stress.resize(gn, 6);
  for (Eigen::Index k = 0; k < values.cols(); ++k)
    for (Eigen::Index i = 0; i < ns; ++i) {
      const Eigen::Matrix<double, 9, 1> v = values.col(k).segment<9>(9 * i);
      r.u.segment<3>(3 * (k * ns + i)) = to_cartesian(v.head<3>(), theta[static_cast<std::size_t>(k)]);
      r.stress.row(k * ns + i) = cartesian_stress(v.tail<6>(), theta[static_cast<std::size_t>(k)]);
    }
  return r;
}

}  // namespace

std::vector<LoadCaseSolution> revolved_load_cases(const FourierSolution& s, const Material& m, int sectors) {
  std::vector<LoadCaseSolution> cases = s.figures.cases;
  for (LoadCaseSolution& lc : cases) {
    // As the analysis builds them: the torque case is what the case's torque adds with the generator in place.
    HarmonicField field = s.torque_with_generator * s.figures.torque_Nm;
    if (lc.name == "generator") field = s.generator;
    if (lc.name == "generator_torque") field += s.generator;
    LoadCaseSolution r = revolved_case(s.section, m, field, sectors);
    lc.u = std::move(r.u);
    lc.stress = std::move(r.stress);
  }
  return cases;
}

FourierSolution analyse_flexspline_fourier(const FlexsplineModel& c, const BandRequest& request) {
  Stopwatch clock;
  SectionMesh section = case_section(c);
  const double section_s = clock.lap();
  FourierSolution s = analyse_section_fourier(c, std::move(section), request);
  s.section_s = section_s;
  return s;
}

FourierSolution analyse_section_fourier(const FlexsplineModel& c, SectionMesh section, const BandRequest& request) {
  return SectionAnalyser(c, std::move(section), request).run();
}

}  // namespace sw
