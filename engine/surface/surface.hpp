#pragma once
// A triangle mesh of the fluid's free surface, reconstructed from particles: the iso-surface
// phi = iso of a smoothed particle density on a voxel grid, meshed by marching cubes.
//
//   phi(x) = sum_j V_j A_j P(d_j . Q_j d_j),  d_j = x - x_j,  P(q) = (1 - q)^3 for q < 1, else 0
//
// V_j: the particle's volume (m_j / m times s^3, s the lattice spacing), so phi is about 1
// inside the fluid and 0 outside, and iso = 1/2 lies half a spacing beyond the outer layer of
// a lattice: the surface then encloses the particles' volume. Q_j and A_j make the kernel an
// ellipsoid that integrates to 1:
//
//   isotropic (Mueller et al. 2003's colour field): Q = I / R^2, A = 315 / (64 pi R^3);
//   anisotropic (Yu & Turk 2013): the axes follow the weighted covariance of the particle's
//     neighbours within R, C = sum_k w_k (x_k - xm)(x_k - xm)^T / sum_k w_k with
//     w_k = (1 - r_k^2 / R^2)^3 and xm the weighted mean: with eigenvalues l1 >= l2 >= l3 and
//     eigenvectors e1..e3, semi-axes a_i = R max(sqrt(l_i / l1), 1 / k_r) along e_i (k_r = 2:
//     the spread of the neighbours, not Yu & Turk's variances, whose ratio of 3 and more
//     between a layered interior's directions opened voids between the layers), so a particle
//     inside the fluid keeps the sphere of radius R and one at a flat surface is squashed
//     across it (a flat, smooth top), while one with fewer than `isolated_below` neighbours
//     gets a sphere of radius R / 2 (a splash's droplet stays visible).
//     Q = sum_i e_i e_i^T / a_i^2 and A = 315 / (64 pi a1 a2 a3).
//   spheres (Zhu & Bridson 2005's smoothed union of spheres): with weights P_j = P(|d_j|^2 / R^2),
//     the weighted centre xb = sum P_j x_j / sum P_j and radius rb = sum P_j r_j / sum P_j
//     (r_j = sphere_radius (V_j / s^3)^(1/3)), the signed distance |x - xb| - rb to that sphere,
//     stored as phi = iso - (|x - xb| - rb) / s so that "inside" is phi > iso as for the others.
//
// Walls: with walls closed or open, the particles within R of a wall face of the domain are
// mirrored across it, so phi meets the wall as if the fluid went on (the surface stands square
// to the wall, at the fluid's true height), and the voxels beyond the face are set so that the
// surface crosses exactly at the face: closed, the mesh includes the wetted wall (one closed
// body); open, those triangles are left out (only the free surface). Along a periodic axis
// the particles within R of a face continue across it (images translated by the domain's
// length, not mirrored), so the surface runs on as the fluid does, and the faces close it (or,
// open, leave it cut there). The solids' faces (the
// cloud's mirrors) mirror their particles too, so the surface meets a solid square as it meets
// a wall; it runs on into the solid as far as the mirrored fluid reaches (up to R and half a
// spacing), where the solid hides it, and closes there.
//
// Deterministic: the particles come in a fixed order (by id), each voxel sums its particles in
// that order, and the mesh is assembled block by block in a fixed order: the same bits at any
// thread count. The grid's voxels are aligned with the domain (its faces lie halfway between
// two voxel layers), so the grid does not depend on where the particles are; and meshed in
// parts (slabs, one a rank; SurfacePart below), the pieces join into the same bits.
#include <array>
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "engine/core/real.hpp"
#include "engine/geometry/triangle_mesh.hpp"

namespace pbf {

// The particles the surface is made of, in a fixed order (ascending id).
struct SurfaceCloud {
  std::vector<real> x, y, z;
  std::vector<double> volume;  // V_j (m^3)
  // Values carried to the mesh's vertices: each attribute's components for every particle,
  // component-major (values[c * n + j]); a vector's (3 components) mirror image flips.
  struct Attribute {
    std::string name;
    int components = 1;
    std::vector<double> values;
  };
  std::vector<Attribute> attributes;
  // Particles within R of a solid's face (a mesh, not the domain's walls), mirrored across the
  // face's plane as the walls mirror theirs: the particle, the face's unit normal into the
  // fluid, and the particle's distance to it (m).
  struct Mirror {
    std::uint32_t particle = 0;
    std::array<double, 3> normal{};
    double distance = 0;
  };
  std::vector<Mirror> mirrors;
  std::size_t size() const { return x.size(); }
};

enum class SurfaceKernel { anisotropic, isotropic, spheres };
enum class SurfaceWalls { closed, open, none };

struct SurfaceSettings {
  double spacing = 0;         // the particles' lattice spacing s (m)
  double mass = 0;            // the mass a particle of spacing s has (kg; what scene_cloud scales volumes by)
  double radius = 0;          // the smoothing radius R (m)
  double voxel = 0;           // the voxel edge asked for (m); each axis's divides the domain
  double iso = 0.5;           // the level of phi that is the surface
  SurfaceKernel kernel = SurfaceKernel::anisotropic;
  int isolated_below = 6;     // fewer neighbours within R than this: a droplet's sphere
  double max_stretch = 2;     // k_r: the longest axis over the shortest, at most
  double sphere_radius = 0;   // spheres: a particle's radius r (m; default 0.6 s)
  int smoothing = 1;          // passes of a (1 2 1) / 4 filter over phi along each axis
  SurfaceWalls walls = SurfaceWalls::closed;
  double lo[3] = {0, 0, 0}, hi[3] = {1, 1, 1};  // the domain
  std::array<bool, 6> wall{};  // which faces (x-, x+, y-, ...) close the surface (walls, periodic faces)
  std::array<bool, 3> periodic{};  // periodic axes: their faces' images are translated, not mirrored
  double memory_limit = 4.0 * (1ull << 30);     // bytes the grid may take
};

struct SurfaceMesh {
  TriangleMesh mesh;                               // outward (right-hand) normals
  std::vector<std::array<float, 3>> normals;       // per vertex: -grad phi, unit
  std::vector<SurfaceCloud::Attribute> attributes;  // per vertex, component-major as the cloud's
};

// What a reconstruction cost.
struct SurfaceStats {
  double seconds_kernels = 0, seconds_field = 0, seconds_mesh = 0, seconds_attributes = 0;
  std::size_t blocks = 0;       // blocks of voxels computed
  std::size_t voxels = 0;       // voxels computed (blocks x 16^3)
  std::size_t bytes = 0;        // the largest memory it held at once (approximate)
  std::size_t images = 0;       // mirror images at walls
};

// Checks the settings (a clear message naming the parameter) and the size of the grid
// (refused beyond memory_limit, with the size it would need); throws pbf::Error.
SurfaceMesh reconstruct_surface(const SurfaceCloud& cloud, const SurfaceSettings& settings,
                                SurfaceStats* stats = nullptr);

// The settings and the particles' positions and volumes checked (what reconstruct_surface
// checks first); throws pbf::Error naming the parameter or the particle.
void check_surface_input(const SurfaceCloud& cloud, const SurfaceSettings& settings);

// Meshing in parts (one a rank): each part meshes the blocks of kBlock^3 voxels
// (engine/surface/surface_parts.hpp) whose index along `axis` lies in [first, end), from a
// cloud that holds every particle within reach of them (SurfaceSlabs::needs), and the pieces
// join into the mesh one part alone makes, bit for bit. The parts agree on which blocks are
// computed (the statuses of the ring of blocks each holds around its own, and once a round the
// blocks the band missed); a block's phi where it matters is exact wherever it is computed.
struct SurfacePart {
  int axis = 0;
  long first = -(1L << 40), end = 1L << 40;  // the block layers along axis this part meshes
  // Called by every part together, at each agreement (voxel_blocks.cpp): `blocks` (numbers:
  // block coordinates and statuses) becomes every part's list joined in part order, and
  // `error` the first part's error (empty: none). Unset for a single part.
  std::function<void(std::vector<std::int64_t>& blocks, std::string& error)> agree;
};

// The parts as slabs: the block layers across the domain's longest axis that is not periodic,
// cut so that each part has about as many particles, and which particles each part's cloud
// needs. A domain periodic along every axis is meshed by the first part alone.
struct SurfaceSlabs {
  // `mirrors`: whether any particle is mirrored across a solid's face (its image reaches further).
  SurfaceSlabs(const SurfaceSettings& settings, bool mirrors);
  int axis = 0;
  long layers = 1;                 // block layers across the domain
  long layer(double x) const;      // a particle's at x along the axis (one beyond the domain: the last)
  // From the particles in each layer (every part's particles counted): the parts' first layers.
  void cut(const std::vector<std::int64_t>& particles_per_layer, int parts);
  SurfacePart part(int r) const;   // the first and last reach beyond the domain
  // Whether part r needs a particle at x along the axis: within reach of its blocks (a kernel's
  // support and the voxels the band, the smoothing and the cubes add, a solid image's
  // original, and the neighbour cells a kernel's sums read, whole).
  bool needs(int r, double x) const;

 private:
  double lo_ = 0, hi_ = 1, voxel_ = 1, reach_ = 0;
  bool whole_ = false;  // every axis periodic: one part meshes everything
  std::vector<long> first_;  // per part, and the layers' end
};

// A part's mesh: its blocks in (z, y, x) order, each with its vertices (in the order of their
// edges) and the triangles of the cubes whose lower corner it holds. A triangle's corner is
// (up << 16) | index: up (bit a: one block up along axis a) names the block that holds the
// vertex; in the block itself the index is the vertex's, in one above the vertex's edge key.
struct SurfacePiece {
  std::vector<std::array<std::int64_t, 3>> blocks;
  std::vector<std::uint32_t> first_vertex{0}, first_triangle{0};  // per block, and the total
  std::vector<std::uint16_t> keys;                                  // per vertex: its edge
  std::vector<std::array<double, 3>> vertices;
  std::vector<std::array<float, 3>> normals;
  std::vector<std::uint8_t> on_wall;  // walls open: the vertex lies on a wall face
  std::vector<SurfaceCloud::Attribute> attributes;  // per vertex, component-major
  std::vector<std::array<std::uint32_t, 3>> corners;
};

SurfacePiece reconstruct_surface_part(const SurfaceCloud& cloud, const SurfaceSettings& settings,
                                      const SurfacePart& part, SurfaceStats* stats = nullptr);
// The pieces of all parts (in any order) as one mesh.
SurfaceMesh join_surface_pieces(const std::vector<SurfacePiece>& pieces, const SurfaceSettings& settings);

}  // namespace pbf
