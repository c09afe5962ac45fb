#pragma once
// What a scene gives its surface (dump/surface, and dump/image drawing water): the settings
// that follow from the scene (the particles' lattice spacing, the domain and which of its faces
// are walls: neither periodic nor open) and the surface of its particles.
#include "engine/output/dump_fields.hpp"
#include "engine/surface/surface.hpp"

namespace pbf {

class Simulation;

// The default settings for `sim`, with the voxel and the smoothing radius given in particle
// spacings. Collective in a distributed run (the mean particle mass).
SurfaceSettings scene_surface_settings(Simulation& sim, double voxel_spacings, double radius_spacings);

// The surface of the particles, with the values of `fields` on its vertices: on rank 0 in a
// distributed run (every rank calls it and meshes a slab of the domain; the others get an
// empty mesh). The same bits at any rank and thread count.
// With `solids`, the particles near a solid at rest are mirrored across its face (the surface
// meets it square, as it meets the domain's walls).
SurfaceMesh scene_surface(Simulation& sim, DumpFields& fields, const SurfaceSettings& settings, bool solids = true);

}  // namespace pbf
