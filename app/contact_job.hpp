#pragma once
// The contact job shared by `strainwave contact` and `strainwave run`: the loaded tooth contact on the FEM's own
// system, its outputs and summary.
#include <functional>
#include <memory>
#include <optional>
#include <utility>
#include <string>
#include <vector>

#include "app/fem_job.hpp"
#include "contact/loaded_contact.hpp"
#include "fem/cholmod_factor.hpp"
#include "generator/ring_slip.hpp"
#include "io/atomic_file.hpp"
#include "io/contact_output.hpp"

namespace sw::app {

/// The files the contact job writes in its output folder: a command that runs it owns them (OutputSet).
inline const std::vector<std::string> kContactJobFiles = {"contact.json", "torque_twist.csv", "contact.svg"};

/// What acts in series with the flexspline body, from the case (tooth pairs, generator bearing, circular spline; the
/// ring solved when the contact first asks for its block).
SeriesParts series_parts(const Case& c);

/// The flexspline body the fem job left for the loaded contact: the harmonic solution's (HarmonicBody) or the TET10
/// mesh and factor's (Tet10Body, reading the generator's field from `fem_u` when not null). Every argument must
/// outlive it.
std::unique_ptr<ContactBody> contact_body(const Case& c, const FemJobResult& fem, const Eigen::VectorXd* fem_u);

/// The contact's options from the case: rated torque, the series parts given (`series`), face slices, flank friction
/// and the catalog size's breakpoints (the torque steps at their default).
ContactOptions contact_options(const Case& c, SeriesParts series);

/// The generator's outer ring on the flexspline's bore at `stations` (generator/ring_slip.hpp): the bore's curvature
/// where it lies on a cam's surface, the rim's and the bearing's lever, and boundary friction (the ring slides on the
/// bore without rolling, as the flanks where their rolling vanishes: gear/mesh_friction.hpp kBoundaryFriction).
/// Without curvatures for a generator that is not a cam with a bearing.
RingOnBore ring_on_bore(const Case& c, const BodyStations& stations);

/// The catalog's law of the case's catalog size, when the catalog gives its stiffness.
std::optional<CatalogLaw> catalog_reference(const Case& c);

/// What a contact run adds to the nominal drive.
struct ContactJobOptions {
  int accuracy_class = 0;   ///< > 0: the band over drives made to this ISO 1328-1 tolerance class (1–11)
  int accuracy_drives = 16; ///< how many drives the band draws
};

/// Runs the contact analysis on the flexspline body with what the FEM gave (`fem`: solved now or read back from an
/// earlier run's result.json), writes contact.json, torque_twist.csv and contact.svg into the set `out` (owning
/// kContactJobFiles), prints the summary.
/// With `job.accuracy_class`, the band over drives of that class too (contact.json's accuracy_band, one line).
ContactAnalysis run_contact_job(const Case& c, const ContactBody& body, const FemReadout& fem, OutputSet& out,
                                const ContactJobOptions& job = {});

}  // namespace sw::app
