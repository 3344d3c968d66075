// The signatures each kind's residual is tested for, and the nuisance columns of every model of a kind.
#include <cmath>
#include <stdexcept>

#include "reconcile/effects.hpp"

namespace sw::reconcile {

namespace {

using Vec = Eigen::VectorXd;
using Mat = Eigen::MatrixXd;
using Columns = std::function<Mat(const Experiment&)>;
using Where = std::function<Vec(const Experiment&)>;

Mat col(const Vec& v) { return v; }
Mat none(const Experiment& e) { return Mat(e.n, 0); }
Vec time_of(const Experiment& e) { return e.time; }

SignatureSpec signature(const std::string& name, const std::string& domain, const std::string& what, Columns basis,
                        Columns condition, std::vector<std::string> triggers, Where where, const std::string& where_unit,
                        bool periodic = false) {
  return {name, domain, what, std::move(basis), std::move(condition), std::move(triggers), std::move(where),
          where_unit, periodic};
}


std::vector<SignatureSpec> dynamics_signatures() {
  return {
      signature("mesh_frequency_lines", "frequency",
                "a line at the mesh frequency f_m and its second harmonic in the meshing-force spectrum",
                [](const Experiment& e) { return mesh_lines(dynamics(e)); }, none, {"mesh_stiffness_variation"},
                time_of, "s"),
      signature("fluctuation_decay", "time",
                "the meshing-force fluctuations after the run-up and load steps decay at another rate or amplitude",
                [](const Experiment& e) { return Mat(dynamics(e).sensitivity.col(2)); }, none, {"damping"}, time_of,
                "s"),
      signature("speed_dependent_offset", "time (speed)",
                "a meshing-force offset that grows with speed (the mesh carries a drag torque besides the load)",
                [](const Experiment& e) { return Mat(dynamics(e).sensitivity.rightCols(2)); }, none, {"drag_torque"},
                time_of, "s")};
}

std::vector<SignatureSpec> torsion_signatures() {
  auto torque = [](const Experiment& e) { return torsion(e).torque_Nm; };
  auto linear = [](const Experiment& e) { return col(torsion(e).torque_Nm); };
  auto shape = [](const Experiment& e) {
    const TorsionExperiment& t = torsion(e);
    Mat m(e.n, 3);
    const double a = t.torque_amplitude_Nm;
    m.col(0) = soft_start_column(t.torque_Nm, 0.15 * a);
    m.col(1) = soft_start_column(t.torque_Nm, 0.3 * a);
    m.col(2) = soft_start_column(t.torque_Nm, 0.5 * a);
    return m;
  };
  auto branches = [](const Experiment& e) {
    const TorsionExperiment& t = torsion(e);
    Mat m(e.n, 2);
    m.col(0) = t.direction;
    m.col(1) = hysteresis_column(t, 0.1 * t.torque_amplitude_Nm);
    return m;
  };
  auto zero_crossing = [](const Experiment& e) {
    return col(lost_motion_column(torsion(e).torque_Nm, 0.01 * torsion(e).torque_amplitude_Nm));
  };
  return {
      signature("torque_linear", "torque", "residual proportional to torque (the drive is softer or stiffer than the "
                "baseline)", linear, none,
                {"series_compliance", "stiffness_nonlinearity#1", "stiffness_nonlinearity#2"}, torque, "N*m"),
      signature("torque_shape", "torque", "residual bends with torque beyond a straight line (soft start or play)",
                shape, linear, {"stiffness_nonlinearity#1", "stiffness_nonlinearity#2", "lost_motion"}, torque, "N*m"),
      signature("loading_unloading", "torque branch", "loading and unloading branches apart at equal torque",
                branches, linear, {"hysteresis#1", "hysteresis#2", "hysteresis#3"}, torque, "N*m"),
      signature("zero_crossing", "torque zero crossing", "twist jumps while the torque crosses zero", zero_crossing,
                linear, {"lost_motion", "stiffness_nonlinearity#1", "stiffness_nonlinearity#2"}, torque, "N*m"),
      signature("time_drift", "time",
                "slow drift of the residual in time (temperature, creep, sensor drift): no catalog effect",
                [](const Experiment& e) { return legendre_columns(e.time, 1, 2); }, none, {}, time_of, "s")};
}

/// A line of each order 1 .. kMaxHarmonicOrder in an angle of the experiment (member `angle` of the kind's data K).
template <class K>
std::vector<SignatureSpec> angle_order_signatures(const std::string& prefix, const std::string& domain,
                                                  const std::string& effect, Vec K::*angle) {
  std::vector<SignatureSpec> v;
  for (int k = 1; k <= kMaxHarmonicOrder; ++k)
    v.push_back(signature(
        prefix + "_order_" + std::to_string(k), domain,
        "order " + std::to_string(k) + " line in the residual's " + domain + " spectrum",
        [k, angle](const Experiment& e) { return harmonic_columns(as<K>(e).*angle, k); }, none,
        {effect + "#" + std::to_string(k)},
        [angle](const Experiment& e) { return Vec(((as<K>(e).*angle) * (180.0 / M_PI)).array()); }, "deg", true));
  return v;
}

std::vector<SignatureSpec> transmission_signatures() {
  auto v = angle_order_signatures("wg", "wave-generator angle", "wg_harmonic", &TransmissionExperiment::wg_angle_rad);
  auto o = angle_order_signatures("output", "output angle", "output_harmonic",
                                  &TransmissionExperiment::output_angle_rad);
  v.insert(v.end(), o.begin(), o.end());
  v.push_back(signature(
      "time_drift", "time",
      "slow drift of the transmission error in time beyond a constant ratio error: no catalog effect",
      [](const Experiment& e) { return legendre_columns(e.time, 2, 3); }, none, {}, time_of, "s"));
  return v;
}

std::vector<SignatureSpec> backlash_signatures() {
  auto v = angle_order_signatures("wg", "wave-generator angle", "wg_harmonic", &BacklashExperiment::wg_angle_rad);
  auto ones = [](const Experiment& e) { return col(Vec::Ones(e.n)); };
  v.push_back(signature("torque_dependence", "torque", "backlash changes with the applied torque",
                        [](const Experiment& e) { return col(as<BacklashExperiment>(e).torque_Nm); }, ones,
                        {"load_torsion"}, [](const Experiment& e) { return as<BacklashExperiment>(e).torque_Nm; },
                        "N*m"));
  v.push_back(signature("mean_offset", "all positions", "backlash offset from the basic model at every position", ones,
                        none, {"uniform_clearance", "load_torsion"},
                        [](const Experiment& e) { return Vec(as<BacklashExperiment>(e).wg_angle_rad * (180.0 / M_PI)); },
                        "deg", true));
  return v;
}

Mat nuisance(const Experiment& e, const TorsionExperiment&) { return Mat::Ones(e.n, 1); }
Mat nuisance(const Experiment& e, const TransmissionExperiment& t) {
  Mat m(e.n, 2);
  m.col(0).setOnes();
  m.col(1) = t.wg_angle_rad;
  return m;
}
Mat nuisance(const Experiment& e, const BacklashExperiment&) { return Mat(e.n, 0); }
Mat nuisance(const Experiment& e, const DynamicsExperiment&) { return Mat(e.n, 0); }

}  // namespace

const std::vector<SignatureSpec>& signature_catalog(Kind kind) {
  static const std::vector<SignatureSpec> torsion = torsion_signatures();
  static const std::vector<SignatureSpec> transmission = transmission_signatures();
  static const std::vector<SignatureSpec> backlash = backlash_signatures();
  static const std::vector<SignatureSpec> dynamics = dynamics_signatures();
  switch (kind) {
    case Kind::Torsion: return torsion;
    case Kind::Transmission: return transmission;
    case Kind::Backlash: return backlash;
    case Kind::Dynamics: return dynamics;
  }
  throw std::logic_error("signature_catalog: unknown kind");
}

Eigen::MatrixXd nuisance_columns(const Experiment& e) {
  return std::visit([&](const auto& d) { return nuisance(e, d); }, e.data);
}

}  // namespace sw::reconcile
