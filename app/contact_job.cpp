#include "app/contact_job.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <memory>
#include <numbers>
#include <optional>
#include <string>

#include "common/constants.hpp"
#include "common/error.hpp"
#include "common/progress.hpp"
#include "io/atomic_file.hpp"
#include "io/contact_output.hpp"
#include "contact/circular_spline.hpp"
#include "contact/harmonic_body.hpp"
#include "contact/tet10_body.hpp"
#include "generator/generator_bearing.hpp"
#include "gear/mesh_friction.hpp"
#include "design/catalog.hpp"
#include "gear/tooth_profile.hpp"
#include "gear/tooth_stiffness.hpp"

namespace sw::app {

SeriesParts series_parts(const Case& c) {
  SeriesParts s;
  s.teeth_source = "rigid teeth";
  if (c.gear) {
    // The tooth pair's own compliance per unit face width over the rim's width, at the flank's contact radius (kept
    // on the active flank): contact/loaded_contact.hpp tooth_pair_compliance_of.
    const FlexsplineModel m = flexspline_model(c);
    const ToothCompliances teeth = tooth_pair_compliance_of(m);
    s.tooth_pair_m_per_N = teeth.pair_m_per_N;
    // The sections' springs side by side: a solid tooth's coupling across the face (SeriesParts::face_shape,
    // contact/tooth_fem.hpp face_coupling) moves the twist by 0.1-2.2 % on the designs measured (bench_face_coupling)
    // and costs its slabs 1-5 s; left out.
    s.teeth_source = std::string("tooth pair compliance (flexspline tooth: ") +
                     (c.flexspline.teeth == TeethModel::Explicit
                          ? "the body's own explicit teeth, loaded on their flanks"
                          : "explicit-tooth FEM less the ring model's share") +
                     "; circular spline tooth: beam over the real outline and Sainsot foundation; Weber flattening; "
                     "both teeth loaded where they touch)";
  }
  if (c.wave_generator && c.wave_generator->bearing) {
    const GeneratorBearing b = *c.wave_generator->bearing;
    // Hertz: the contact ellipse's shape does not depend on the load, so δ = δ(1 N)·Q^(2/3) exactly.
    const double unit = ball_approach_m(b, 1.0);
    s.bearing_approach_m = [unit](double ball_load_N) { return unit * std::cbrt(ball_load_N * ball_load_N); };
    s.bearing_balls = b.balls;
  }
  if (c.circular_spline && c.gear) {
    // The ring is solved when the contact first asks (the multibody model reads the teeth only), once.
    auto ring = std::make_shared<std::optional<CircularSplineRing>>();
    s.circular_spline = [ring, cs = *c.circular_spline, g = *c.gear, m = c.material,
                         slices = c.contact.face_slices](const std::vector<FlankPattern>& patterns) {
      if (!*ring) ring->emplace(circular_spline_ring(cs, g, m, slices));
      return circular_spline_block(**ring, patterns);
    };
  }
  return s;
}

std::optional<CatalogLaw> catalog_reference(const Case& c) {
  if (!c.catalog_size || !c.gear) return std::nullopt;
  const std::optional<int> ratio = reduction_ratio(*c.gear);
  if (!ratio) return std::nullopt;  // no catalog ratio
  const std::optional<CatalogDrive> d = catalog_stiffness(*c.catalog_size, *ratio);
  if (!d) return std::nullopt;
  return CatalogLaw{d->size, *ratio, d->t1_Nm, d->t2_Nm, d->k1_Nm_per_rad, d->k2_Nm_per_rad, d->k3_Nm_per_rad};
}

ContactOptions contact_options(const Case& c, SeriesParts series) {
  ContactOptions o;
  o.rated_torque_Nm = c.load.rated_torque_Nm.value_or(c.load.torque_Nm);
  o.series = std::move(series);
  o.contact = c.contact;
  if (const std::optional<CatalogLaw> reference = catalog_reference(c)) {
    o.catalog_t1_Nm = reference->t1_Nm;
    o.catalog_t2_Nm = reference->t2_Nm;
  }
  return o;
}

RingOnBore ring_on_bore(const Case& c, const BodyStations& stations) {
  RingOnBore r;
  const Cam* cam = c.wave_generator ? cam_of(*c.wave_generator) : nullptr;
  if (!cam || !c.wave_generator->bearing) return r;
  r.bore_radius_m = c.flexspline.inner_radius_m;
  r.curvature_change_per_m = bore_curvature_change_per_m(
      CamSurface(*cam, c.wave_generator->radial_deformation_m.value_or(0.0), r.bore_radius_m), r.bore_radius_m,
      stations.angle_rad);
  r.lever_m = ring_slip_lever_m(c.flexspline.rim_thickness_m, *c.wave_generator->bearing);
  r.friction = kBoundaryFriction;
  return r;
}

namespace {

/// The problem's size, the twist at rated torque and the flank carrying the most there, the three segments.
void print_contact_headline(const Case& c, const ContactAnalysis& a, const std::string& teeth_source) {
  const TorqueStep& r = a.steps.back();
  std::size_t top = 0;  // the flank carrying the largest force at +rated, where it is and what touches
  for (std::size_t i = 0; i < a.flanks.size(); ++i)
    if (r.flank_force_N[i] > r.flank_force_N[top]) top = i;
  const FlankContact& tf = a.flanks[top];
  std::printf("contact %s: %d contacts (%zu flanks%s, generator: %s, locked at %.4g deg from a tooth on the major "
              "axis), %zu torque steps in %.2f s (influence %.2f s)\n",
              c.path.c_str(), a.unknowns, a.flanks.size(), a.half_turn_pairs ? " × 2 teeth" : "",
              a.generator_support.c_str(), c.contact.generator_angle_rad * 180 / std::numbers::pi, a.steps.size(),
              a.contact_s, a.influence_s);
  const char* unit = a.face_slices > 1 ? "flank slices" : "flanks";
  std::printf("  twist at rated torque %.4g N·m: %.3f arcmin; %d %s in contact, largest force on one %.1f N at "
              "%.1f deg (the flexspline's %s on the circular spline's %s); teeth: %s\n", a.rated_torque_Nm,
              r.twist_rad * kArcmin, r.pairs_in_contact, unit, r.max_pair_force_N, tf.phi_rad * 180 / std::numbers::pi,
              part_name(tf.part_f), part_name(tf.part_c), teeth_source.c_str());
  std::printf("  three segments (%s): T1 %.3g N·m, T2 %.3g N·m, K1 %.4g, K2 %.4g, K3 %.4g N·m/rad\n",
              a.catalog.breakpoints_fitted ? "breakpoints fitted" : "the catalog's breakpoints", a.catalog.t1_Nm,
              a.catalog.t2_Nm, a.catalog.k1_Nm_per_rad, a.catalog.k2_Nm_per_rad, a.catalog.k3_Nm_per_rad);
  // Straight teeth on the coned rim first touch at a face end along a length that grows with the load: the sections
  // resolve the twist at rated torque from 5 (3 leave it 5–7 % low), the start of the curve from about 12
  // (contact/README.md, How many sections: on the designed size 17, 3 sections put K1 some 40 % above 16's and the
  // lost motion 35–45 % below).
  if (face_slices_leave_k1_unresolved(a.face_slices))
    std::printf("  the face in %d sections: the curve below T1 (K1, lost motion) is not resolved along the face, "
                "which takes about %d ([contact] face_slices)\n", a.face_slices, kFaceSlicesResolvingK1);
}

/// The computed curve against the catalog's law of the case's size.
void print_against_catalog(const ContactAnalysis& a, const CatalogLaw& reference) {
  const SegmentLaw catalog = reference.law();
  const auto law = [&](double T) { return catalog.twist_rad(T); };
  // A catalog row without K3 (ratio 50) gives no twist beyond T2: "not listed".
  const auto listed = [](double v, const char* format) {
    char b[32];
    if (!(std::isfinite(v) && v > 0)) return std::string("not listed");
    std::snprintf(b, sizeof b, format, v);
    return std::string(b);
  };
  std::printf("  against catalog size %d at ratio %d: twist at T1 %.3g N·m %.3f vs %.3f arcmin, at T2 %.3g N·m %.3f "
              "vs %.3f arcmin, at rated %.4g N·m %.3f vs %s arcmin (computed vs catalog); K1/K2/K3 %.3g/%.3g/%.3g "
              "vs %.3g/%.3g/%s N·m/rad\n",
              reference.size, reference.ratio, reference.t1_Nm, twist_at(a.curve, reference.t1_Nm) * kArcmin,
              law(reference.t1_Nm) * kArcmin, reference.t2_Nm, twist_at(a.curve, reference.t2_Nm) * kArcmin,
              law(reference.t2_Nm) * kArcmin, a.rated_torque_Nm, a.curve.twist_rad.back() * kArcmin,
              listed(law(a.rated_torque_Nm) * kArcmin, "%.3f").c_str(), a.catalog.k1_Nm_per_rad,
              a.catalog.k2_Nm_per_rad, a.catalog.k3_Nm_per_rad, reference.k1_Nm_per_rad, reference.k2_Nm_per_rad,
              listed(reference.k3_Nm_per_rad, "%.3g").c_str());
}

/// Lost motion and play, and what the twist at rated torque is made of.
void print_lost_motion_and_split(const Case& c, const ContactAnalysis& a) {
  std::printf("  lost motion (twist between ±4 %% of rated, middle line) %.3f arcmin; play (dead band at zero torque) "
              "%.3f arcmin\n", a.lost_motion_rad * kArcmin, a.play_rad * kArcmin);
  // The split reads the tangent at rated torque: its intercept is what the pairs' engagement adds (play taken up,
  // pairs closing one after another); it is negative when the curve softens toward rated torque (the tangent's slope
  // in twist per torque above the secant's), and then says so instead of naming a negative engagement.
  const std::string mounting = c.circular_spline ? " (" + to_string(c.circular_spline->mounting) + ")" : "";
  std::printf("  twist at rated, along the tangent there: body %.1f %% (toothed rim %.1f, wall %.1f, diaphragm %.1f, "
              "boss %.1f), teeth %.1f %%, generator %.1f %% (%s), circular spline%s %.1f %%; the tangent's "
              "intercept %.1f %% (%s)\n", 100 * a.split.body, 100 * a.split.rim, 100 * a.split.wall,
              100 * a.split.diaphragm, 100 * a.split.boss, 100 * a.split.teeth, 100 * a.split.generator,
              generator_share_meaning(a.split.generator).c_str(), mounting.c_str(), 100 * a.split.circular_spline,
              100 * a.split.engagement,
              a.split.engagement >= 0 ? "engagement: play taken up and pairs closing one after another"
                                      : "below the origin: the curve softens toward rated torque");
}

/// The split of the twist at rated torque in arcmin, beside the catalog's twist there (when its row lists K3): what
/// each part holds, and how much more (or less) the catalog's twist is.
void print_split_against_catalog(const ContactAnalysis& a, const CatalogLaw& reference) {
  const double catalog_rad = reference.law().twist_rad(a.rated_torque_Nm);
  if (!(std::isfinite(catalog_rad) && catalog_rad > 0)) return;  // a row without K3 (ratio 50)
  const double model_rad = a.curve.twist_rad.back();
  const auto arcmin = [&](double share) { return share * model_rad * kArcmin; };
  const double short_rad = catalog_rad - model_rad;
  std::printf("  beside the catalog's twist at rated (%.3f arcmin): body %.3f, teeth %.3f, generator %.3f, circular "
              "spline %.3f, engagement %.3f arcmin, the model's %.3f; the catalog's is %.3f arcmin (%.1f %%) %s\n",
              catalog_rad * kArcmin, arcmin(a.split.body), arcmin(a.split.teeth), arcmin(a.split.generator),
              arcmin(a.split.circular_spline), arcmin(a.split.engagement), model_rad * kArcmin,
              std::abs(short_rad) * kArcmin, 100 * std::abs(short_rad) / catalog_rad,
              short_rad >= 0 ? "more, in no part of the model" : "less");
}

/// Whether the mesh zones' edges hold under load: the last engaged tooth, the flanks beyond the tip circle, the
/// nearest tooth left out.
void print_zone_edges_hold(const ContactAnalysis& a) {
  // The zone's edge: the loaded edge tooth with the least radial overlap left, the free one that comes closest.
  const EdgeTooth* held = nullptr;
  const EdgeTooth* free = nullptr;
  int beyond = 0, beyond_loaded = 0;
  for (const EdgeTooth& e : a.edges) {
    if (e.engaged && (!held || e.overlap_min_m < held->overlap_min_m)) held = &e;
    if (!e.candidate && (!free || e.overlap_max_m > free->overlap_max_m)) free = &e;
  }
  for (std::size_t i = 0; i < a.flanks.size(); ++i)
    if (a.flanks[i].beyond_tip_circle) {
      ++beyond;
      beyond_loaded += a.steps.front().flank_force_N[i] > 0 || a.steps.back().flank_force_N[i] > 0;
    }
  std::string line = a.zone_edges_hold ? "  mesh-zone edges hold under load:" : "  WARNING: a mesh-zone edge moves under load:";
  char buf[256];
  if (held) {
    std::snprintf(buf, sizeof buf, " the last engaged tooth (%.1f deg) keeps %.2f of its %.2f µm radial overlap%s;",
                  held->phi_rad * 180 / std::numbers::pi, held->overlap_min_m * 1e6, held->overlap_at_rest_m * 1e6,
                  held->slips ? " and loses it while loaded (its tip would slip over the circular spline's tip)" : "");
    line += buf;
  }
  if (beyond > 0) {
    std::snprintf(buf, sizeof buf, " %d flanks short of the circular spline's tip circle at rest take part, %d loaded at "
                  "±rated;", beyond, beyond_loaded);
    line += buf;
  }
  if (free) {
    std::snprintf(buf, sizeof buf, " the nearest tooth left out (%.1f deg) stays %.2f µm clear of the circular spline's tip circle%s",
                  free->phi_rad * 180 / std::numbers::pi, -free->overlap_max_m * 1e6,
                  free->enters ? " (negative: it comes into mesh)" : "");
    line += buf;
  }
  std::printf("%s\n", line.c_str());
}

/// What the curve rests on at the edges: teeth engaged a few µm deep, touching at their tips.
void print_edge_teeth_share(const Case& c, const ContactAnalysis& a) {
  const double without = a.twist_at_rated_without_edge_teeth_rad, with = a.curve.twist_rad.back();
  char rest[96] = "not defined (no other flank carries it)";
  if (std::isfinite(without))
    std::snprintf(rest, sizeof rest, "%.3f arcmin (%+.1f %%)", without * kArcmin, 100 * (without / with - 1));
  const bool sharp = c.gear->tip_rounding_flexspline_m == 0 && c.gear->tip_rounding_circular_m == 0;
  std::printf("  the teeth within two pitches of the zones' edges carry %.1f %% of the rated torque%s; without them "
              "the twist at rated torque is %s\n", 100 * a.edge_teeth_torque_share,
              sharp ? " on sharp tip corners (real tips are rounded: design --tip-rounding-per-m cuts the teeth "
                      "with rounded corners, [gear] tip_rounding_flexspline_mm and tip_rounding_circular_mm round them "
                      "as cut)"
                    : "",
              rest);
}

/// The cup's coning across the face: the rim's deflection and the teeth's clearance at the ends and the centre.
void print_coning(const ContactAnalysis& a) {
  const FaceSection *d = &a.face_sections[0], *m = &a.face_sections[1], *o = &a.face_sections[2];
  auto closing = [](const FaceSection& f) {
    char b[64];
    if (f.overlap_m > 0)
      std::snprintf(b, sizeof b, "overlap %.2f µm (%.1f deg)", f.overlap_m * 1e6, f.overlap_phi_rad * 180 / std::numbers::pi);
    else std::snprintf(b, sizeof b, "first flank closes at %.3f arcmin", f.first_closing_rad * kArcmin);
    return std::string(b);
  };
  std::printf("  coning across the face (diaphragm end / centre / open end): the rim's radial deflection at the major "
              "axis %.1f / %.1f / %.1f µm; at rest %s / %s / %s; %s\n", d->w_major_m * 1e6, m->w_major_m * 1e6,
              o->w_major_m * 1e6, closing(*d).c_str(), closing(*m).c_str(), closing(*o).c_str(),
              a.face_slices > 1
                  ? ("the contact meshes straight teeth in " + std::to_string(a.face_slices) +
                     " sections across the face (its ends and evenly between)").c_str()
                  : "the contact takes the teeth as relieved along the face for it (every section meshing as the "
                    "centre; [contact] face_slices meshes straight teeth)");
}

/// A warning for teeth overlapping at rest, and the torque balance.
void print_overlap_and_balance(const ContactAnalysis& a) {
  if (a.overlap_at_rest_m > 0)
    std::printf("  WARNING: the teeth overlap at rest by %.2f µm on the FEM's neutral curve, so part of the curve above is a "
                "preload from that interference, not a property of the drive; remove the interference first (the "
                "backlash stage's geometry check gives the remedy)\n", a.overlap_at_rest_m * 1e6);
  std::printf("  torque balance: flank moments vs torque %.1e (relative, worst step); clamp reaction in a direct FEM "
              "solve %.6g N·m vs %.6g N·m\n", a.torque_balance_error_rel, a.fem_reaction_torque_Nm, a.rated_torque_Nm);
  if (a.circular_spline_torque_Nm != 0)
    std::printf("  the circular spline's mounting carries %.6g N·m in a direct solve of its ring: the flanks' torque, the "
                "output's less the locked generator's share\n", a.circular_spline_torque_Nm);
}

/// The band over drives of one tolerance class: each figure's smallest, median and largest.
void print_accuracy_band(const ContactResult::AccuracyBand& b) {
  const auto of = [](const Spread& s, const char* format) {
    char buf[96];
    std::snprintf(buf, sizeof buf, format, s.min, s.median, s.max);
    return std::string(buf);
  };
  std::printf("  over %d drives of %s class %d (teeth placed within ±f_pT/2: f_pT %.2f µm flexspline, %.2f µm circular "
              "spline%s; runout, profile and helix deviations left out), smallest / median / largest: K1 %s, K2 %s, "
              "K3 %s N·m/rad; twist at rated %s arcmin; lost motion %s arcmin; play %s arcmin; preload at rest %s µm%s\n",
              b.drives, b.standard.c_str(), b.tolerance_class, b.single_pitch_tolerance_flexspline_um,
              b.single_pitch_tolerance_circular_spline_um,
              b.outside_scope ? ("; " + *b.outside_scope).c_str() : "", of(b.K1_Nm_per_rad, "%.3g/%.3g/%.3g").c_str(),
              of(b.K2_Nm_per_rad, "%.3g/%.3g/%.3g").c_str(), of(b.K3_Nm_per_rad, "%.3g/%.3g/%.3g").c_str(),
              of(b.twist_at_rated_arcmin, "%.3f/%.3f/%.3f").c_str(), of(b.lost_motion_arcmin, "%.3f/%.3f/%.3f").c_str(),
              of(b.play_arcmin, "%.3f/%.3f/%.3f").c_str(), of(b.preload_overlap_at_rest_um, "%.2f/%.2f/%.2f").c_str(),
              b.hysteresis_loss_arcmin
                  ? ("; hysteresis loss from the flanks' friction " +
                     of(*b.hysteresis_loss_arcmin, "%.3f/%.3f/%.3f") + " arcmin").c_str()
                  : "");
}

}  // namespace

std::unique_ptr<ContactBody> contact_body(const Case& c, const FemJobResult& fem, const Eigen::VectorXd* fem_u) {
  if (fem.harmonic) return std::make_unique<HarmonicBody>(flexspline_model(c), *fem.harmonic);
  if (!fem.mesh || !fem.system) throw std::logic_error("contact: the FEM job left no model to solve on");
  return std::make_unique<Tet10Body>(flexspline_model(c), *fem.mesh, *fem.system, fem_u);
}

ContactAnalysis run_contact_job(const Case& c, const ContactBody& body, const FemReadout& fem, OutputSet& out,
                                const ContactJobOptions& job) {
  const ContactOptions o = contact_options(c, series_parts(c));
  const std::optional<CatalogLaw> reference = catalog_reference(c);
  const ContactAnalysis a =
      naming_file(c.path, [&] { return analyse_contact(flexspline_model(c), body, fem, o); });
  ContactResult result = contact_result(a, c, reference);
  std::optional<AccuracyBand> band;
  if (job.accuracy_class > 0) {
    band = naming_file(c.path, [&] {
      return accuracy_band(flexspline_model(c), body, fem, o, job.accuracy_class, job.accuracy_drives);
    });
    result.accuracy_band = accuracy_band_figures(*band);
  }
  out.own(kContactJobFiles);
  write_file_atomic(out.staging() / "contact.json", contact_json(result));
  write_file_atomic(out.staging() / "torque_twist.csv", torque_twist_csv(a));
  write_file_atomic(out.staging() / "contact.svg", contact_svg(a, reference));
  print_contact_headline(c, a, o.series.teeth_source);
  if (reference) print_against_catalog(a, *reference);
  print_lost_motion_and_split(c, a);
  if (reference) print_split_against_catalog(a, *reference);
  if (a.friction) {
    const FrictionLoop& f = *a.friction;
    std::printf("  friction on the flanks (mu = %g): hysteresis loss %.3f arcmin as a rig reads it (the output's place "
                "on returning to zero torque from +rated less that from -rated: the flanks' friction %.3f, the dead "
                "band the branches cross there %.3f); the loop is widest at %.4g N m, %.3f arcmin; loop area %.4g J = "
                "friction work %.4g J per cycle; steady after %d cycle%s of %d steps a quarter; lost motion and the "
                "three segments above read on the loop's middle line\n",
                f.friction_coefficient, f.rig_hysteresis_loss_rad * kArcmin, f.hysteresis_loss_rad * kArcmin,
                f.zero_torque_dead_band_rad() * kArcmin, f.widest.torque_Nm, f.widest.width_rad * kArcmin,
                f.dissipated_energy_J, f.friction_work_J, f.cycles, f.cycles == 1 ? "" : "s", f.steps_per_quarter);
  }
  if (!a.edges.empty()) {
    print_zone_edges_hold(a);
    print_edge_teeth_share(c, a);
  }
  if (a.face_sections.size() == 3) print_coning(a);
  print_overlap_and_balance(a);
  if (result.accuracy_band) print_accuracy_band(*result.accuracy_band);
  return a;
}

}  // namespace sw::app
