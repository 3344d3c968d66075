#pragma once
// The harmonic analysis of a flexspline that is a body of revolution, as the steps of the TET10 path's
// (fem/flexspline_analysis.hpp): supports, loads, every harmonic solved on its factor (fem/fourier_solver.hpp), the
// load cases built from them (the generator's contact or forces, the torque) and the figures read from them.
#include "fem/fourier_solver.hpp"

namespace sw {

/// Solves the case (teeth "ring", "layer" or "none") by harmonics 0..c.solver.harmonics on its meridian section
/// (figures.cases without fields: revolved_load_cases evaluates them for VTU output).
FourierSolution analyse_flexspline_fourier(const FlexsplineModel& c, const BandRequest& request = {});

/// Same on a given section (tests: the annulus of fem/fourier_section.hpp).
FourierSolution analyse_section_fourier(const FlexsplineModel& c, SectionMesh section,
                                        const BandRequest& request = {});

/// The solution's load cases (figures.cases: their names and rotations) with each one's displacement and stress at
/// every node of fourier::revolve_section(s.section, sectors)'s grid (midside nodes included, every node evaluated
/// from the series), for VTU output after the analysis (the fem job writes them while the contact goes on).
std::vector<LoadCaseSolution> revolved_load_cases(const FourierSolution& s, const Material& m, int sectors);

}  // namespace sw
