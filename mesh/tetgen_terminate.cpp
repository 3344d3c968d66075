// Replacement for TetGen 1.5's terminatetetgen(). The library's own version frees the mesh and throws an int; the
// tetgenmesh destructor then frees it again while the exception unwinds, which crashes. libtet exports its copy as a
// weak symbol and calls it through the PLT, so this strong definition takes its place: it ends the (forked) TetGen
// child at once with the error code in its exit status. Only ever reached inside that child (see tetgen_mesh.cpp).
// tetgen.h is deliberately not included: it defines the inline original.
#include <unistd.h>

#include "mesh/tetgen_terminate.hpp"

class tetgenmesh;

namespace sw::detail {
int tetgen_exit_base() { return 100; }
}  // namespace sw::detail

void terminatetetgen(tetgenmesh* /*mesh*/, int code) { ::_exit(sw::detail::tetgen_exit_base() + code); }
