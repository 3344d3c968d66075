#include <chrono>
#include <cstdio>

#include <gtest/gtest.h>

#include "dynamics/analysis.hpp"
#include "tests/dynamics/seed_models.hpp"

using namespace sw;

TEST(DynamicsProbe, PrintsNumbers) {
  for (auto cfg : {DynamicsConfiguration::CsFixed, DynamicsConfiguration::FsFixed, DynamicsConfiguration::WgFixed,
                   DynamicsConfiguration::AllFree}) {
    auto m = test::seed_model(cfg);
    const auto t0 = std::chrono::steady_clock::now();
    auto s = simulate(m);
    const double el = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    auto r = summarize(m, s);
    std::printf("%s: %.2f s, steps %ld rhs %ld jac %ld etf %ld; pairs %zu\n", to_string(cfg), el, s.stats.steps,
                s.stats.rhs_evals, s.stats.jac_evals, s.stats.error_test_fails, m.pairs.size());
    for (auto& c : r.speeds) std::printf("  %s sim %.8g th %.8g err %.3g\n", c.body.c_str(), c.simulated_rpm, c.theory_rpm, c.error_rel);
    std::printf("  max pair err %.3g torque err %.3g energy %.3g (in %.4g out %.4g diss %.4g ke %.4g pe %.4g) fluct %.4g mean %.4g fm %.1f\n",
                r.max_pair_force_error_rel, r.torque_balance_error_rel, r.energy_error_rel, s.energy.input_J,
                s.energy.output_J, s.energy.dissipated_J, s.energy.kinetic_J, s.energy.potential_J, r.force_fluctuation_N,
                r.mean_total_force_N, r.theory.mesh_frequency_Hz);
    for (int i = 0; i < 3 && i < int(r.lines.size()); ++i) std::printf("  line %.1f Hz %.4g N\n", r.lines[i].frequency_Hz, r.lines[i].amplitude_N);
  }
}

TEST(DynamicsProbe, Varying) {
  for (int which = 0; which < 2; ++which)
  for (double c : {1e2, 3e2, 1e3, 3e3, 1e4}) {
    auto m = which ? test::small_model() : test::seed_model();
    m.params.stiffness_variation_N_per_m = 0.2 * m.params.stiffness_N_per_m;
    m.params.damping_Ns_per_m = c;
    const auto t0 = std::chrono::steady_clock::now();
    auto s = simulate(m);
    const double el = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    auto r = summarize(m, s);
    std::printf("%d c %.0f: %.2f s steps %ld; fluct %.5g mean %.5g, pair err %.3g, energy %.3g par %.4g fm %.1f speederr %.3g\n", which, c, el,
                s.stats.steps, r.force_fluctuation_N, r.mean_total_force_N, r.max_pair_force_error_rel, r.energy_error_rel,
                s.energy.parametric_J, r.theory.mesh_frequency_Hz, r.max_speed_error_rel);
    for (int i = 0; i < 4 && i < int(r.lines.size()); ++i) std::printf("  line %.1f Hz %.4g N\n", r.lines[i].frequency_Hz, r.lines[i].amplitude_N);
  }
}
