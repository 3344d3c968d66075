#include "datasheet/datasheet.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <numbers>

#include "common/constants.hpp"
#include "design/catalog.hpp"

namespace sw {
namespace {


std::string fmt(const char* f, double v) {
  char buf[64];
  std::snprintf(buf, sizeof buf, f, v);
  return buf;
}

DatasheetFigure computed(std::string name, std::string label, std::string unit, double value, std::string method) {
  return {std::move(name), std::move(label), std::move(unit), value, std::move(method), std::nullopt, ""};
}
DatasheetFigure not_computed(std::string name, std::string label, std::string unit, std::string why) {
  return {std::move(name), std::move(label), std::move(unit), std::nullopt, std::move(why), std::nullopt, ""};
}

void publish(DatasheetFigure& f, double value, std::string source) {
  if (value <= 0) return;  // the reference lists none
  f.published = value;
  f.published_source = std::move(source);
}

/// The stiffness, twist and loss figures of the loaded contact.
void add_contact_figures(Datasheet& d, const DatasheetInputs& in) {
  const ContactAnalysis& a = *in.contact;
  const std::string law = a.catalog.breakpoints_fitted ? "breakpoints fitted to the curve"
                                                       : "at the catalog's breakpoints T1, T2";
  const std::string curve = "the loaded contact's torque-twist curve, wave generator locked, 0 to rated torque (" +
                            a.solver + " flexspline body, tooth pairs, generator bearing and circular spline in series)";
  d.figures.push_back(computed("T1_Nm", "T1", "N·m", a.catalog.t1_Nm, "breakpoint of the three-segment law, " + law));
  d.figures.push_back(computed("T2_Nm", "T2", "N·m", a.catalog.t2_Nm, "breakpoint of the three-segment law, " + law));
  d.figures.push_back(computed("K1_Nm_per_rad", "K1", "N·m/rad", a.catalog.k1_Nm_per_rad, "secant 0..T1 of " + curve));
  d.figures.push_back(computed("K2_Nm_per_rad", "K2", "N·m/rad", a.catalog.k2_Nm_per_rad, "secant T1..T2 of the same"));
  d.figures.push_back(computed("K3_Nm_per_rad", "K3", "N·m/rad", a.catalog.k3_Nm_per_rad, "secant T2..rated of the same"));
  const double lost = a.friction ? a.friction->lost_motion_rad : a.lost_motion_rad;
  d.figures.push_back(computed("lost_motion_arcmin", "lost motion", "arcmin", lost * kArcmin,
                               "twist between ±4 % of rated torque on the loop's middle line (play and elastic twist)"));
  d.figures.push_back(computed("play_arcmin", "play (dead band)", "arcmin", a.play_rad * kArcmin,
                               "the curve's jump at zero torque: the teeth's clearance at the locked generator"));
  if (a.friction) {
    const FrictionLoop& f = *a.friction;
    d.figures.push_back(computed(
        "hysteresis_loss_arcmin", "hysteresis loss", "arcmin", f.rig_hysteresis_loss_rad * kArcmin,
        "the output's place on returning to zero torque from +rated less that from −rated, the steady loop ±rated "
        "as a rig reads it (its output stays where it arrives), Coulomb μ = " +
            fmt("%.3g", f.friction_coefficient) + " on the flanks: the flanks' friction " +
            fmt("%.3f", f.hysteresis_loss_rad * kArcmin) + " arcmin (the branches apart in the middle of their dead "
            "bands) and the dead band the branches cross at zero torque " + fmt("%.3f", f.zero_torque_dead_band_rad() * kArcmin) +
            " arcmin (clearance, not friction)" +
            "; the loop is widest at " + fmt("%.4g", f.widest.torque_Nm) + " N·m, " +
            fmt("%.3f", f.widest.width_rad * kArcmin) + " arcmin"));
  } else {
    d.figures.push_back(not_computed("hysteresis_loss_arcmin", "hysteresis loss", "arcmin",
                                     "not computed: the case gives no flank friction ([contact] friction_coefficient)"));
  }
}

/// The flexspline's first yield: the torque at which its largest von Mises stress over a revolution reaches R_e.
void add_first_yield_figure(Datasheet& d, const DatasheetInputs& in) {
  if (!in.first_yield) {
    d.figures.push_back(not_computed("first_yield_torque_Nm", "torque at first yield (flexspline)", "N·m",
                                     in.why_no_yield));
    return;
  }
  const FirstYield& y = *in.first_yield;
  std::string method = "the largest von Mises stress of the flexspline body over a generator revolution (harmonic "
                       "solution, the generator's bending plus the torque's stresses, at each instant) reaching the "
                       "yield strength, at " + y.at_yield.place + " r = " + fmt("%.2f", y.at_yield.r_m * 1e3) +
                       " mm, z = " + fmt("%.2f", y.at_yield.z_m * 1e3) + " mm; the generator alone " +
                       fmt("%.0f", y.at_zero.von_mises_Pa / 1e6) +
                       " MPa; the rim without its teeth and the clamp's corner left out, as for the fatigue";
  if (y.torque_Nm == 0) method = "0: the generator's bending alone reaches the yield strength (" + method + ")";
  d.figures.push_back(computed("first_yield_torque_Nm", "torque at first yield (flexspline)", "N·m", y.torque_Nm,
                               method));
}

/// The ratcheting torque from the loaded contact's ramp past rated torque (contact/ratcheting.hpp), with where the last
/// teeth held and what parted them.
void add_ratcheting_figure(Datasheet& d, const DatasheetInputs& in) {
  const char* name = "ratcheting_torque_Nm";
  const char* label = "ratcheting torque";
  if (!in.contact || !in.contact->ratcheting) {
    d.figures.push_back(not_computed(name, label, "N·m", "not computed: the loaded contact is not at hand"));
    return;
  }
  const Ratcheting& r = *in.contact->ratcheting;
  const int sections = in.contact->face_slices;
  const auto where = [&](int slice) -> std::string {  // the face's section a tooth let go or held in
    if (sections <= 1) return "";
    if (slice == 0) return ", at the face's closed end";
    if (slice == sections - 1) return ", at the face's open end";
    return ", face section " + std::to_string(slice + 1) + " of " + std::to_string(sections);
  };
  const std::string how =
      "generator locked, torque raised past rated until the teeth still overlapping the circular spline's tip circle "
      "cannot carry it; each tooth lets go (in each section of the face on its own) when the rim's inward and the "
      "ring's outward give under the flanks' radial forces take its overlap; the contacts climb as the teeth part (each "
      "flank closed where the parting leaves it, its force turned with the contact's normal, the parting iterated to "
      "its fixed point), each load kept at its point of application at rest, a released tooth stays out";
  const double deg = 180 / std::numbers::pi;
  if (!std::isfinite(r.torque_Nm)) {  // a lower bound: beyond the search
    d.figures.push_back(computed(name, label, "N·m", r.torque_Nm,
                                 "above " + fmt("%.0f", r.ceiling_Nm) + " N·m: not reached where the search stops; " +
                                     how));
    return;
  }
  if (r.torque_Nm == 0) {
    d.figures.push_back(computed(name, label, "N·m", 0.0,
                                 "0: the teeth still overlapping do not hold a thousandth of rated torque; " + how));
    return;
  }
  std::string method = how + "; ±" + fmt("%.1g", 100 * r.tolerance_rel) + " %. First loaded tooth to let go at " +
                       fmt("%.3g", r.first_release_Nm) + " N·m (" + fmt("%.1f", r.first_phi_rad * deg) +
                       " deg from the major axis" + where(r.first_slice) + "); just below, " +
                       std::to_string(r.teeth_holding) + (sections > 1 ? " tooth sections" : " teeth") +
                       " hold, the last at " + fmt("%.1f", r.last_phi_rad * deg) + " deg" + where(r.last_slice) +
                       " with " +
                       fmt("%.2f", r.last_overlap_m * 1e6) + " um of overlap left, its tip parted " +
                       fmt("%.1f", r.last_rim_in_m * 1e6) + " um by the rim and " +
                       fmt("%.1f", r.last_ring_out_m * 1e6) + " um by the ring";
  if (!r.last_contact.empty())
    method += ", touching " + r.last_contact + " with its normal turned " + fmt("%.1f", r.last_normal_turn_rad * deg) +
              " deg from rest";
  d.figures.push_back(computed(name, label, "N·m", r.torque_Nm, method));
}

void add_limit_figures(Datasheet& d, const DatasheetInputs& in) {
  if (in.buckling)
    d.figures.push_back(computed("buckling_torque_Nm", "buckling torque", "N·m", in.buckling->torque_Nm,
                                 in.buckling->method));
  else
    d.figures.push_back(not_computed("buckling_torque_Nm", "buckling torque", "N·m", in.why_no_buckling));
  add_ratcheting_figure(d, in);
  if (in.infinite_life) {
    const InfiniteLife& l = *in.infinite_life;
    const FatigueState& w = l.at_limit;
    std::string method = "flexspline body: Sines' criterion with Goodman's line over one generator revolution (harmonic "
                         "solution, the generator's bending plus the torque's stresses), worst point " + w.place +
                         " at r = " + fmt("%.2f", w.r_m * 1e3) + " mm, z = " + fmt("%.2f", w.z_m * 1e3) +
                         " mm; safety factor with the generator alone " + fmt("%.2f", l.at_zero.safety_factor);
    if (l.torque_Nm == 0) method = "0: the generator's bending alone exceeds the fatigue limit (" + method + ")";
    d.figures.push_back(computed("infinite_life_torque_Nm", "torque for infinite life (flexspline)", "N·m",
                                 l.torque_Nm, method));
  } else {
    d.figures.push_back(
        not_computed("infinite_life_torque_Nm", "torque for infinite life (flexspline)", "N·m", in.why_no_infinite_life));
  }
  if (in.tooth_root)
    d.figures.push_back(computed("tooth_root_limit_Nm", "torque at the teeth's root limit", "N·m",
                                 in.tooth_root->torque_Nm, in.tooth_root->method));
  else
    d.figures.push_back(
        not_computed("tooth_root_limit_Nm", "torque at the teeth's root limit", "N·m", in.why_no_tooth_root));
  add_first_yield_figure(d, in);
  // The momentary limit: the first of yield, ratcheting and buckling, those computed; an upper bound when one is not.
  struct Limit {
    const char* name;
    const char* what;
  };
  double limit = std::numeric_limits<double>::infinity();
  std::string first, missing;
  for (const Limit& l : {Limit{"first_yield_torque_Nm", "yield"}, Limit{"ratcheting_torque_Nm", "ratcheting"},
                         Limit{"buckling_torque_Nm", "buckling"}}) {
    const DatasheetFigure* f = d.find(l.name);
    if (!f || !f->value) {
      missing += (missing.empty() ? "" : " and ") + std::string(l.what);
      continue;
    }
    if (*f->value < limit) {
      limit = *f->value;
      first = l.what;
    }
  }
  if (first.empty()) {
    d.figures.push_back(not_computed("momentary_limit_Nm", "momentary limit", "N·m",
                                     "not computed: the first of yield, ratcheting and buckling, none of them computed"));
    return;
  }
  std::string method = "the first of yield, ratcheting and buckling: " + first;
  if (!missing.empty()) method += "; " + missing + " not computed, so an upper bound";
  d.figures.push_back(computed("momentary_limit_Nm", "momentary limit", "N·m", limit, method));
}

void add_life_figures(Datasheet& d, const DatasheetInputs& in) {
  if (in.bearing) {
    d.figures.push_back(computed("bearing_life_L10_h", "generator bearing L10", "h", in.bearing->l10_h,
                                 in.bearing->method));
    d.figures.push_back(computed("bearing_life_exponent", "life exponent against torque", "", in.bearing->life_exponent,
                                 "−d ln L10 / d ln T between half and full rated torque (the catalog's scaling takes 3)"));
  } else {
    d.figures.push_back(not_computed("bearing_life_L10_h", "generator bearing L10", "h", in.why_no_bearing));
  }
}

/// Where the power goes: the efficiency and the input's torques from the generator bearing's friction and the flanks'
/// sliding (datasheet/losses.hpp), each figure saying what it counts and what it leaves out.
void add_loss_figures(Datasheet& d, const DatasheetInputs& in) {
  if (!in.losses) {
    d.figures.push_back(not_computed("efficiency", "efficiency (rated torque, 2,000 rpm)", "", in.why_no_losses));
    d.figures.push_back(not_computed("no_load_running_torque_Nm", "no-load running torque (input, 2,000 rpm)", "N·m",
                                     in.why_no_losses));
    d.figures.push_back(not_computed("starting_torque_Nm", "starting torque (input)", "N·m", in.why_no_losses));
    d.figures.push_back(not_computed("backdriving_torque_Nm", "backdriving torque (output)", "N·m", in.why_no_losses));
  } else {
    const LossFigures& l = *in.losses;
    const std::string damping = "the flexspline's material damping under the generator's wave (loss factor " +
                                fmt("%.3g", l.loss_factor) + " at small amplitude: " +
                                fmt("%.3g", l.damping_input_torque_Nm * 1e3) + " mN·m at the input, at any speed)";
    const std::string ring = l.ring_slip_input_torque_Nm > 0
                                 ? ", the generator's outer ring slipping on the bore as rim and ring bend together "
                                   "(boundary μ " + fmt("%.3g", l.ring_friction) + ", gross slip; " +
                                       fmt("%.3g", l.ring_slip_input_torque_Nm * 1e3) +
                                       " mN·m at the input with no load, at any speed)"
                                 : "";
    const std::string counts = "counts the generator bearing (Palmgren M0 + M1, balls loaded as the contact loads "
                               "them), the flanks' sliding (μ = " + fmt("%.3g", l.flank_friction) + ", " +
                               l.flank_friction_from + "), " + damping + ring + "; leaves out the lubricant's drag "
                               "beyond the bearing's f0 and seals, so it is an upper bound; " + l.lubricant;
    const auto split = [](const LossSplit& s) {
      return " (losses: bearing viscous " + fmt("%.3g", s.bearing_viscous_W) + " W, bearing load " +
             fmt("%.3g", s.bearing_load_W) + " W, flanks " + fmt("%.3g", s.flank_sliding_W) + " W, flexspline " +
             "damping " + fmt("%.3g", s.flexspline_damping_W) + " W, ring on the bore " +
             fmt("%.3g", s.ring_slip_W) + " W, of " + fmt("%.3g", s.input_power_W()) + " W in)";
    };
    d.loss_map = l.map;
    d.loss_map_counts = counts;
    d.figures.push_back(computed("efficiency", "efficiency (rated torque, 2,000 rpm)", "", l.rated_2000.efficiency(),
                                 "P_out/P_in; " + counts + split(l.rated_2000)));
    d.figures.push_back(computed("efficiency_1000rpm", "efficiency (rated torque, 1,000 rpm)", "",
                                 l.rated_1000.efficiency(), "as at 2,000 rpm" + split(l.rated_1000)));
    d.figures.push_back(computed("efficiency_half_rated", "efficiency (half rated torque, 2,000 rpm)", "",
                                 l.half_rated_2000.efficiency(), "as at rated torque" + split(l.half_rated_2000)));
    d.figures.push_back(computed("no_load_running_torque_Nm", "no-load running torque (input, 2,000 rpm)", "N·m",
                                 l.no_load_2000.input_torque_Nm(),
                                 "the generator bearing's friction under its own preload (the flanks carry no force "
                                 "at zero torque), " + damping + ring + "; the lubricant's drag beyond the bearing's "
                                 "f0 and seals left out" + split(l.no_load_2000)));
    d.figures.push_back(computed("starting_torque_Nm", "starting torque (input)", "N·m", l.starting_torque_Nm,
                                 "Palmgren's breakaway moment M1 of the generator bearing under its preload, " +
                                 damping + ring + ", the flanks' sliding where the teeth bear with no load (" +
                                 fmt("%.3g", l.flanks_at_rest_input_torque_Nm * 1e3) +
                                 " mN·m): a lower bound (the grease's yield stress, seals and stiction left out)"));
    if (!std::isfinite(l.backdriving_torque_Nm))
      d.figures.push_back(not_computed("backdriving_torque_Nm", "backdriving torque (output)", "N·m",
                                       "none: the flanks' sliding per output torque reaches 1/ratio, so the mesh locks "
                                       "itself against the output"));
    else
      d.figures.push_back(computed("backdriving_torque_Nm", "backdriving torque (output)", "N·m",
                                   l.backdriving_torque_Nm,
                                   "the output torque whose power at breakaway goes into the starting torque's "
                                   "breakaway at the input and the flanks' sliding (proportional to the torque, as "
                                   "at rated torque): ratio x starting torque / (1 - the flanks' share); a lower "
                                   "bound as the starting torque is"));
  }
}

/// The catalog's figures beside the computed ones, for the size and ratio the case names.
void add_published(Datasheet& d, const DatasheetInputs& in) {
  if (!in.catalog_size) return;
  const int size = *in.catalog_size;
  const std::string ratio_text = "ratio " + std::to_string(in.ratio);
  auto set = [&](const std::string& name, double value, const std::string& source) {
    for (DatasheetFigure& f : d.figures)
      if (f.name == name) publish(f, value, source);
  };
  if (const std::optional<CatalogDrive> row = catalog_stiffness(size, in.ratio)) {  // ratios 30, 50 and ≥ 80
    const std::string source = in.ratio >= 80 ? "CSF/CSG, ratio ≥ 80" : "CSF/CSG, " + ratio_text;
    set("T1_Nm", row->t1_Nm, source);
    set("T2_Nm", row->t2_Nm, source);
    set("K1_Nm_per_rad", row->k1_Nm_per_rad, source);
    set("K2_Nm_per_rad", row->k2_Nm_per_rad, source);
    set("K3_Nm_per_rad", row->k3_Nm_per_rad, source);  // not listed at ratio 50 (0: left empty)
    if (in.ratio == 100) set("rated_torque_Nm", row->rated_torque_Nm, "CSG, ratio 100");
  }
  if (const CatalogLimits* lim = catalog_limits(size)) {
    set("buckling_torque_Nm", lim->buckling_csf_Nm, "CSF (CSG " + fmt("%.0f", lim->buckling_csg_Nm) + ")");
    const double csf = lim->ratcheting_Nm(in.ratio, false), csg = lim->ratcheting_Nm(in.ratio, true);
    set("ratcheting_torque_Nm", csf, "CSF, " + ratio_text + (csg > 0 ? " (CSG " + fmt("%.0f", csg) + ")" : ""));
    if (in.ratio == 100) set("momentary_limit_Nm", lim->momentary_csg_Nm, "CSG, ratio 100");
    set("bearing_life_L10_h", lim->bearing_l10_csf_h,
        "CSF at rated torque, 2,000 rpm (CSG " + fmt("%.0f", lim->bearing_l10_csg_h) + ")");
    set("bearing_life_exponent", 3, "the catalog's scaling L ∝ (T_r/T)³");
    if (in.ratio == 100) {
      const std::string losses = "another maker's ratio-100 cup set, 20 °C, grease";
      set("efficiency", lim->efficiency, losses + " (rated torque, 2,000 rpm)");
      set("no_load_running_torque_Nm", lim->no_load_running_torque_Nm, losses);
      set("starting_torque_Nm", lim->starting_torque_Nm, losses);
      set("backdriving_torque_Nm", lim->backdriving_torque_Nm, losses);
    }
  }
}

}  // namespace

const DatasheetFigure* Datasheet::find(const std::string& name) const {
  for (const DatasheetFigure& f : figures)
    if (f.name == name) return &f;
  return nullptr;
}

Datasheet make_datasheet(const DatasheetInputs& in) {
  Datasheet d;
  d.catalog_size = in.catalog_size;
  d.ratio = in.ratio;
  d.figures.push_back(computed("rated_torque_Nm", "rated torque", "N·m", in.rated_torque_Nm,
                               "given: " + in.rated_torque_origin + " (the tool does not rate a drive)"));
  if (in.contact) add_contact_figures(d, in);
  add_limit_figures(d, in);
  add_life_figures(d, in);
  add_loss_figures(d, in);
  add_published(d, in);
  d.idealisations = {
      "the flexspline is linear elastic (small displacements) about the generator-deformed state; stresses superpose",
      "fatigue: a polished part at the material's fatigue limit (no surface, size or reliability factors); the teeth are "
      "the root check's, the clamp's singular corner is left out",
      "the loaded contact: Coulomb friction on the flanks only where the case gives μ; the teeth are ideal involutes "
      "(no pitch or profile deviations)",
  };
  return d;
}

}  // namespace sw
