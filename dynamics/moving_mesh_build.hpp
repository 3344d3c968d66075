#pragma once
// Building the moving mesh of dynamics/moving_mesh.hpp from a case: the flank table from the backlash module, and,
// for a rim coupled through the flexspline's body, the loaded-contact problem at a few generator phases over one pitch.
#include <functional>

#include "fem/flexspline_model.hpp"
#include "contact/contact_body.hpp"
#include "contact/loaded_contact.hpp"
#include "dynamics/moving_mesh.hpp"
#include "fem/flexspline_analysis.hpp"
#include "fem/flexspline_system.hpp"
#include "kinematics/backlash.hpp"
#include "kinematics/neutral_curve.hpp"
#include "mesh/tet_mesh.hpp"

namespace sw {

/// Tooth-pair compliance (m/N over the face width) at a contact radius on the flexspline tooth; empty: rigid teeth.
using ToothCompliance = std::function<double(double contact_radius_f_m, double contact_radius_c_m)>;

/// Independent pairs on a rigid rim: the flank table on `curve` (e.g. the case's generator curve), sampled every
/// pitch/samples_per_pitch over the whole circle (half of it when z_f is even).
MovingMesh rigid_rim_mesh(const GearParams& gear, const NeutralCurve& curve, const ToothCompliance& teeth,
                          int samples_per_pitch);

/// Pairs coupled through the rim: on the flexspline body `body` (the harmonic solver's or TET10's), the loaded contact's
/// problem (contact/loaded_contact.hpp, every flank that can close
/// within reach_factor body twists at rated torque, the generator's stations when unilateral) at `phases` generator
/// phases over one pitch, and the flank table on the FEM's generator-deformed neutral curve, sampled every
/// pitch/(phases·table_per_phase) so that the phases fall on its grid.
MovingMesh fem_coupled_mesh(const FlexsplineModel& model, const ContactBody& body, const FemReadout& fem,
                            const ToothCompliance& teeth, double rated_torque_Nm, int phases, int table_per_phase,
                            double reach_factor = 12.0);

/// The relative velocity at one flank's contact when the mesh follows the kinematics (zero mesh deflection): the
/// flexspline's contact point (fc.point_f, carried by its tooth at material angle φ along the deformed neutral curve)
/// against the circular spline's (fc.point_c, turning by z_f/z_c of φ's change in the generator's frame), per unit
/// σ̇ = ω_w − ω_f (m/rad). Along the flank normal n (fc.normal) it is the clearance's rate d(clearance)/dφ; along the
/// profile t = ẑ × n it is the flanks' sliding. tangent_arm_m = n·p_f is t's moment arm about the axis (m): a rigid
/// turn of the flexspline rim by ė slides the flank by tangent_arm_m·ė.
struct FlankVelocity {
  double normal_m_per_rad = 0, sliding_m_per_rad = 0, tangent_arm_m = 0;
};
FlankVelocity flank_velocity(const BacklashModel& model, const FlankClearance& fc, double phi_rad);

/// The generator angle `wg_angle_rad` of contact/ (against the fixed circular spline) for σ = θ_w − θ_f.
double contact_wg_angle_rad(const GearParams& gear, double sigma_rad);

}  // namespace sw
