#pragma once
// The loaded contact's own case keys (the case file's [contact] table) and their ranges.
#include <string>

namespace sw {

struct ContactParams {
  /// Axial slices of the toothed face in the loaded contact (ContactOptions::face_slices); 1, the default: the face
  /// as one contact at its centre section.
  int face_slices = 1;
};

/// Most slices of the face: each slice repeats the flanks' influence solves.
inline constexpr int kMaxFaceSlices = 8;

}  // namespace sw
