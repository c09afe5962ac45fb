#pragma once
// The SPH curl of the velocity (the vorticity), volume-weighted form over the current
// neighbour lists: omega_i = sum_j V_j gradW_ij x (v_j - v_i), V_j = m_j / rho_j
// (Simulation::summed_volume). Shared by vorticity confinement and by dumps that write
// |omega| without it.
#include <vector>

#include "engine/core/real.hpp"

namespace pbf {

class Simulation;

// Writes omega into wx, wy, wz and |omega| into magnitude (each sized for every particle).
void velocity_curl(Simulation& sim, const std::vector<real>& volume, real* wx, real* wy, real* wz, real* magnitude);

}  // namespace pbf
