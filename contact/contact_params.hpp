#pragma once
// The loaded contact's own case keys (the case file's [contact] table) and their ranges.
#include <numbers>
#include <string>
#include <vector>

#include "common/case_keys.hpp"

namespace sw {

/// Face sections from which the designed drives' K1 changes by about 1 % (12 against 16 on size 17 at ratios 30 and
/// 100; the lost motion by 1 % and 7 %: contact/README.md, How many sections). Straight teeth on the coned rim first
/// touch at a face end along a length that grows with the load: fewer sections (n ≥ 2) resolve the twist at rated
/// torque (from 5) but not the curve below T1.
inline constexpr int kFaceSlicesResolvingK1 = 12;

/// Whether n ≥ 2 face sections leave the curve below T1 (K1, the lost motion) unresolved along the face.
constexpr bool face_slices_leave_k1_unresolved(int face_slices) {
  return face_slices >= 2 && face_slices < kFaceSlicesResolvingK1;
}

struct ContactParams {
  /// Sections of the toothed face in the loaded contact (ContactOptions::face_slices): n ≥ 2 meshes straight teeth
  /// at the face's two ends and evenly between (contact/contact_body.hpp face_slice); 1, the default: the face as one
  /// contact at its centre section (teeth relieved along the face for the cup's coning, an idealisation).
  int face_slices = 1;
  /// Coulomb's μ on the tooth flanks (the loaded contact's loop, the moving pairs of the dynamics); 0, the default:
  /// frictionless flanks.
  double friction_coefficient = 0;
  /// Where the generator is locked while the output is turned: its angle in the circular spline's frame from the
  /// position with flexspline tooth 0 on the major axis (the kinematics' wave-generator angle; tooth k then sits at
  /// the material angle 2πk/z_f − angle·z_c/z_f from the major axis). The mesh repeats every 2π/z_c of it and mirrors
  /// about π/z_c. 0, the default: a tooth on the major axis.
  double generator_angle_rad = 0;
};

/// Most slices of the face: each slice repeats the flanks' influence solves and adds its flanks to the dense contact
/// solve (size 17 at ratio 100: 47 s of contact solve at 12 slices against 2 s at 3); at 16 the designed size 17's
/// bands are some 0.4 mm wide, and narrower ones find no edge of its section's mesh.
inline constexpr int kMaxFaceSlices = 16;

/// The [contact] table's schema (common/case_keys.hpp).
inline const std::vector<CaseKey<ContactParams>>& contact_keys() {
  using P = ContactParams;
  static const std::vector<CaseKey<P>> keys = {
      integer_key<P>("face_slices", &P::face_slices,
                     within(1, kMaxFaceSlices, false, false, "each slice adds its flanks to the contact solve"),
                     "sections of the toothed face, its ends and evenly between (straight teeth), each flank one "
                     "contact per section with its own gap; 1: the centre section alone (teeth relieved for the "
                     "coning, an idealisation)"),
      number_key<P>("friction_coefficient", &P::friction_coefficient, 1, "", within(0, 1),
                    "Coulomb's mu on the tooth flanks (the loaded contact's loop, the dynamics' moving pairs)"),
      number_key<P>("generator_angle_deg", &P::generator_angle_rad, std::numbers::pi / 180, "deg",
                    within(0, 360, false, true),
                    "where the generator is locked while the output turns: its angle from the position with a "
                    "flexspline tooth on the major axis (the mesh repeats every 360/z_c deg)"),
  };
  return keys;
}

/// Checks the keys' ranges; throws InputError "contact.face_slices = 17; must be in [1, 16] ...".
inline void validate_contact_params(const ContactParams& p) { check_key_ranges(p, contact_keys(), "contact"); }

}  // namespace sw
