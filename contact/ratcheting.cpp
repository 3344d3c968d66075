#include "contact/ratcheting.hpp"

#include <cmath>
#include <stdexcept>
#include <utility>

#include "common/error.hpp"
#include "common/first_crossing.hpp"

namespace sw {

std::optional<std::pair<std::vector<bool>, RatchetState>> teeth_holding(const std::vector<RatchetTooth>& teeth,
                                                                         const RatchetSolve& solve, double torque_Nm) {
  std::vector<bool> carry(teeth.size());
  for (std::size_t t = 0; t < teeth.size(); ++t) carry[t] = teeth[t].overlap_at_rest_m > 0;
  for (;;) {
    std::optional<RatchetState> s = solve(torque_Nm, carry);
    if (!s) return std::nullopt;
    bool released = false;
    for (std::size_t t = 0; t < teeth.size(); ++t)
      if (carry[t] && s->overlap_m[static_cast<Eigen::Index>(t)] <= 0) carry[t] = !(released = true);
    if (!released) return std::make_pair(carry, std::move(*s));
  }
}

Ratcheting ratcheting_torque(const std::vector<RatchetTooth>& teeth, const RatchetSolve& solve, double from_Nm,
                             double ceiling_Nm, double tolerance_rel) {
  if (!(from_Nm > 0) || !(ceiling_Nm >= from_Nm) || !(tolerance_rel > 0))
    throw std::invalid_argument("ratcheting_torque: needs 0 < from <= ceiling and a positive tolerance");
  Ratcheting r;
  r.ceiling_Nm = ceiling_Nm;
  r.tolerance_rel = tolerance_rel;
  const auto engaged_released = [&](const std::vector<bool>& carry) {
    for (std::size_t t = 0; t < teeth.size(); ++t)
      if (teeth[t].overlap_at_rest_m > 0 && !carry[t]) return static_cast<int>(t);
    return -1;
  };
  const auto at_from = teeth_holding(teeth, solve, from_Nm);
  if (!at_from)
    throw InputError("ratcheting: the teeth do not hold " + std::to_string(from_Nm) + " N·m, where the ramp starts");
  const auto fails = [&](double T) { return !teeth_holding(teeth, solve, T); };
  const auto releases = [&](double T) {
    const auto h = teeth_holding(teeth, solve, T);
    return !h || engaged_released(h->first) >= 0;
  };
  // The ramp: 10 % steps to the first torque that does not hold.
  double lo = from_Nm, hi = from_Nm;
  bool reached = false;
  while (hi < ceiling_Nm) {
    lo = hi;
    hi = std::min(1.1 * hi, ceiling_Nm);
    if (fails(hi)) {
      reached = true;
      break;
    }
  }
  // The first release: at the start already, or between the start and the torque that does not hold.
  const double release_hi = reached ? hi : ceiling_Nm;
  if (engaged_released(at_from->first) >= 0) r.first_release_Nm = from_Nm;
  else if (releases(release_hi))
    r.first_release_Nm = first_crossing(from_Nm, release_hi, 0, tolerance_rel, releases).second;
  if (std::isfinite(r.first_release_Nm)) {
    const auto h = teeth_holding(teeth, solve, r.first_release_Nm);
    const int t = h ? engaged_released(h->first) : -1;
    if (t >= 0) {
      r.first_tooth = teeth[t].tooth;
      r.first_slice = teeth[t].slice;
      r.first_phi_rad = teeth[t].phi_rad;
    }
  }
  if (!reached) return r;
  const auto [below, at] = first_crossing(lo, hi, 0, tolerance_rel, fails);
  r.torque_Nm = at;
  // What holds just below it.
  if (const auto h = teeth_holding(teeth, solve, below)) {
    r.twist_below_rad = h->second.twist_rad;
    double least = std::numeric_limits<double>::infinity();
    for (std::size_t t = 0; t < teeth.size(); ++t) {
      if (!h->first[t]) continue;
      ++r.teeth_holding;
      const double o = h->second.overlap_m[static_cast<Eigen::Index>(t)];
      if (h->second.loaded[t] && o < least) {
        least = o;
        r.last_tooth = teeth[t].tooth;
        r.last_slice = teeth[t].slice;
        r.last_phi_rad = teeth[t].phi_rad;
        r.last_overlap_m = o;
        if (h->second.rim_in_m.size()) r.last_rim_in_m = h->second.rim_in_m[static_cast<Eigen::Index>(t)];
        if (h->second.ring_out_m.size()) r.last_ring_out_m = h->second.ring_out_m[static_cast<Eigen::Index>(t)];
        if (t < h->second.normal_turn_rad.size()) r.last_normal_turn_rad = h->second.normal_turn_rad[t];
        if (t < h->second.contact.size()) r.last_contact = h->second.contact[t];
      }
    }
  }
  return r;
}

}  // namespace sw
