// A fitted torsion model read in the catalog's terms: segment stiffnesses, hysteresis loss and lost motion at rated
// torque.
#include <cmath>

#include "reconcile/effects.hpp"
#include "reconcile/fit.hpp"

namespace sw::reconcile {

namespace {

/// The torque the loss and lost motion are read at: the recording's rated torque, its catalog size's, or its amplitude.
void read_rated_torque(const TorsionExperiment& t, CatalogFigures& c) {
  if (t.rated_torque_Nm > 0.0) {
    c.rated_torque_Nm = t.rated_torque_Nm;
    c.rated_from = "metadata rated_torque_Nm";
  } else if (c.reference) {
    c.rated_torque_Nm = c.reference->rated_torque_Nm;
    c.rated_from = "catalog size " + std::to_string(c.reference->size);
  } else {
    c.rated_torque_Nm = t.torque_amplitude_Nm;
    c.rated_from = "the recording's torque amplitude (no rated torque in the metadata)";
  }
}

/// A curve baseline's own three segments (with the series compliance, if named) as segment secants, as catalogs read
/// them: K1 over 0..T1, K2 over T1..T2, K3 over T2 to the top of the recorded range. Friction and play are not
/// stiffness: they stay out, as they stay out of the stiffness effect's slopes.
void read_curve_segments(const TorsionExperiment& t, double c_series, CatalogFigures& c) {
  const double t1 = t.model.curve_t1_Nm, t2 = t.model.curve_t2_Nm, top = t.torque_amplitude_Nm;
  auto twist = [&](double T) { return 0.5 * (t.model.twist_rad(T) - t.model.twist_rad(-T)) + c_series * T; };
  c.segments = 3;
  c.t1 = t1;
  c.t2 = t2;
  c.k1 = t1 / twist(t1);
  c.k2 = (t2 - t1) / (twist(t2) - twist(t1));
  c.k3 = (top - t2) / (twist(top) - twist(t2));
}

}  // namespace

const CatalogDrive* catalog_stiffness(int size) {
  const CatalogDrive* d = catalog_drive(size);
  return d && d->has_stiffness() ? d : nullptr;
}

std::optional<CatalogFigures> catalog_figures(const Experiment& e, const FitResult& f) {
  const auto* t = std::get_if<TorsionExperiment>(&e.data);
  if (!t) return std::nullopt;
  CatalogReading r;
  CatalogFigures& c = r.figures;
  c.reference = catalog_stiffness(t->drive_size);
  read_rated_torque(*t, c);
  const double R = c.rated_torque_Nm;
  const double c_series = added_series_compliance(f);
  const double c_last = t->model.compliance_rad_per_Nm + c_series;
  c.k1 = c.k2 = c.k3 = 1.0 / c_last;
  c.hysteresis_loss_arcmin = t->model.loop_loss_rad * kArcmin;  // a loop baseline's own; effects add to it
  // The middle line of the loop after cycling to +-R: everything but the branch-dependent part of hysteresis. A
  // curve baseline (the contact stage's) is its own middle line.
  r.middle_twist_rad = [c_last](double T) { return c_last * T; };
  if (t->model.twist_rad)
    r.middle_twist_rad = [curve = t->model.twist_rad, c_series](double T) { return curve(T) + c_series * T; };
  for (std::size_t i = 0; i < f.terms.size(); ++i)
    if (f.terms[i].spec->catalog) f.terms[i].spec->catalog(e, f, static_cast<int>(i), r);
  c.catalog_lost_motion_arcmin = (r.middle_twist_rad(0.04 * R) - r.middle_twist_rad(-0.04 * R)) * kArcmin;
  const bool stiffness_effect = c.segments > 1;
  const double t1 = t->model.curve_t1_Nm, t2 = t->model.curve_t2_Nm, top = t->torque_amplitude_Nm;
  if (t->model.twist_rad && !stiffness_effect && t1 > 0.0 && t2 > t1 && top > t2) read_curve_segments(*t, c_series, c);
  return c;
}

}  // namespace sw::reconcile
