#include "fem/infinite_life.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <set>

#include "common/constants.hpp"
#include "common/error.hpp"
#include "common/first_crossing.hpp"

namespace sw {
namespace {

constexpr int kSamples = 360;                 // 1° steps over the revolution, as fem/fatigue.hpp's history
constexpr double kTorqueTolerance = 1e-4;     // bisection's relative width on the limit torque
constexpr int kScanSteps = 64;                // the scan for the first crossing before the bisection

/// The histories over one revolution of the section's boundary nodes (fatigue starts at a surface) outside the boss
/// and more than one wall from the clamp: the generator's field and the unit torque's, per node.
struct Histories {
  std::vector<int> node;
  std::vector<StressHistory> generator, torque_unit;
};

StressHistory history_of(const std::vector<Eigen::MatrixXd>& sym, const std::vector<Eigen::MatrixXd>& anti, int i,
                         const std::vector<std::vector<double>>& cos_nt, const std::vector<std::vector<double>>& sin_nt) {
  StressHistory h;
  for (auto& v : h) v.assign(kSamples, 0.0);
  for (std::size_t n = 0; n < sym.size(); ++n) {
    if (sym[n].size() == 0) continue;
    for (int c = 0; c < 6; ++c) {
      const double a = sym[n](i, c), b = anti[n](i, c);
      if (a == 0 && b == 0) continue;
      // σ_r, σ_z, σ_θ, τ_rz go as a·cos nθ + b·sin nθ; τ_rθ, τ_θz as a·sin nθ − b·cos nθ (fem/fourier_solver.hpp).
      for (int k = 0; k < kSamples; ++k)
        h[c][k] += c < 4 ? a * cos_nt[n][k] + b * sin_nt[n][k] : a * sin_nt[n][k] - b * cos_nt[n][k];
    }
  }
  return h;
}

std::vector<int> candidate_nodes(const FourierSolution& s, const FlexsplineModel& c) {
  const SectionMesh& sec = s.section;
  std::vector<bool> boss(sec.n_nodes(), false);
  for (std::size_t e = 0; e < sec.triangles.size(); ++e)
    if (sec.region[e] == 3)
      for (int a : sec.triangles[e]) boss[a] = true;
  const double wall = c.flexspline.shape == FlexsplineShape::Cup
                          ? std::max(c.flexspline.diaphragm_thickness_m, c.flexspline.wall_thickness_m)
                          : c.flexspline.wall_thickness_m;
  std::vector<Eigen::Vector2d> clamp;
  for (std::size_t i = 0; i < s.clamped.size() && i < sec.n_nodes(); ++i)
    if (s.clamped[i]) clamp.push_back(sec.nodes.row(static_cast<Eigen::Index>(i)).transpose());
  std::set<int> surface;
  for (const SectionEdge& e : sec.edges)
    for (int a : e.nodes) surface.insert(a);
  std::vector<int> out;
  for (int i : surface) {
    if (boss[i]) continue;
    const Eigen::Vector2d p = sec.nodes.row(i).transpose();
    if (std::any_of(clamp.begin(), clamp.end(), [&](const Eigen::Vector2d& q) { return (p - q).norm() < wall; }))
      continue;
    out.push_back(i);
  }
  return out;
}

Histories histories(const FourierSolution& s, const FlexsplineModel& c) {
  std::vector<Eigen::MatrixXd> gs, ga, ts, ta;
  fourier::nodal_stress(s.section, c.material, s.generator, gs, ga);
  fourier::nodal_stress(s.section, c.material, s.torque_with_generator, ts, ta);
  const std::size_t harmonics = std::max(gs.size(), ts.size());
  std::vector<std::vector<double>> cos_nt(harmonics, std::vector<double>(kSamples)), sin_nt = cos_nt;
  for (std::size_t n = 0; n < harmonics; ++n)
    for (int k = 0; k < kSamples; ++k) {
      cos_nt[n][k] = std::cos(static_cast<double>(n) * 2 * kPi * k / kSamples);
      sin_nt[n][k] = std::sin(static_cast<double>(n) * 2 * kPi * k / kSamples);
    }
  Histories h;
  h.node = candidate_nodes(s, c);
  for (int i : h.node) {
    h.generator.push_back(history_of(gs, ga, i, cos_nt, sin_nt));
    h.torque_unit.push_back(history_of(ts, ta, i, cos_nt, sin_nt));
  }
  return h;
}

std::string place_of(const FlexsplineModel& c, double z_m) {
  const FlexsplineParams& f = c.flexspline;
  if (z_m >= f.length_m - f.rim_width_m) return "rim";
  if (f.shape == FlexsplineShape::Cup && z_m <= f.diaphragm_thickness_m + f.fillet_radius_m) return "diaphragm";
  return "body wall";
}

struct Amplitudes {
  double alternating_von_mises_Pa = 0, mean_normal_sum_Pa = 0;
};

Amplitudes amplitudes(const StressHistory& h) {
  std::array<double, 6> a{}, m{};
  for (int c = 0; c < 6; ++c) {
    const auto [lo, hi] = std::minmax_element(h[c].begin(), h[c].end());
    a[c] = (*hi - *lo) / 2;
    m[c] = (*hi + *lo) / 2;
  }
  Amplitudes out;
  out.alternating_von_mises_Pa =
      std::sqrt(0.5 * ((a[0] - a[1]) * (a[0] - a[1]) + (a[1] - a[2]) * (a[1] - a[2]) + (a[2] - a[0]) * (a[2] - a[0])) +
                3 * (a[3] * a[3] + a[4] * a[4] + a[5] * a[5]));
  out.mean_normal_sum_Pa = m[0] + m[1] + m[2];
  return out;
}

double safety(const Amplitudes& a, double Se, double Su) {
  const double inverse = a.alternating_von_mises_Pa / Se + std::max(0.0, a.mean_normal_sum_Pa) / Su;
  return inverse > 0 ? 1 / inverse : std::numeric_limits<double>::infinity();
}

void require_fatigue_data(const Material& m) {
  if (!m.fatigue_limit_Pa || !m.ultimate_strength_Pa)
    throw InputError("the flexspline's fatigue needs material.fatigue_limit_MPa and material.ultimate_strength_MPa");
}

FatigueState worst(const Histories& h, const FourierSolution& s, const FlexsplineModel& c, double T) {
  const double Se = *c.material.fatigue_limit_Pa, Su = *c.material.ultimate_strength_Pa;
  FatigueState w;
  w.torque_Nm = T;
  w.safety_factor = std::numeric_limits<double>::infinity();
  StressHistory combined;
  for (std::size_t j = 0; j < h.node.size(); ++j) {
    for (int k = 0; k < 6; ++k) {
      combined[k] = h.generator[j][k];
      for (int q = 0; q < kSamples; ++q) combined[k][q] += T * h.torque_unit[j][k][q];
    }
    const Amplitudes a = amplitudes(combined);
    const double n = safety(a, Se, Su);
    if (n < w.safety_factor) {
      w.safety_factor = n;
      w.r_m = s.section.nodes(h.node[j], 0);
      w.z_m = s.section.nodes(h.node[j], 1);
      w.alternating_von_mises_Pa = a.alternating_von_mises_Pa;
      w.mean_normal_sum_Pa = a.mean_normal_sum_Pa;
    }
  }
  w.place = place_of(c, w.z_m);
  return w;
}

/// The largest von Mises stress of the combined history (generator + T × the unit torque's) over the revolution.
double peak_von_mises(const StressHistory& g, const StressHistory& t, double T) {
  double peak = 0;
  for (int q = 0; q < kSamples; ++q) {
    std::array<double, 6> x{};
    for (int k = 0; k < 6; ++k) x[k] = g[k][q] + T * t[k][q];
    const double v = 0.5 * ((x[0] - x[1]) * (x[0] - x[1]) + (x[1] - x[2]) * (x[1] - x[2]) +
                            (x[2] - x[0]) * (x[2] - x[0])) +
                     3 * (x[3] * x[3] + x[4] * x[4] + x[5] * x[5]);
    peak = std::max(peak, v);
  }
  return std::sqrt(peak);
}

/// The point whose peak von Mises stress is largest at torque T.
StressPeak largest_peak(const Histories& h, const FourierSolution& s, const FlexsplineModel& c, double T) {
  StressPeak w;
  w.torque_Nm = T;
  for (std::size_t j = 0; j < h.node.size(); ++j) {
    const double v = peak_von_mises(h.generator[j], h.torque_unit[j], T);
    if (v > w.von_mises_Pa) {
      w.von_mises_Pa = v;
      w.r_m = s.section.nodes(h.node[j], 0);
      w.z_m = s.section.nodes(h.node[j], 1);
    }
  }
  w.place = place_of(c, w.z_m);
  return w;
}

}  // namespace

StressPeak flexspline_peak_stress_at(const FourierSolution& s, const FlexsplineModel& c, double torque_Nm) {
  return largest_peak(histories(s, c), s, c, torque_Nm);
}

FirstYield first_yield_torque(const FourierSolution& s, const FlexsplineModel& c, double search_limit_Nm) {
  if (!c.material.yield_strength_Pa)
    throw InputError("the flexspline's first yield needs material.yield_strength_MPa");
  if (!c.wave_generator) throw InputError("the flexspline's first yield needs a [wave_generator]");
  const double Sy = *c.material.yield_strength_Pa;
  const Histories h = histories(s, c);
  FirstYield out;
  out.at_zero = largest_peak(h, s, c, 0.0);
  const auto yields = [&](double T) { return largest_peak(h, s, c, T).von_mises_Pa >= Sy; };
  if (out.at_zero.von_mises_Pa >= Sy) {
    out.at_yield = out.at_zero;
    return out;
  }
  if (!yields(search_limit_Nm)) {
    out.at_yield = largest_peak(h, s, c, search_limit_Nm);
    out.torque_Nm = std::numeric_limits<double>::infinity();
    return out;
  }
  const auto [lo, hi] = first_crossing(0.0, search_limit_Nm, kScanSteps, kTorqueTolerance, yields);
  out.torque_Nm = 0.5 * (lo + hi);
  out.at_yield = largest_peak(h, s, c, out.torque_Nm);
  return out;
}

double sines_goodman_safety_factor(const StressHistory& history, double fatigue_limit_Pa,
                                   double ultimate_strength_Pa) {
  return safety(amplitudes(history), fatigue_limit_Pa, ultimate_strength_Pa);
}

FatigueState flexspline_fatigue_at(const FourierSolution& s, const FlexsplineModel& c, double torque_Nm) {
  require_fatigue_data(c.material);
  return worst(histories(s, c), s, c, torque_Nm);
}

InfiniteLife infinite_life_torque(const FourierSolution& s, const FlexsplineModel& c, double search_limit_Nm) {
  require_fatigue_data(c.material);
  if (!c.wave_generator) throw InputError("the flexspline's fatigue needs a [wave_generator] (the bending it cycles)");
  const Histories h = histories(s, c);
  InfiniteLife out;
  out.at_zero = worst(h, s, c, 0.0);
  if (out.at_zero.safety_factor <= 1) {
    out.at_limit = out.at_zero;
    return out;
  }
  const FatigueState top = worst(h, s, c, search_limit_Nm);
  if (top.safety_factor > 1) {
    out.at_limit = top;
    out.torque_Nm = std::numeric_limits<double>::infinity();
    return out;
  }
  // The first crossing on a scan (the safety factor need not fall monotonically with torque), then bisection.
  const auto [lo, hi] = first_crossing(0.0, search_limit_Nm, kScanSteps, kTorqueTolerance,
                                       [&](double T) { return worst(h, s, c, T).safety_factor <= 1; });
  out.torque_Nm = 0.5 * (lo + hi);
  out.at_limit = worst(h, s, c, out.torque_Nm);
  return out;
}

}  // namespace sw
