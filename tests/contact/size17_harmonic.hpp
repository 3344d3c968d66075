#pragma once
// The shipped designed size-17 cup (cases/cup_size17.toml) solved once on the harmonic solver, with the contact's
// bands: the rim at rest for contact tests that need a real drive's geometry.
#include <memory>

#include "app/contact_job.hpp"
#include "contact/harmonic_body.hpp"
#include "fem/fourier_analysis.hpp"
#include "fem/fourier_solver.hpp"
#include "io/case.hpp"

namespace sw::test {

struct Size17Harmonic {
  Case c;
  std::shared_ptr<FourierSolution> fourier;
  std::shared_ptr<HarmonicBody> body;
  FemReadout readout;
  ContactOptions options;  ///< the case's (app::contact_options)
};

inline const Size17Harmonic& size17_harmonic() {
  static const Size17Harmonic* s = [] {
    auto* k = new Size17Harmonic;
    k->c = load_case("cases/cup_size17.toml");
    const FlexsplineModel m = flexspline_model(k->c);
    k->fourier = std::make_shared<FourierSolution>(
        analyse_flexspline_fourier(m, contact_band_request(m, k->c.contact.face_slices)));
    k->body = std::make_shared<HarmonicBody>(m, *k->fourier);
    k->readout = fem_readout(k->fourier->figures);
    k->options = app::contact_options(k->c, app::series_parts(k->c));
    return k;
  }();
  return *s;
}

}  // namespace sw::test
