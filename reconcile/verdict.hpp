#pragma once
// The reconcile report: what reconcile.json holds (SPEC.md keys) as a typed value, written and read by
// io/reconcile_output.hpp; reconcile.html, a self-contained page with inline SVG plots (recording vs baseline vs
// reconciled model, residual before/after with the located region shaded, and the order spectrum of the residual for
// transmission and backlash recordings); and the verdict printed on stdout.
#include <map>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "reconcile/experiment.hpp"
#include "reconcile/reconcile.hpp"

namespace sw::reconcile {

/// A located mismatch (the report's mismatch.locations[]).
struct ReportLocation {
  std::string domain, description;
  double p_value = 1.0;
  bool operator==(const ReportLocation&) const = default;
};

/// An accepted effect (effects[]): its headline parameters with 95 % intervals.
struct ReportEffect {
  std::string name, physics;
  std::optional<int> order;                                 ///< a harmonic's order (params.order, exact)
  std::map<std::string, double> params;                     ///< every other headline parameter
  std::map<std::string, std::pair<double, double>> ci95;    ///< per fitted parameter of `params`
  std::map<std::string, std::string> fixed;                 ///< per held parameter of `params`: where it is read
  double delta_bic = 0.0, p_value = 1.0;
  std::string meaning;                                      ///< what it means for the drive ("": key absent)
  /// Refitted on re-runs of the model: how far the columns missed it at their estimate, and the runs (0: key absent).
  double model_discrepancy = 0.0;
  int model_runs = 0;
  bool operator==(const ReportEffect&) const = default;
};

/// The catalog's published row of the recording's size, beside the fitted figures (catalog.reference).
struct ReportCatalogReference {
  int size = 0;
  double k1_Nm_per_rad = 0, k2_Nm_per_rad = 0, k3_Nm_per_rad = 0, t1_Nm = 0, t2_Nm = 0, rated_torque_Nm = 0;
  double hysteresis_loss_max_arcmin = 0, lost_motion_max_arcmin = 0;  ///< the catalog's limits
  bool operator==(const ReportCatalogReference&) const = default;
};

/// A torsion model in the catalog's terms (the "catalog" block; CatalogFigures).
struct ReportCatalog {
  int segments = 1;
  double k1_Nm_per_rad = 0, k2_Nm_per_rad = 0, k3_Nm_per_rad = 0, t1_Nm = 0, t2_Nm = 0;
  double rated_torque_Nm = 0;
  std::string rated_torque_from;
  double hysteresis_loss_arcmin = 0, play_width_arcmin = 0, catalog_lost_motion_arcmin = 0;
  std::string note;                                          ///< what the two lost-motion figures mean
  std::optional<ReportCatalogReference> reference;
  /// With a soft start: the twist the K1 segment spans over the final residual RMS (below ~10 the soft start is hard
  /// to tell from the next segment).
  std::optional<double> k1_segment_twist_over_noise;
  bool operator==(const ReportCatalog&) const = default;
};

/// The model re-run with the fitted physical values (the "refit" block): its RMS over all rows and the held-out rows.
struct ReportRefit {
  double rms = 0, heldout_rms = 0;
  bool operator==(const ReportRefit&) const = default;
};

/// reconcile.json as values.
struct Report {
  Kind kind = Kind::Torsion;
  int samples = 0;
  std::string baseline_model;
  std::string baseline_source;                               ///< "" when given directly (the key is then absent)
  double baseline_rms = 0, baseline_heldout_rms = 0;
  bool significant = false;
  /// The located signatures, then those still significant after the final model (described as unexplained).
  std::vector<ReportLocation> locations;
  std::vector<ReportEffect> effects;
  std::vector<Rejected> rejected;
  double final_rms = 0, final_heldout_rms = 0;
  std::optional<ReportRefit> refit;                          ///< with physical effects refitted on model re-runs
  std::optional<ReportCatalog> catalog;                      ///< torsion
  std::string verdict;
  bool operator==(const Report&) const = default;
};

/// The report of an analysis.
Report report_of(const Result& r);

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
