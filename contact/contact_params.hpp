#pragma once
// The loaded contact's own case keys (the case file's [contact] table) and their ranges.
#include <string>
#include <vector>

#include "common/case_keys.hpp"

namespace sw {

struct ContactParams {
  /// Sections of the toothed face in the loaded contact (ContactOptions::face_slices): n ≥ 2 meshes straight teeth
  /// at the face's two ends and evenly between (contact/contact_body.hpp face_slice); 1, the default: the face as one
  /// contact at its centre section (teeth relieved along the face for the cup's coning, an idealisation).
  int face_slices = 1;
  /// Coulomb's μ on the tooth flanks (the loaded contact's loop, the moving pairs of the dynamics); 0, the default:
  /// frictionless flanks.
  double friction_coefficient = 0;
};

/// Most slices of the face: each slice repeats the flanks' influence solves.
inline constexpr int kMaxFaceSlices = 8;

/// The [contact] table's schema (common/case_keys.hpp).
inline const std::vector<CaseKey<ContactParams>>& contact_keys() {
  using P = ContactParams;
  static const std::vector<CaseKey<P>> keys = {
      integer_key<P>("face_slices", &P::face_slices,
                     within(1, kMaxFaceSlices, false, false, "each slice repeats the flanks' influence solves"),
                     "sections of the toothed face, its ends and evenly between (straight teeth), each flank one "
                     "contact per section with its own gap; 1: the centre section alone (teeth relieved for the "
                     "coning, an idealisation)"),
      number_key<P>("friction_coefficient", &P::friction_coefficient, 1, "", within(0, 1),
                    "Coulomb's mu on the tooth flanks (the loaded contact's loop, the dynamics' moving pairs)"),
  };
  return keys;
}

/// Checks the keys' ranges; throws InputError "contact.face_slices = 9; must be in [1, 8] ...".
inline void validate_contact_params(const ContactParams& p) { check_key_ranges(p, contact_keys(), "contact"); }

}  // namespace sw
