#pragma once
// The backlash job shared by `strainwave backlash` and `strainwave run`.
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "io/atomic_file.hpp"
#include "io/case.hpp"
#include "io/backlash_output.hpp"

namespace sw::app {

/// The files the backlash job writes in its output folder: a command that runs it owns them (OutputSet).
inline const std::vector<std::string> kBacklashJobFiles = {"backlash.json", "backlash.csv", "backlash.svg",
                                                           "profiles.vtp", "drive.svg"};

struct BacklashJobOptions {
  std::optional<std::filesystem::path> fem_result;  ///< --fem DIR/result.json: φ₀ (or C_τ·T) and neutral_curve.csv
  std::optional<double> phi0_rad;                   ///< --phi0: overrides the FEM's φ₀
  bool fem_curve = false;                           ///< --curve fem: neutral_curve.csv beside result.json
  int revolution_steps = 3600;                      ///< 0.1° steps
};

/// Where the backlash stage reads the teeth when the contact meshes the face in sections (" on the face's centre
/// section (...)"; empty for one section): the stage has one neutral curve, the rim at mid-face.
inline std::string at_face_centre(const Case& c) {
  if (c.contact.face_slices <= 1) return "";
  return " on the face's centre section (the contact meshes " + std::to_string(c.contact.face_slices) +
         " sections of straight teeth, each with its own play: the drive's play is theirs together)";
}

/// Builds the model from the case, sweeps, writes backlash.json/.csv/.svg, profiles.vtp and drive.svg (the drawing of
/// the drive's parts) into the set `out` (owning
/// kBacklashJobFiles; an fem result of the same set is read as staged), prints the paper's table on stdout. Throws
/// InputError for a case without [gear] or without wave_generator.radial_deformation_mm.
BacklashReport run_backlash_job(const Case& c, const BacklashJobOptions& options, OutputSet& out);

}  // namespace sw::app
