#pragma once
// The model reconcile updates: the case re-run with some of its numeric keys changed (the FEM on the harmonic solver,
// and the loaded contact for a torsion recording held against the drive's curve), the physical candidates a case
// offers, and `--candidate KEY[=LO:HI]`.
#include <string>
#include <vector>

#include "app/reconcile_baseline.hpp"
#include "contact/loaded_contact.hpp"
#include "io/case.hpp"
#include "reconcile/model_update.hpp"

namespace sw::app {

/// How the re-runs are made: the loaded contact's torque steps each way (ContactOptions::steps).
struct ModelRunOptions {
  int contact_steps = ContactOptions{}.steps;
};

/// The case's resolved text (describe_case) with `values` set, parsed: every key the file leaves out (the mesh, the
/// harmonics, derived thicknesses) stays at the base case's value, so a re-run changes only the keys named. Throws
/// InputError naming the key for a value the case refuses.
Case case_with(const Case& c, const reconcile::ModelKeyValues& values);

/// The torsion baseline of the case computed now, with the re-run that changes keys (Baseline::model_run, its runs
/// remembered): for TorsionBaseline::Contact the drive's torque-twist curve (FEM and loaded contact, in memory, read
/// as make_baseline reads contact.json), for Fem C_tau T of the flexspline body. Needs solver.method = "fourier" (a
/// re-run is then seconds); `src.recording` (optional) is checked to lie within the curve as make_baseline does.
reconcile::Baseline model_baseline(const Case& c, const BaselineSources& src, const ModelRunOptions& options = {});

/// The tool's physical candidates for a torsion recording against `baseline` that the case has: against the contact
/// curve the rim, wall and diaphragm thickness, the generator's radial deformation, the circular spline's bolt
/// circles (bolted_face), the flexspline's tip rounding and the flank friction; against C_tau only the three
/// thicknesses. Each with its physics, its plausible range and the case's resolved value.
std::vector<reconcile::ModelCandidate> default_candidates(const Case& c, TorsionBaseline baseline);

/// `--candidate KEY[=LO:HI]`: a numeric key of the case with its plausible range (without one: the default
/// candidate's, else +-20 % of the case value). Throws InputError (one line naming the option, the key and the
/// expectation) for a key the case has no number for, a malformed range, LO >= HI, or a case value outside it.
reconcile::ModelCandidate parse_candidate(const Case& c, const std::string& spec, TorsionBaseline baseline);

/// The candidates: the defaults with each --candidate added (replacing a default of the same key).
std::vector<reconcile::ModelCandidate> model_candidates(const Case& c, TorsionBaseline baseline,
                                                        const std::vector<std::string>& specs);

/// reconciled.toml: the case's resolved text with the refitted values set, headed by what was fitted.
std::string reconciled_case_text(const Case& c, const reconcile::Refit& refit);

}  // namespace sw::app
