#pragma once
// Looking up what reconcile named in a Result (shared by the reconcile tests).
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "reconcile/reconcile.hpp"

namespace sw::reconcile::testing {

/// The accepted effect of this name (and harmonic order, when > 0); nullptr when not named.
inline const AcceptedEffect* find(const Result& r, const std::string& name, int order = 0) {
  for (const auto& e : r.effects) {
    if (e.name != name) continue;
    if (order == 0) return &e;
    for (const auto& p : e.params)
      if (p.name == "order" && std::lround(p.value) == order) return &e;
  }
  return nullptr;
}

/// A headline parameter's value; a test failure (and NaN) when the effect has no such parameter.
inline double param(const AcceptedEffect& e, const std::string& name) {
  for (const auto& p : e.params)
    if (p.name == name) return p.value;
  ADD_FAILURE() << "no parameter " << name;
  return NAN;
}

/// The effects named, the verdict, what is left and why others were rejected, for a test's trace.
inline std::string trace_of(const Result& r) {
  std::string s;
  for (const auto& e : r.effects) s += e.name + " ";
  s += "| verdict " + r.verdict;
  for (const auto& u : r.unexplained) s += " | left: " + u.description;
  for (const auto& x : r.rejected) s += " | rejected " + x.reason;
  return s;
}

inline double rel_err(double got, double want) { return std::abs(got - want) / std::abs(want); }

}  // namespace sw::reconcile::testing
