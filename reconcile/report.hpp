#pragma once
// The reconcile report: reconcile.json exactly per SPEC.md, and reconcile.html, a self-contained page with inline SVG
// plots (recording vs baseline vs reconciled model, residual before/after with the located region shaded, and the
// order spectrum of the residual for transmission and backlash recordings).
#include <string>

#include "reconcile/experiment.hpp"
#include "reconcile/reconcile.hpp"

namespace sw::reconcile {

/// reconcile.json text (SPEC.md keys only).
std::string report_json(const Result& r);

/// reconcile.html text. `notes` are extra lines shown at the top (e.g. case/metadata disagreements).
std::string report_html(const Experiment& e, const Recording& rec, const Result& r, const std::vector<std::string>& notes);

/// The short verdict printed on stdout.
std::string report_summary(const Result& r);

/// Amplitude spectrum of y sampled at `angle_rad` (monotone), resampled to a uniform angle grid: amplitude per order
/// (cycles per revolution of that angle) for orders 0 .. max_order in steps of 1/revolutions.
struct Spectrum {
  std::vector<double> order;
  std::vector<double> amplitude;
};
Spectrum order_spectrum(const Eigen::VectorXd& angle_rad, const Eigen::VectorXd& y, double max_order);

}  // namespace sw::reconcile
