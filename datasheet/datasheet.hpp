#pragma once
// The designed drive's catalog sheet: each figure a catalog lists (rated torque, the limits, the torsional stiffness,
// lost motion, hysteresis, the generator bearing's life), computed from the drive's geometry by the stages below, with
// one line on how it was computed and, where the case names a catalog size, the published figure beside it (compared,
// never fitted). A figure the tool does not compute is listed with the reason, not left out.
#include <optional>
#include <string>
#include <vector>

#include "contact/loaded_contact.hpp"
#include "datasheet/losses.hpp"
#include "fem/infinite_life.hpp"

namespace sw {

struct DatasheetFigure {
  std::string name;   ///< key in datasheet.json ("buckling_torque_Nm")
  std::string label;  ///< for the printed table ("buckling torque")
  std::string unit;   ///< "N·m", "N·m/rad", "arcmin", "h"
  std::optional<double> value;      ///< empty: not computed (`method` says why)
  std::string method;               ///< one line: how it was computed, or why it was not
  std::optional<double> published;  ///< the catalog's figure for the case's size and ratio
  std::string published_source;     ///< which catalog row ("CSF, ratio 100")
};

/// The flexspline's linear buckling under the output torque (fem/fourier_buckling.hpp), as the sheet reads it.
struct BucklingFigure {
  double torque_Nm = 0;
  int harmonic = 0;  ///< circumferential waves of the mode
  std::string method;
};

/// The generator bearing's rating life at rated torque and an input speed (generator/bearing_life.hpp).
struct BearingLifeFigure {
  double l10_h = 0;
  double input_speed_rpm = 2000;
  double life_exponent = 0;  ///< −d ln L10 / d ln T between half and full rated torque (the catalog takes 3)
  std::string method;
};

/// The teeth's root strength (gear/tooth_root.hpp): the output torque at which the most loaded tooth's root stress
/// reaches its allowable.
struct ToothRootFigure {
  double torque_Nm = 0;
  double root_stress_at_rated_Pa = 0;
  std::string method;
};

/// Where the power goes (datasheet/losses.hpp) at the catalog's conditions: rated torque at 2,000 and 1,000 rpm, half
/// rated at 2,000 rpm, and no load at 2,000 rpm (the no-load running torque); the starting torque Palmgren's
/// breakaway moment of the generator bearing under the generator's own ball loads.
struct LossFigures {
  LossSplit rated_2000, rated_1000, half_rated_2000, no_load_2000;
  double starting_torque_Nm = 0;
  double damping_input_torque_Nm = 0;  ///< the flexspline's material damping at the input, at any speed
  double ring_slip_input_torque_Nm = 0;  ///< the generator's outer ring slipping on the bore, at no load, any speed
  double ring_friction = 0;              ///< μ of the ring on the bore
  double flanks_at_rest_input_torque_Nm = 0;  ///< the flanks' sliding with no load (a preloaded mesh), at any speed
  double loss_factor = 0;              ///< η it was computed with
  double backdriving_torque_Nm = 0;  ///< at the output (datasheet/losses.hpp backdriving_torque_Nm)
  double flank_friction = 0;
  std::string flank_friction_from;  ///< "[contact] friction_coefficient" or why the boundary value is taken
  std::string lubricant;            ///< "grease, base oil 68/8.6 mm²/s at 40/100 °C, 20 °C: 220 mm²/s"
  LossMap map;                      ///< over speed, load and temperature (the sheet's plot page)
};

/// Everything the sheet is made from; an empty optional is a figure not computed, with `why_not` naming the reason.
struct DatasheetInputs {
  double rated_torque_Nm = 0;
  std::string rated_torque_origin;  ///< "[load] rated_torque_Nm", "the catalog's for size 17"
  int ratio = 0;                    ///< z_f / (z_c − z_f)
  std::optional<int> catalog_size;
  const ContactAnalysis* contact = nullptr;  ///< the loaded contact (with friction when the case gives μ)
  std::optional<InfiniteLife> infinite_life;
  std::optional<FirstYield> first_yield;
  std::optional<BucklingFigure> buckling;
  std::optional<BearingLifeFigure> bearing;
  std::optional<ToothRootFigure> tooth_root;
  std::optional<LossFigures> losses;
  std::string why_no_infinite_life, why_no_yield, why_no_buckling, why_no_bearing, why_no_tooth_root, why_no_losses;
};

struct Datasheet {
  std::optional<int> catalog_size;
  int ratio = 0;
  std::vector<DatasheetFigure> figures;
  /// What the figures take as given or leave out, in words (the page says them too).
  std::vector<std::string> idealisations;
  /// The losses over speed, load and temperature (with the loss figures), and what they count.
  std::optional<LossMap> loss_map;
  std::string loss_map_counts;
  const DatasheetFigure* find(const std::string& name) const;
};

/// The sheet of the computed figures, the catalog's beside them where the size and ratio are listed.
Datasheet make_datasheet(const DatasheetInputs& in);

}  // namespace sw
