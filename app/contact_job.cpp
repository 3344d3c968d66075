#include "app/contact_job.hpp"

#include <cstdio>
#include <numbers>
#include <optional>

#include "common/error.hpp"
#include "common/progress.hpp"
#include "io/atomic_file.hpp"
#include "io/contact_output.hpp"

namespace sw::app {
namespace {

constexpr double kArcmin = 10800.0 / std::numbers::pi;

/// What acts in series with the body, from the case.
SeriesParts series_parts(const Case&) {
  SeriesParts s;
  s.teeth_source = "rigid teeth";
  return s;
}

}  // namespace

ContactAnalysis run_contact_job(const Case& c, const FemJobResult& fem, const std::filesystem::path& dir) {
  if (!fem.system || !fem.mesh)
    throw InputError(c.path + ": contact solves on the TET10 model (solver.method = \"tet10\")");
  ContactOptions o;
  o.rated_torque_Nm = c.load.torque_Nm;
  o.series = series_parts(c);
  const std::optional<CatalogLaw> reference;
  const ContactAnalysis a = analyse_contact(c, *fem.mesh, *fem.system, fem.solution, o);
  write_file_atomic(dir / "contact.json", contact_json(a, c.path, reference));
  write_file_atomic(dir / "torque_twist.csv", torque_twist_csv(a));
  write_file_atomic(dir / "contact.svg", contact_svg(a, reference));
  const TorqueStep& r = a.steps.back();
  std::printf("contact %s: %d contacts (%zu flanks%s, generator: %s), %zu torque steps in %.2f s (influence %.2f s)\n",
              c.path.c_str(), a.unknowns, a.flanks.size(), a.half_turn_pairs ? " × 2 teeth" : "",
              a.generator_support.c_str(), a.steps.size(), a.contact_s, a.influence_s);
  std::printf("  twist at rated torque %.4g N·m: %.3f arcmin; %d flanks in contact, largest flank force %.1f N; "
              "teeth: %s\n", a.rated_torque_Nm, r.twist_rad * kArcmin, r.pairs_in_contact, r.max_pair_force_N,
              o.series.teeth_source.c_str());
  std::printf("  three segments (%s): T1 %.3g N·m, T2 %.3g N·m, K1 %.4g, K2 %.4g, K3 %.4g N·m/rad\n",
              a.catalog.breakpoints_fitted ? "breakpoints fitted" : "the catalog's breakpoints", a.catalog.t1_Nm,
              a.catalog.t2_Nm, a.catalog.k1_Nm_per_rad, a.catalog.k2_Nm_per_rad, a.catalog.k3_Nm_per_rad);
  std::printf("  lost motion (twist between ±4 %% of rated, middle line) %.3f arcmin; play (dead band at zero torque) "
              "%.3f arcmin\n", a.lost_motion_rad * kArcmin, a.play_rad * kArcmin);
  std::printf("  twist at rated: engagement %.1f %%, body %.1f %%, teeth %.1f %%, generator bearing %.1f %%, circular "
              "spline %.1f %%\n", 100 * a.split.engagement, 100 * a.split.body, 100 * a.split.teeth,
              100 * a.split.generator, 100 * a.split.circular_spline);
  if (a.overlap_at_rest_m > 0)
    std::printf("  WARNING: the teeth overlap at rest by %.2f µm on the FEM's neutral curve, so part of the curve above is a "
                "preload from that interference, not a property of the drive; remove the interference first (the "
                "backlash stage's geometry check gives the remedy)\n", a.overlap_at_rest_m * 1e6);
  std::printf("  torque balance: flank moments vs torque %.1e (relative, worst step); clamp reaction in a direct FEM "
              "solve %.6g N·m vs %.6g N·m\n", a.torque_balance_error_rel, a.fem_reaction_torque_Nm, a.rated_torque_Nm);
  return a;
}

}  // namespace sw::app
