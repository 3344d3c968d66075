#pragma once
// The loaded contact's own case keys (the case file's [contact] table) and their ranges.
#include <sstream>
#include <string>

#include "common/error.hpp"

namespace sw {

struct ContactParams {
  /// Axial slices of the toothed face in the loaded contact (ContactOptions::face_slices); 1, the default: the face
  /// as one contact at its centre section.
  int face_slices = 1;
  /// Coulomb's μ on the tooth flanks (the loaded contact's loop, the moving pairs of the dynamics); 0, the default:
  /// frictionless flanks.
  double friction_coefficient = 0;
};

/// Most slices of the face: each slice repeats the flanks' influence solves.
inline constexpr int kMaxFaceSlices = 8;

/// Checks face_slices in [1, kMaxFaceSlices] and friction_coefficient in [0, 1]; throws InputError
/// "contact.face_slices = 9; must be ..." or "contact.friction_coefficient = -0.1; must be in [0, 1]".
inline void validate_contact_params(const ContactParams& p) {
  if (p.face_slices < 1 || p.face_slices > kMaxFaceSlices)
    throw InputError("contact.face_slices = " + std::to_string(p.face_slices) + "; must be in [1, " +
                     std::to_string(kMaxFaceSlices) + "] (each slice repeats the flanks' influence solves)");
  if (!(p.friction_coefficient >= 0 && p.friction_coefficient <= 1)) {
    std::ostringstream os;
    os << "contact.friction_coefficient = " << p.friction_coefficient << "; must be in [0, 1]";
    throw InputError(os.str());
  }
}

}  // namespace sw
