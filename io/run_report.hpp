#pragma once
// report.html: one self-contained page per run (inline SVG, no scripts, no network) with what a designer reads: the
// case, the FEM figures and their checks, the neutral curve (FEM against the generator model's ring/cam curve), the
// hoop stress around the rim, the backlash over a revolution, what is not computed, and how to open the 3-D results.
#include <filesystem>
#include <string>
#include <vector>

namespace sw {

struct RunReportInputs {
  std::filesystem::path out_dir;   ///< holds result.json, neutral_curve.csv, backlash.json/.svg of the run
  std::filesystem::path shown_dir; ///< the folder the page names (where the run's files appear); empty: out_dir
  std::string case_path;
  std::string case_text;           ///< the resolved case (describe_case)
  std::vector<double> theory_phi_rad, theory_w_m;  ///< the generator model's neutral curve, for comparison
  std::string theory_label;
};

/// The page's HTML. Reads the run's files from out_dir through their typed readers (read_fem_result,
/// read_backlash_result, read_contact_result); a missing backlash.json or contact.json leaves its section out. Throws
/// InputError naming the file, the key and the value when result.json is missing or any file read is not what its
/// writer writes.
std::string run_report_html(const RunReportInputs& in);

}  // namespace sw
