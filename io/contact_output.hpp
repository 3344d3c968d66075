#pragma once
// What `strainwave contact` writes: contact.json (keys in SPEC.md), torque_twist.csv, contact.svg (the torque–twist
// curve with the catalog's three segments, and the force on every flank at ± rated torque).
#include <optional>
#include <string>

#include "contact/loaded_contact.hpp"

namespace sw {

/// A catalog's three-segment law to set beside the computed one (the case's catalog size).
struct CatalogLaw {
  int size = 0;
  double t1_Nm = 0, t2_Nm = 0, k1_Nm_per_rad = 0, k2_Nm_per_rad = 0, k3_Nm_per_rad = 0;
  SegmentLaw law() const { return {t1_Nm, t2_Nm, k1_Nm_per_rad, k2_Nm_per_rad, k3_Nm_per_rad}; }
};

/// contact.json text. `reference`: the catalog's law of the case's size, if any.
std::string contact_json(const ContactAnalysis& a, const std::string& case_path, const std::optional<CatalogLaw>& reference);

/// torque_twist.csv text: torque_Nm,twist_rad,twist_arcmin,pairs_in_contact,max_pair_force_N.
std::string torque_twist_csv(const ContactAnalysis& a);

/// contact.svg text: two plots stacked.
std::string contact_svg(const ContactAnalysis& a, const std::optional<CatalogLaw>& reference);

}  // namespace sw
