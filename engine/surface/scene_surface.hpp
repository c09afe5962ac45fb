#pragma once
// What a scene gives its surface (dump/surface, and dump/image drawing water): the settings
// that follow from the scene (the particles' lattice spacing, the domain and which of its faces
// are walls: neither periodic nor open) and the particles in id order with their volumes.
#include "engine/output/dump_fields.hpp"
#include "engine/surface/surface.hpp"

namespace pbf {

class Simulation;

// The default settings for `sim`, with the voxel and the smoothing radius given in particle
// spacings. Collective in a distributed run (the mean particle mass).
SurfaceSettings scene_surface_settings(Simulation& sim, double voxel_spacings, double radius_spacings);

// Every particle's position, volume (its mass over the mean mass, times s^3) and the values of
// `fields`, in id order: on rank 0 in a distributed run (every rank calls it; the others get an
// empty cloud).
SurfaceCloud scene_cloud(Simulation& sim, DumpFields& fields, const SurfaceSettings& settings);

}  // namespace pbf
