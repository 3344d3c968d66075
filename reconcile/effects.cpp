#include "reconcile/effects.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <stdexcept>

#include "common/error.hpp"

namespace sw::reconcile {

namespace {

using Vec = Eigen::VectorXd;
using Mat = Eigen::MatrixXd;

/// The continuation of a generator's help over several lines.
const std::string kHelpMore = "\n                  ";

Mat column_matrix(const Vec& v) { return v; }
std::pair<Vec, Vec> no_bounds(const Experiment&) { return {Vec(0), Vec(0)}; }
std::pair<Vec, Vec> bounds1(double lo, double hi) { return {Vec::Constant(1, lo), Vec::Constant(1, hi)}; }

/// A linear effect with one column and one headline parameter: its coefficient.
EffectSpec linear_effect(const std::string& name, const std::string& physics, const std::string& parameter,
                         std::function<Vec(const Experiment&)> column) {
  return {.name = name,
          .physics = physics,
          .bounds = no_bounds,
          .columns = [column](const Experiment& e, const Vec&) { return column_matrix(column(e)); },
          .headline = [parameter](const Experiment&, const FitResult& f, int t) {
            return NamedValues{{parameter, f.terms[t].beta[0]}};
          }};
}

/// A generator of a linear effect: its column times the parameter asked for (or its default).
SynthGenerator linear_generator(const std::string& name, const std::string& parameter, const std::string& help,
                                std::function<Vec(const Experiment&)> column,
                                std::function<double(const Experiment&)> fallback) {
  return {name, {parameter}, help, false, ColumnLaw([=](const SynthEffect& fx, const Experiment& e) {
            SynthShape s;
            s.column = column(e);
            s.amplitude = synth_param(fx, parameter, fallback(e));
            s.truth = [parameter](double a) { return NamedValues{{parameter, a}}; };
            return s;
          })};
}


// ---- torsion ------------------------------------------------------------------------------------------------------

Effect series_compliance_effect() {
  auto torque = [](const Experiment& e) { return torsion(e).torque_Nm; };
  EffectSpec s = linear_effect(
      "series_compliance",
      "compliance in series with the flexspline body (tooth bending and contact, wave-generator bearing): the whole "
      "drive twists more per newton-metre than the flexspline alone",
      "compliance_rad_per_Nm", torque);
  return {s.name, Kind::Torsion, {s},
          {linear_generator(s.name, "compliance_rad_per_Nm", ":compliance_rad_per_Nm (0.25 C)", torque,
                            [](const Experiment& e) { return 0.25 * torsion(e).model.compliance_rad_per_Nm; })}};
}

/// Against a curve (the model's whole drive) a segment law's K's replace the curve's, and its last slope carries the
/// series compliance the model lacks (reconcile reports the two as this one law): what that means, or "".
std::string law_meaning(const Experiment& e, const FitResult& f, int breakpoints) {
  const TorsionExperiment& x = torsion(e);
  const double added = added_series_compliance(f), c_end = x.model.compliance_rad_per_Nm;
  if (!x.model.twist_rad || added == 0.0) return "";
  char buf[320];
  std::snprintf(buf, sizeof buf,
                "the drive's own law replaces the model's torque-twist curve: its last slope K%d %.4g N*m/rad is "
                "%.0f %% of the model's %.4g N*m/rad at the curve's ends (a series compliance of %.3g rad/(N*m) "
                "beside the model's, held in K%d, not a second effect)",
                breakpoints + 1, 1.0 / (c_end + added), 100.0 * c_end / (c_end + added), 1.0 / c_end, added,
                breakpoints + 1);
  return buf;
}

/// The catalog's segment law with one breakpoint (K1 up to T1, then K2) or two (K1, K2, K3). K of the last segment is
/// 1 / (C_tau + the series compliance effect): the law is of the whole drive, the catalog's form.
EffectSpec stiffness_variant(int breakpoints) {
  EffectSpec s;
  s.name = "stiffness_nonlinearity";
  s.order = breakpoints;
  s.label = s.name + (breakpoints == 2 ? " (three segments)" : " (two segments)");
  s.exclusive_variants = true;
  s.n_linear = breakpoints;
  s.physics = breakpoints == 1
                  ? "soft start of the torque-twist curve (progressive tooth engagement): below T1 the drive is "
                    "softer (catalog segment law with two slopes, K1 up to T1, then K2)"
                  : "stiffness that grows with torque as more teeth engage: the catalog's three-segment law (K1 up "
                    "to T1, K2 up to T2, K3 beyond)";
  s.nonlinear_names = breakpoints == 1 ? std::vector<std::string>{"T1_Nm"} : std::vector<std::string>{"T1_Nm", "T2_Nm"};
  s.bounds = [breakpoints](const Experiment& e) {
    const double a = torsion(e).torque_amplitude_Nm;
    // Below 0.08 A a breakpoint is a jump at zero torque: play's signature, not a soft start.
    if (breakpoints == 1) return bounds1(0.08 * a, 0.7 * a);
    // The two breakpoints enter symmetrically (the headline sorts them), so they share one range. Above 0.8 A the
    // last segment is too short to tell K3 from series compliance.
    return std::make_pair(Vec(Vec::Constant(2, 0.08 * a)), Vec(Vec::Constant(2, 0.8 * a)));
  };
  s.columns = [](const Experiment& e, const Vec& th) {
    Mat m(e.n, th.size());
    for (int j = 0; j < th.size(); ++j) m.col(j) = soft_start_column(torsion(e).torque_Nm, th[j]);
    return m;
  };
  s.headline = [breakpoints](const Experiment& e, const FitResult& f, int t) {
    const double c_last = torsion(e).model.compliance_rad_per_Nm + added_series_compliance(f);
    const Vec& b = f.terms[t].beta;
    const Vec& th = f.terms[t].theta;
    if (breakpoints == 1)
      return NamedValues{{"K1_Nm_per_rad", 1.0 / (c_last + b[0])}, {"T1_Nm", th[0]}, {"K2_Nm_per_rad", 1.0 / c_last}};
    // The two breakpoints enter symmetrically: T1 is the lower one.
    const int lo = th[0] <= th[1] ? 0 : 1, hi = 1 - lo;
    const double c2 = c_last + b[hi];
    return NamedValues{{"K1_Nm_per_rad", 1.0 / (c2 + b[lo])}, {"T1_Nm", th[lo]}, {"K2_Nm_per_rad", 1.0 / c2},
                       {"T2_Nm", th[hi]}, {"K3_Nm_per_rad", 1.0 / c_last}};
  };
  s.meaning = [breakpoints](const Experiment& e, const FitResult& f, int) { return law_meaning(e, f, breakpoints); };
  // The last slope is the baseline's own unless series compliance is in the model: read, not fitted.
  s.held = [breakpoints](const Experiment& e, const FitResult& f, int, const std::string& parameter) {
    const std::string last = breakpoints == 1 ? "K2_Nm_per_rad" : "K3_Nm_per_rad";
    if (parameter != last || f.find("series_compliance") >= 0) return std::string();
    return std::string(torsion(e).model.twist_rad ? "the torque-twist curve's slope at its ends"
                                                  : "1/C_tau, the baseline's compliance");
  };
  s.catalog = [](const Experiment& e, const FitResult& f, int i, CatalogReading& r) {
    const Term& t = f.terms[i];
    const NamedValues h = t.spec->headline(e, f, i);
    CatalogFigures& c = r.figures;
    c.segments = t.spec->order + 1;
    c.k1 = h[0].second;
    c.t1 = h[1].second;
    c.k2 = h[2].second;
    if (c.segments == 3) c.t2 = h[3].second;
    r.middle_twist_rad = [mid = r.middle_twist_rad, b = t.beta, th = t.theta](double T) {
      double v = mid(T);
      for (int j = 0; j < th.size(); ++j) v += b[j] * std::clamp(T, -th[j], th[j]);
      return v;
    };
  };
  return s;
}

/// The whole drive's law (catalog form: K1 up to T1, K2 up to T2, K3 beyond; two segments without T2) minus the
/// baseline C_tau T; a last slope other than 1/C_tau is series compliance, listed in the truth as implied. `rounded`
/// rounds each corner over width * T (tanh steps of the compliance): a structure the fitter's straight segments do not
/// have.
ColumnLaw stiffness_law(bool rounded) {
  return [rounded](const SynthEffect& fx, const Experiment& e) {
    const TorsionExperiment& t = torsion(e);
    const double A = t.torque_amplitude_Nm;
    const double C = t.model.compliance_rad_per_Nm;
    const bool three = fx.params.count("T2_Nm") > 0;
    const double t1 = synth_param(fx, "T1_Nm", 0.3 * A), t2 = three ? synth_param(fx, "T2_Nm", 0.0) : INFINITY;
    const double k1 = synth_param(fx, "K1_Nm_per_rad", 0.5 / C);
    const double k2 = synth_param(fx, "K2_Nm_per_rad", three ? 0.75 / C : 1.0 / C);
    const double k3 = three ? synth_param(fx, "K3_Nm_per_rad", 1.0 / C) : k2;
    if (!(t1 > 0.0) || (three && !(t2 > t1)) || !(k1 > 0.0) || !(k2 > 0.0) || !(k3 > 0.0))
      throw InputError("synth effect " + fx.name + ": expected 0 < T1_Nm < T2_Nm and K1, K2, K3 > 0");
    const double w = synth_param(fx, "width", 0.3);
    SynthShape s;
    s.column.resize(e.n);
    for (int i = 0; i < e.n; ++i) {
      const double T = t.torque_Nm[i];
      s.column[i] = (rounded ? rounded_segment_law_twist(T, k1, k2, k3, t1, t2, w)
                             : segment_law_twist(T, k1, k2, k3, t1, std::isfinite(t2) ? t2 : 1e300)) -
                    C * T;
    }
    s.amplitude = 1.0;  // a scale of every compliance step relative to C_tau
    s.implied = ImpliedEffect{"series_compliance", "compliance_rad_per_Nm", t.torque_Nm,
                              [k3, C](double a) { return a * (1.0 / k3 - C); }};
    s.truth = [=](double a) {
      auto K = [&](double k) { return 1.0 / (C + a * (1.0 / k - C)); };
      NamedValues v{{"K1_Nm_per_rad", K(k1)}, {"T1_Nm", t1}, {"K2_Nm_per_rad", K(k2)}};
      if (three) v.insert(v.end(), {{"T2_Nm", t2}, {"K3_Nm_per_rad", K(k3)}});
      if (rounded) v.emplace_back("corner_width", w);
      return v;
    };
    return s;
  };
}

Effect stiffness_effect() {
  const std::vector<std::string> keys{"K1_Nm_per_rad", "K2_Nm_per_rad", "K3_Nm_per_rad", "T1_Nm", "T2_Nm"};
  std::vector<std::string> rounded_keys = keys;
  rounded_keys.push_back("width");
  SynthGenerator law{"stiffness_nonlinearity", keys,
                     ":K1_Nm_per_rad (0.5/C),T1_Nm (0.3 A),K2_Nm_per_rad (1/C)" + kHelpMore +
                         "three segments with T2_Nm: K2 default 0.75/C, K3_Nm_per_rad (1/C); a last slope other than" +
                         kHelpMore + "1/C is series compliance, listed in the truth as implied",
                     true, stiffness_law(false)};
  SynthGenerator rounded{"stiffness_smooth", rounded_keys,
                         ": the same keys + width (0.3): corners rounded over width*T (other structure)", true,
                         stiffness_law(true)};
  return {"stiffness_nonlinearity", Kind::Torsion, {stiffness_variant(1), stiffness_variant(2)}, {law, rounded}};
}

/// Friction as one exponential (Dahl-type) branch transition, or two in parallel (a two-element slip model) when the
/// branches bend in a way one transition cannot follow (Bouc-Wen-like friction, several contact zones).
EffectSpec hysteresis_variant(int elements) {
  EffectSpec s;
  s.name = "hysteresis";
  s.order = elements;
  s.label = s.name + (elements == 2 ? " (two friction elements)" : " (one friction element)");
  s.exclusive_variants = true;
  s.n_linear = elements;
  s.physics = "friction in the tooth contacts: the loading branch lies below the unloading branch and the drive "
              "needs some torque after each reversal before it moves the other way";
  s.nonlinear_names = elements == 1 ? std::vector<std::string>{"transition_Nm"}
                                    : std::vector<std::string>{"transition_Nm", "transition2_Nm"};
  s.bounds = [elements](const Experiment& e) {
    return std::make_pair(Vec(Vec::Constant(elements, 0.005 * torsion(e).torque_amplitude_Nm)),
                          Vec(Vec::Constant(elements, 0.25 * torsion(e).torque_amplitude_Nm)));
  };
  s.columns = [](const Experiment& e, const Vec& th) {
    Mat m(e.n, th.size());
    for (int j = 0; j < th.size(); ++j) m.col(j) = hysteresis_column(torsion(e), th[j]);
    return m;
  };
  s.headline = [elements](const Experiment& e, const FitResult& f, int t) {
    const Vec& b = f.terms[t].beta;
    const Vec& th = f.terms[t].theta;
    double loss = 0.0;
    for (int j = 0; j < th.size(); ++j) loss += hysteresis_loss_rad(b[j], th[j], torsion(e).torque_amplitude_Nm);
    NamedValues v{{"loss_rad", loss}, {"loss_arcmin", loss * kArcmin}};
    if (elements == 1) {
      v.emplace_back("transition_Nm", th[0]);
    } else {
      const int lo = th[0] <= th[1] ? 0 : 1;
      v.emplace_back("transition_Nm", th[lo]);
      v.emplace_back("transition2_Nm", th[1 - lo]);
    }
    return v;
  };
  // A friction element dissipates: two elements fitted with losses of opposite sign are a difference of two nearly
  // equal columns (a derivative), not friction.
  s.implausible = [](const Experiment& e, const FitResult& f, int t) {
    const Term& term = f.terms[t];
    for (int j = 0; j < term.theta.size(); ++j)
      if (hysteresis_loss_rad(term.beta[j], term.theta[j], torsion(e).torque_amplitude_Nm) < 0.0)
        return std::string("a friction element would return energy (a negative loss): the two elements cancel "
                           "rather than describe friction");
    return std::string();
  };
  s.catalog = [](const Experiment&, const FitResult& f, int i, CatalogReading& r) {
    const Term& t = f.terms[i];
    const double R = r.figures.rated_torque_Nm;
    for (int j = 0; j < t.theta.size(); ++j) {
      const double h = t.beta[j], th = t.theta[j];
      r.figures.hysteresis_loss_arcmin += hysteresis_loss_rad(h, th, R) * kArcmin;
      r.middle_twist_rad = [mid = r.middle_twist_rad, h, th, R](double T) {
        return mid(T) + hysteresis_middle_twist(h, th, R, T);
      };
    }
  };
  return s;
}

/// Intervals of the gap profile's hats over [0, A]: fine enough to follow a loop whose width peaks between zero and
/// the amplitude (the preloaded size-17 drive's peaks near A/2), few enough that a gap saturating at once (one Dahl
/// element) keeps the cheaper law by BIC.
constexpr int kGapProfileIntervals = 8;

/// Friction whose branch gap changes along the torque, not as a transition after each reversal: the gap at every
/// eighth of the amplitude, linear between (gap_profile_columns). Its loss is read where the data are, at zero torque.
EffectSpec hysteresis_profile_variant() {
  EffectSpec s;
  s.name = "hysteresis";
  s.order = 3;
  s.label = s.name + " (branch gap varying with torque)";
  s.exclusive_variants = true;
  s.n_linear = kGapProfileIntervals;
  s.physics = "friction in the tooth contacts, the loop's width changing with the torque as flanks close, open, stick "
              "and slip: the loading branch lies below the unloading branch";
  s.bounds = no_bounds;
  s.columns = [](const Experiment& e, const Vec&) { return gap_profile_columns(torsion(e), kGapProfileIntervals); };
  s.headline = [](const Experiment&, const FitResult& f, int t) {
    const Vec& b = f.terms[t].beta;
    return NamedValues{{"loss_rad", b[0]}, {"loss_arcmin", b[0] * kArcmin},
                       {"widest_gap_arcmin", b.maxCoeff() * kArcmin}};
  };
  s.catalog = [](const Experiment&, const FitResult& f, int i, CatalogReading& r) {
    r.figures.hysteresis_loss_arcmin += f.terms[i].beta[0] * kArcmin;  // the middle line is unchanged
  };
  return s;
}

SynthShape hysteresis_shape(const SynthEffect& fx, const Experiment& e) {
  const TorsionExperiment& t = torsion(e);
  const double th = synth_param(fx, "transition_Nm", 0.05 * t.torque_amplitude_Nm);
  const double factor = hysteresis_loss_rad(1.0, th, t.torque_amplitude_Nm);
  SynthShape s;
  s.column = hysteresis_column(t, th) / factor;  // per unit of loss (gap at zero torque)
  s.amplitude = synth_param(fx, "loss_rad", 1e-4);
  s.truth = [th](double a) { return NamedValues{{"loss_rad", a}, {"transition_Nm", th}}; };
  return s;
}

/// Bouc-Wen friction (bouc_wen_column, n = 2 by default): the branch gap grows with amplitude and its shape is not
/// the fitter's exponential; scaled so the gap at zero torque is loss_rad.
SynthShape bouc_wen_shape(const SynthEffect& fx, const Experiment& e) {
  const TorsionExperiment& t = torsion(e);
  const double th = synth_param(fx, "transition_Nm", 0.05 * t.torque_amplitude_Nm), nexp = synth_param(fx, "n", 2.0);
  SynthShape s;
  s.column = bouc_wen_column(t.torque_Nm, th, nexp);
  s.amplitude = synth_param(fx, "loss_rad", 1e-4);
  s.truth = [th, nexp](double a) {
    return NamedValues{{"loss_rad", a}, {"bouc_wen_transition_Nm", th}, {"bouc_wen_n", nexp}};
  };
  return s;
}

Effect hysteresis_effect() {
  SynthGenerator law{"hysteresis", {"loss_rad", "transition_Nm"}, ":loss_rad (1e-4),transition_Nm (0.05 A)", false,
                     ColumnLaw(hysteresis_shape)};
  SynthGenerator bouc_wen{"friction_bouc_wen", {"loss_rad", "transition_Nm", "n"},
                          ":loss_rad (1e-4),transition_Nm (0.05 A),n (2): Bouc-Wen friction, the branch" + kHelpMore +
                              "gap grows with amplitude (other structure; named hysteresis in the truth)",
                          true, ColumnLaw(bouc_wen_shape)};
  return {"hysteresis", Kind::Torsion, {hysteresis_variant(1), hysteresis_variant(2), hysteresis_profile_variant()},
          {law, bouc_wen}};
}

std::string arcmin(double rad) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.3g arcmin", rad * kArcmin);
  return buf;
}

/// A fitted play against the baseline's own: more play in the drive than in the model, or less (a negative width
/// against a curve whose teeth leave a dead band), with the case key that sets the model's.
std::string play_meaning(const Experiment& e, const FitResult& f, int term) {
  const double w = f.terms[term].beta[0], model = baseline_play_rad(torsion(e));
  const std::string key = "the model's play is set by the tooth thickness: gear.profile_shift_circular against "
                          "gear.profile_shift_flexspline";
  if (model > 0.0 && w < 0.0)
    return "the model has " + arcmin(-w) + " more play than the drive (the model " + arcmin(model) +
           ", the drive about " + arcmin(std::max(model + w, 0.0)) + "); " + key;
  if (model > 0.0) return "the drive has " + arcmin(w) + " more play than the model (" + arcmin(model) + "); " + key;
  if (w < 0.0)
    return "a dead band of negative width (" + arcmin(w) + ") against a baseline without play is not play: the "
           "twist near zero torque bends the other way (another effect's shape there)";
  return "the drive has " + arcmin(w) + " of play the baseline does not hold";
}

Effect lost_motion_effect() {
  const EffectSpec s{
      .name = "lost_motion",
      .physics = "play between the teeth (or in the output coupling): the twist jumps while the torque crosses zero",
      .nonlinear_names = {"transition_Nm"},
      .bounds =
          [](const Experiment& e) {
            return bounds1(0.001 * torsion(e).torque_amplitude_Nm, 0.05 * torsion(e).torque_amplitude_Nm);
          },
      .columns =
          [](const Experiment& e, const Vec& th) { return column_matrix(lost_motion_column(torsion(e).torque_Nm, th[0])); },
      .headline =
          [](const Experiment&, const FitResult& f, int t) {
            return NamedValues{{"width_rad", f.terms[t].beta[0]},
                               {"width_arcmin", f.terms[t].beta[0] * kArcmin},
                               {"transition_Nm", f.terms[t].theta[0]}};
          },
      .meaning = play_meaning,
      .catalog =
          [](const Experiment&, const FitResult& f, int i, CatalogReading& r) {
            const double w = f.terms[i].beta[0], ts = f.terms[i].theta[0];
            r.figures.play_arcmin = w * kArcmin;
            r.middle_twist_rad = [mid = r.middle_twist_rad, w, ts](double T) {
              return mid(T) + w * lost_motion_twist(T, ts);
            };
          }};
  SynthGenerator law{"lost_motion", {"width_rad", "transition_Nm"}, ":width_rad (1e-4),transition_Nm (0.01 A)", false,
                     ColumnLaw([](const SynthEffect& fx, const Experiment& e) {
                       const TorsionExperiment& t = torsion(e);
                       const double ts = synth_param(fx, "transition_Nm", 0.01 * t.torque_amplitude_Nm);
                       SynthShape sh;
                       sh.column = lost_motion_column(t.torque_Nm, ts);
                       sh.amplitude = synth_param(fx, "width_rad", 1e-4);
                       sh.truth = [ts](double a) { return NamedValues{{"width_rad", a}, {"transition_Nm", ts}}; };
                       return sh;
                     })};
  return {s.name, Kind::Torsion, {s}, {law}};
}

// ---- harmonics of an angle (transmission, backlash) ----------------------------------------------------------------

/// synth's line of order k (SynthEffect::order) in an angle of the experiment (member `angle` of the kind's data K):
/// amplitude cos(k angle + phase).
template <class K>
ColumnLaw harmonic_law(Vec K::*angle, const std::string& unit, double default_amplitude) {
  return [=](const SynthEffect& fx, const Experiment& e) {
    const int k = fx.order;
    if (k < 1 || k > kMaxHarmonicOrder)
      throw InputError("synth effect " + fx.name + ": order = " + std::to_string(k) + "; expected 1.." +
                       std::to_string(kMaxHarmonicOrder));
    const double ph = synth_param(fx, "phase_rad", 0.3);
    SynthShape s;
    s.column = (k * (as<K>(e).*angle).array() + ph).cos();
    s.amplitude = synth_param(fx, "amplitude_" + unit, default_amplitude);
    s.truth = [k, ph, unit](double a) {
      return NamedValues{{"order", double(k)}, {"amplitude_" + unit, a}, {"phase_rad", ph}};
    };
    return s;
  };
}

/// A line locked to an angle of the experiment (member `angle` of the kind's data K), one variant per order 1 ..
/// kMaxHarmonicOrder: amplitude and phase in the response's unit.
template <class K>
Effect harmonic_effect(const std::string& name, Vec K::*angle, const std::string& unit, double default_amplitude,
                       const std::string& help, const std::function<std::string(int order)>& physics) {
  Effect effect{name, K::kind, {}, {}};
  for (int k = 1; k <= kMaxHarmonicOrder; ++k) {
    effect.variants.push_back(
        {.name = name,
         .order = k,
         .physics = physics(k),
         .label = name + " (order " + std::to_string(k) + ")",
         .n_linear = 2,
         .bounds = no_bounds,
         .columns = [k, angle](const Experiment& e, const Vec&) { return harmonic_columns(as<K>(e).*angle, k); },
         .headline =
             [unit](const Experiment&, const FitResult& f, int t) {
               const Vec& b = f.terms[t].beta;
               return NamedValues{{"order", double(f.terms[t].spec->order)},
                                  {"amplitude_" + unit, std::hypot(b[0], b[1])},
                                  {"phase_rad", std::atan2(-b[1], b[0])}};
             },
         .multiplicity = kMaxHarmonicOrder});
  }
  effect.generators.push_back({name, {"order", "amplitude_" + unit, "phase_rad"}, help, false,
                               harmonic_law(angle, unit, default_amplitude)});
  return effect;
}

std::vector<Effect> transmission_effects() {
  const std::string help = ":order=k,amplitude_rad (1e-5),phase_rad (0.3)";
  return {harmonic_effect("wg_harmonic", &TransmissionExperiment::wg_angle_rad, "rad", 1e-5, help,
                          [](int k) {
                            return k == 1 ? "kinematic error locked to the wave generator, once per revolution: "
                                            "eccentricity"
                                          : "kinematic error locked to the wave generator, order " + std::to_string(k) +
                                                (k == 2 ? ": ovality of the generator or the circular spline" : "");
                          }),
          harmonic_effect("output_harmonic", &TransmissionExperiment::output_angle_rad, "rad", 1e-5, help,
                          [](int k) {
                            return "error locked to the flexspline/output, order " + std::to_string(k) +
                                   " per output revolution (runout, accumulated pitch error)";
                          })};
}

// ---- backlash -----------------------------------------------------------------------------------------------------

std::vector<Effect> backlash_effects() {
  // The flexspline's rotation phi0 = C T closes the clearance on the loaded flanks by its arc at the pitch radius.
  auto torsion_arc = [](const Experiment& e) {
    const BacklashExperiment& b = as<BacklashExperiment>(e);
    return Vec(-b.pitch_radius_m * 1e6 * b.torque_Nm);  // um per (rad/Nm)
  };
  EffectSpec load = linear_effect("load_torsion",
                                  "the flexspline's torsional rotation under load (phi0 = C_tau * T) closes the "
                                  "clearance on the loaded flanks; the basic kinematic model assumes phi0 = 0",
                                  "compliance_rad_per_Nm", torsion_arc);
  auto ones = [](const Experiment& e) { return Vec(Vec::Ones(e.n)); };
  EffectSpec uniform = linear_effect(
      "uniform_clearance", "a clearance change everywhere (tooth thickness, centre distance, thermal growth)",
      "offset_um", ones);
  return {{load.name, Kind::Backlash, {load},
           {linear_generator(load.name, "compliance_rad_per_Nm", ":compliance_rad_per_Nm (2e-5)", torsion_arc,
                             [](const Experiment&) { return 2e-5; })}},
          harmonic_effect("wg_harmonic", &BacklashExperiment::wg_angle_rad, "um", 1.0,
                          ":order=k,amplitude_um (1),phase_rad (0.3)",
                          [](int k) {
                            return "clearance modulated with the wave-generator angle, order " + std::to_string(k) +
                                   (k == 1 ? " (eccentric assembly)"
                                           : k == 2 ? " (ovality of generator or circular spline)" : "");
                          }),
          {uniform.name, Kind::Backlash, {uniform},
           {linear_generator(uniform.name, "offset_um", ":offset_um (1)", ones,
                             [](const Experiment&) { return 1.0; })}}};
}

// ---- dynamics -----------------------------------------------------------------------------------------------------


Effect mesh_stiffness_effect() {
  // The responses to r sin(psi) and r cos(psi) (the sensitivity columns at phase 0 and pi/2; k(t) is linear in
  // r cos(phi) and r sin(phi)), whole waveforms: on moving pairs the mesh has its own f_m content, so the
  // variation's response is not a pair of lines and its f_m line depends on phi. r from the coefficients' magnitude
  // through the calibration curve of runs at a few r (the response is far from linear in r on frozen pairs).
  // The columns' parts not locked to the mesh come with coefficients of their own (they carry the response's
  // transient part, not r).
  const EffectSpec s{
      .name = "mesh_stiffness_variation",
      .physics = "mesh stiffness that varies as teeth engage and disengage: k(t) = k0 (1 + r sin(2 pi f_m t + phi)), "
                 "a line at the mesh frequency f_m = z_f |n_f - n_w| / 60 in the meshing force",
      .n_linear = 4,
      .bounds = no_bounds,
      .columns =
          [](const Experiment& e, const Vec&) {
            Mat m(e.n, 4);
            m << dynamics(e).sensitivity.leftCols(2), dynamics(e).stiffness_unlocked;
            return m;
          },
      .headline =
          [](const Experiment& e, const FitResult& f, int t) {
            const DynamicsExperiment& d = dynamics(e);
            const Vec& b = f.terms[t].beta;
            const Vec contribution = d.sensitivity.leftCols(2) * b.head(2);
            const Vec line = mesh_lines(d).colPivHouseholderQr().solve(contribution);
            return NamedValues{{"amplitude_ratio", invert_calibration(d.calib_ratio, d.calib_stiffness_beta, 0.01,
                                                                      std::hypot(b[0], b[1]))},
                               {"frequency_Hz", d.model.mesh_frequency_Hz},
                               {"line_amplitude_N", std::hypot(line[0], line[1])},
                               {"phase_rad", std::atan2(b[1], b[0])}};
          },
      .held = [](const Experiment&, const FitResult&, int, const std::string& parameter) {
        return std::string(parameter == "frequency_Hz" ? "the model's mesh frequency" : "");
      },
      // Refitted on runs at (r, phi): the columns are the response to a small r, and the mesh answers r far from
      // linearly (the coupled seed gear: 19 % of an r = 0.05 response outside them, r read 10 % low).
      .run_law = RunLaw{
          .lo = Eigen::Vector2d(0.0, -INFINITY),
          .hi = Eigen::Vector2d(INFINITY, INFINITY),
          .start =
              [](const Experiment& e, const FitResult& f, int t) {
                const NamedValues h = f.terms[t].spec->headline(e, f, t);
                return Vec(Eigen::Vector2d(h[0].second, h[3].second));
              },
          .step = [](const Experiment&, const Vec& p, int i) { return i == 0 ? std::max(0.05 * p[0], 2e-3) : 0.05; },
          .vary =
              [](const Experiment&, const Vec& p, DynamicsVariation& v) {
                v.stiffness_ratio = p[0];
                v.stiffness_phase_rad = p[1];
              },
          .headline =
              [](const Experiment& e, const Vec& p, const Vec& change) {
                const DynamicsExperiment& d = dynamics(e);
                const Vec line = mesh_lines(d).colPivHouseholderQr().solve(change);
                return NamedValues{{"amplitude_ratio", p[0]},
                                   {"frequency_Hz", d.model.mesh_frequency_Hz},
                                   {"line_amplitude_N", std::hypot(line[0], line[1])},
                                   {"phase_rad", p[1]}};
              }}};
  SynthGenerator g{s.name, {"amplitude_ratio", "phase_rad"}, ":amplitude_ratio (0.05),phase_rad (0.3)   [frequency_Hz = f_m]",
                   false, VariationLaw([](const SynthEffect& fx, const DynamicsPrediction& p) {
                     const double r = synth_param(fx, "amplitude_ratio", 0.05), ph = synth_param(fx, "phase_rad", 0.3);
                     const double fm = p.mesh_frequency_Hz;
                     return SynthVariation{
                         [r, ph](DynamicsVariation& v, double k) {
                           v.stiffness_ratio = k * r;
                           v.stiffness_phase_rad = ph;
                         },
                         [r, ph, fm](double k) {
                           return NamedValues{{"amplitude_ratio", k * r}, {"frequency_Hz", fm}, {"phase_rad", ph}};
                         }};
                   })};
  return {s.name, Kind::Dynamics, {s}, {g}};
}

Effect damping_effect() {
  // The column is the model's own response to a change of c from c0 to theta, per unit change (the secant of the
  // response, from the table of runs), and its coefficient is the change: added = beta, c = c0 + beta. The damping
  // sets the decay rate of the ringing after a step, so a large change alters the response's shape and theta finds
  // the shape (beta = theta - c0 when the model is right); a small one only scales it, and then beta alone is
  // determined, whatever theta. The one linear column at c0 mapped through a calibration curve that stood here
  // before left 45 % of a c = 2 c0 response unexplained and read c 25 % low (frozen seed gear).
  const EffectSpec s{
      .name = "damping",
      .physics = "contact damping other than the model's: the meshing-force fluctuations (the ringing after the "
                 "run-up and load steps; with moving pairs also each tooth's entry into the mesh) are damped at "
                 "another rate",
      .nonlinear_names = {"secant_to_Ns_per_m"},
      .bounds =
          [](const Experiment& e) {
            const auto& c = dynamics(e).damping_table_Ns_per_m;
            return c.empty() ? bounds1(0.0, 1.0) : bounds1(c.front(), c.back());
          },
      .columns = [](const Experiment& e, const Vec& th) { return Mat(damping_secant(dynamics(e), th[0])); },
      .headline =
          [](const Experiment& e, const FitResult& f, int t) {
            const double c0 = dynamics(e).model.damping_Ns_per_m, added = f.terms[t].beta[0];
            return NamedValues{{"coefficient_Ns_per_m", c0 + added}, {"added_Ns_per_m", added}};
          },
      // Refitted on runs at c: between the table's runs the cubic misses the model's response (the coupled seed gear
      // read the change 15 % high).
      .run_law = RunLaw{
          .lo = Vec::Zero(1),
          .hi = Vec::Constant(1, INFINITY),
          .start =
              [](const Experiment& e, const FitResult& f, int t) {
                return Vec(Vec::Constant(1, std::max(0.0, dynamics(e).model.damping_Ns_per_m + f.terms[t].beta[0])));
              },
          .step =
              [](const Experiment& e, const Vec& p, int) {
                const double c0 = dynamics(e).model.damping_Ns_per_m;
                return c0 > 0.0 ? std::max(0.25 * std::abs(p[0] - c0), 5e-3 * c0) : std::max(0.25 * p[0], 1.0);
              },
          .vary = [](const Experiment&, const Vec& p, DynamicsVariation& v) { v.damping_Ns_per_m = p[0]; },
          .headline =
              [](const Experiment& e, const Vec& p, const Vec&) {
                return NamedValues{{"coefficient_Ns_per_m", p[0]},
                                   {"added_Ns_per_m", p[0] - dynamics(e).model.damping_Ns_per_m}};
              }}};
  SynthGenerator g{s.name, {"coefficient_Ns_per_m"}, ":coefficient_Ns_per_m (2 c0)", false,
                   VariationLaw([](const SynthEffect& fx, const DynamicsPrediction& p) {
                     const double c0 = p.damping_Ns_per_m;
                     const double c = synth_param(fx, "coefficient_Ns_per_m", c0 > 0 ? 2.0 * c0 : 1e3);
                     return SynthVariation{
                         [c, c0](DynamicsVariation& v, double k) { v.damping_Ns_per_m = std::max(0.0, c0 + k * (c - c0)); },
                         [c, c0](double k) {
                           return NamedValues{{"coefficient_Ns_per_m", std::max(0.0, c0 + k * (c - c0))},
                                              {"added_Ns_per_m", k * (c - c0)}};
                         }};
                   })};
  return {s.name, Kind::Dynamics, {s}, {g}};
}

Effect drag_torque_effect() {
  const EffectSpec s{
      .name = "drag_torque",
      .physics = "friction drag in bearings and teeth (Coulomb + viscous) on the output: the mesh carries more torque "
                 "than the load, by an amount that grows with speed",
      .n_linear = 2,
      .bounds = no_bounds,
      .columns = [](const Experiment& e, const Vec&) { return Mat(dynamics(e).sensitivity.rightCols(2)); },
      .headline =
          [](const Experiment& e, const FitResult& f, int t) {
            const Vec& b = f.terms[t].beta;
            return NamedValues{{"coulomb_Nm", b[0]},
                               {"viscous_Nms_per_rad", b[1]},
                               {"torque_at_speed_Nm", b[0] + b[1] * dynamics(e).model.output_speed_rad_s}};
          },
      // Refitted on runs at (Coulomb, viscous): the coupled seed gear answers the drag far from linearly (25 % of its
      // response outside the columns, the torque at speed read 10 % low).
      .run_law = RunLaw{
          // A drag dissipates: neither part is negative (the columns' split of the two may be; the sum at speed is
          // what a run at one speed determines).
          .lo = Eigen::Vector2d::Zero(),
          .hi = Eigen::Vector2d::Constant(INFINITY),
          .start =
              [](const Experiment& e, const FitResult& f, int t) {
                // The columns' sum at speed with a split that dissipates: a negative part (the split is what the
                // columns cannot read) gives the whole sum to the other part.
                const Vec& b = f.terms[t].beta;
                const double w = std::max(dynamics(e).model.output_speed_rad_s, 1e-6);
                const double sum = std::max(0.0, b[0] + b[1] * w);
                if (b[0] < 0.0) return Vec(Eigen::Vector2d(0.0, sum / w));
                if (b[1] < 0.0) return Vec(Eigen::Vector2d(sum, 0.0));
                return Vec(b);
              },
          .step =
              [](const Experiment& e, const Vec& p, int i) {
                const DynamicsPrediction& m = dynamics(e).model;
                const double w = std::max(m.output_speed_rad_s, 1e-6);
                const double torque = std::max({0.1 * std::abs(p[0] + p[1] * w), 1e-3 * m.load_torque_Nm, 1e-6});
                return i == 0 ? torque : torque / w;
              },
          .vary =
              [](const Experiment&, const Vec& p, DynamicsVariation& v) {
                v.drag_coulomb_Nm = p[0];
                v.drag_viscous_Nms_per_rad = p[1];
              },
          .headline =
              [](const Experiment& e, const Vec& p, const Vec&) {
                return NamedValues{{"coulomb_Nm", p[0]},
                                   {"viscous_Nms_per_rad", p[1]},
                                   {"torque_at_speed_Nm", p[0] + p[1] * dynamics(e).model.output_speed_rad_s}};
              }}};
  SynthGenerator g{s.name, {"coulomb_Nm", "viscous_Nms_per_rad"},
                   ":coulomb_Nm (0.02 load),viscous_Nms_per_rad (same torque at speed)", false,
                   VariationLaw([](const SynthEffect& fx, const DynamicsPrediction& p) {
                     const double tc = synth_param(fx, "coulomb_Nm", std::max(0.02 * p.load_torque_Nm, 0.1));
                     const double bv = synth_param(fx, "viscous_Nms_per_rad", tc / std::max(p.output_speed_rad_s, 1e-6));
                     const double w = p.output_speed_rad_s;
                     return SynthVariation{[tc, bv](DynamicsVariation& v, double k) {
                                             v.drag_coulomb_Nm = k * tc;
                                             v.drag_viscous_Nms_per_rad = k * bv;
                                           },
                                           [tc, bv, w](double k) {
                                             return NamedValues{{"coulomb_Nm", k * tc},
                                                                {"viscous_Nms_per_rad", k * bv},
                                                                {"torque_at_speed_Nm", k * (tc + bv * w)}};
                                           }};
                   })};
  return {s.name, Kind::Dynamics, {s}, {g}};
}

/// The rows of a kind with each variant's kind and (where it has none of its own) label filled in.
std::vector<Effect> finished(std::vector<Effect> effects) {
  for (Effect& fx : effects)
    for (EffectSpec& s : fx.variants) {
      s.kind = fx.kind;
      if (s.label.empty()) s.label = s.name;
    }
  return effects;
}

std::vector<EffectSpec> variants_of(const std::vector<Effect>& effects) {
  std::vector<EffectSpec> v;
  for (const Effect& fx : effects) v.insert(v.end(), fx.variants.begin(), fx.variants.end());
  return v;
}

}  // namespace

double synth_param(const SynthEffect& fx, const std::string& key, double fallback) {
  const auto it = fx.params.find(key);
  return it == fx.params.end() ? fallback : it->second;
}

const std::vector<Effect>& effect_table(Kind kind) {
  static const std::vector<Effect> torsion = finished(
      {series_compliance_effect(), stiffness_effect(), hysteresis_effect(), lost_motion_effect()});
  static const std::vector<Effect> transmission = finished(transmission_effects());
  static const std::vector<Effect> backlash = finished(backlash_effects());
  static const std::vector<Effect> dynamics = finished({mesh_stiffness_effect(), damping_effect(), drag_torque_effect()});
  switch (kind) {
    case Kind::Torsion: return torsion;
    case Kind::Transmission: return transmission;
    case Kind::Backlash: return backlash;
    case Kind::Dynamics: return dynamics;
  }
  throw std::logic_error("effect_table: unknown kind");
}

const std::vector<EffectSpec>& effect_catalog(Kind kind) {
  static const std::vector<EffectSpec> torsion = variants_of(effect_table(Kind::Torsion));
  static const std::vector<EffectSpec> transmission = variants_of(effect_table(Kind::Transmission));
  static const std::vector<EffectSpec> backlash = variants_of(effect_table(Kind::Backlash));
  static const std::vector<EffectSpec> dynamics = variants_of(effect_table(Kind::Dynamics));
  switch (kind) {
    case Kind::Torsion: return torsion;
    case Kind::Transmission: return transmission;
    case Kind::Backlash: return backlash;
    case Kind::Dynamics: return dynamics;
  }
  throw std::logic_error("effect_catalog: unknown kind");
}

SynthLaw synth_law(Kind kind, const SynthEffect& fx) {
  for (const Effect& effect : effect_table(kind))
    for (const SynthGenerator& g : effect.generators) {
      if (g.name != fx.name) continue;
      for (const auto& [k, v] : fx.params)
        if (std::find(g.keys.begin(), g.keys.end(), k) == g.keys.end()) {
          std::string list;
          for (const auto& a : g.keys) list += (list.empty() ? "" : ", ") + a;
          throw InputError("synth effect " + fx.name + ": parameter " + k + " = " + std::to_string(v) +
                           "; unknown, expected one of " + list);
        }
      return {&effect, &g};
    }
  throw InputError("synth effect = '" + fx.name + "'; not an effect of kind " + kind_name(kind) +
                   " (see strainwave synth --help)");
}

double baseline_play_rad(const TorsionExperiment& t) {
  if (!t.model.twist_rad) return 0.0;
  // Either side of zero torque by a hair of the amplitude: the curve's dead band is its jump there.
  const double eps = 1e-9 * t.torque_amplitude_Nm;
  return std::max(0.0, t.model.twist_rad(eps) - t.model.twist_rad(-eps));
}

double added_series_compliance(const FitResult& f) {
  const int s = f.find("series_compliance");
  return s >= 0 ? f.terms[s].beta[0] : 0.0;
}

std::string model_effect_name(const std::string& key) { return "model:" + key; }

bool is_model_effect(const EffectSpec& spec) { return spec.name.rfind(model_effect_name(""), 0) == 0; }

double FitResult::bic() const {
  return n_w * std::log(std::max(rss_w, 1e-300) / n_w) + k * std::log(static_cast<double>(n_w));
}

Eigen::VectorXd FitResult::params() const {
  std::vector<double> p(nuisance_beta.data(), nuisance_beta.data() + nuisance_beta.size());
  for (const auto& t : terms) {
    p.insert(p.end(), t.beta.data(), t.beta.data() + t.beta.size());
    p.insert(p.end(), t.theta.data(), t.theta.data() + t.theta.size());
  }
  return Eigen::Map<Eigen::VectorXd>(p.data(), p.size());
}

void FitResult::set_params(const Eigen::VectorXd& p) {
  int i = 0;
  for (int j = 0; j < nuisance_beta.size(); ++j) nuisance_beta[j] = p[i++];
  for (auto& t : terms) {
    for (int j = 0; j < t.beta.size(); ++j) t.beta[j] = p[i++];
    for (int j = 0; j < t.theta.size(); ++j) t.theta[j] = p[i++];
  }
}

int FitResult::find(const std::string& name) const {
  for (std::size_t i = 0; i < terms.size(); ++i)
    if (terms[i].spec->name == name) return static_cast<int>(i);
  return -1;
}

}  // namespace sw::reconcile
