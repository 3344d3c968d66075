#pragma once
// Size of a flexspline's TET10 model before it is built: nodes, equations, the Cholesky factor and peak memory,
// estimated from the geometry and the mesh sizes, so that work that would never fit is refused in seconds (not after
// minutes of meshing). Calibrated on the cases' meshes (constants and their origin in estimate.cpp).
#include <optional>
#include <string>

#include "gear/gear.hpp"
#include "mesh/flexspline_params.hpp"

namespace sw {

struct ModelSizeEstimate {
  double nodes = 0;
  double equations = 0;
  double factor_nnz = 0;    ///< nonzeros of the Cholesky factor L
  double peak_bytes = 0;    ///< mesh + matrix + factor + solves, as measured on the benches
  std::string mesh_text;    ///< the mesh sizes it was made for (mesh_size_text), for the refusal's message
  std::string model = "TET10 model";  ///< what is estimated, for the refusal's message
  /// What the user can change, for the refusal's message.
  std::string remedy = "coarsen mesh.size_mm or mesh.wall_layers, use [solver] method = \"fourier\" for a body of "
                       "revolution, or raise --max-memory";
};

/// The estimate for the case's flexspline (tube or cup, ring/none/explicit teeth) and mesh parameters.
ModelSizeEstimate estimate_model_size(const FlexsplineParams& f, const std::optional<GearParams>& gear,
                                      const MeshParams& mesh);

/// Memory this machine can give now (MemAvailable of /proc/meminfo), bytes; 0 if unknown.
double available_memory_bytes();

/// Throws InputError, in one line with the estimate, when the model would need more than `limit_bytes` (the machine's
/// available memory when limit_bytes = 0). `file` names the case in the message.
void refuse_if_too_large(const ModelSizeEstimate& e, double limit_bytes, const std::string& file);

}  // namespace sw
