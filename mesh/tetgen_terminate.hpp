#pragma once
// Internal to mesh/: the exit status base a TetGen child process uses to report TetGen's error code.
namespace sw::detail {

/// Exit status of the TetGen child = this + TetGen's error code (1 memory, 2 internal, 3 self-intersection,
/// 4 small feature, 5 close facets, 10 input). Defined beside the terminatetetgen() replacement so that
/// referencing it links the replacement in.
int tetgen_exit_base();

}  // namespace sw::detail
