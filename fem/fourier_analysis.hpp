#pragma once
// The harmonic analysis of a flexspline that is a body of revolution, as the steps of the TET10 path's
// (fem/flexspline_analysis.hpp): supports, loads, every harmonic solved on its factor (fem/fourier_solver.hpp), the
// load cases built from them (the generator's contact or forces, the torque) and the figures read from them.
#include "fem/fourier_solver.hpp"

namespace sw {

/// Solves the case (teeth "ring" or "none") by harmonics 0..c.solver.harmonics on its meridian section. With
/// `grid_sectors` > 0 also revolves the section into a TET10 grid of that many sectors (midside nodes included,
/// every node evaluated from the series) and fills figures.cases[].u / .stress on it for VTU output.
FourierSolution analyse_flexspline_fourier(const FlexsplineModel& c, int grid_sectors = 0,
                                          const BandRequest& request = {});

/// The solution's load cases (figures.cases: their names and rotations) with each one's displacement and stress at
/// every node of revolve_section(s.section, sectors)'s grid, as `grid_sectors` > 0 fills them: for VTU output after
/// the analysis (the fem job writes them while the contact goes on).
std::vector<LoadCaseSolution> revolved_load_cases(const FourierSolution& s, const Material& m, int sectors);

/// Same on a given section (tests: the annulus of fem/fourier_section.hpp).
FourierSolution analyse_section_fourier(const FlexsplineModel& c, SectionMesh section, int grid_sectors = 0,
                                        const BandRequest& request = {});

/// The solution's load cases (figures.cases: their names and rotations) with each one's displacement and stress at
/// every node of revolve_section(s.section, sectors)'s grid, as `grid_sectors` > 0 fills them: for VTU output after
/// the analysis (the fem job writes them while the contact goes on).
std::vector<LoadCaseSolution> revolved_load_cases(const FourierSolution& s, const Material& m, int sectors);

}  // namespace sw
