#pragma once
// The steps of reconstruct_surface (engine/surface/surface.hpp), each in its own file:
// mirror images at the walls and each particle's kernel (particle_kernels.cpp), the field on
// blocks of voxels (voxel_blocks.cpp; its walls and smoothing, smooth_blocks.cpp), marching
// cubes over them (march_blocks.cpp) and the particles' values carried to the vertices
// (vertex_values.cpp); the pieces of parts joined (surface_pieces.cpp).
#include <cstdint>
#include <vector>

#include "engine/sph/neighbor_grid.hpp"
#include "engine/surface/surface.hpp"

namespace pbf {

// The cloud's particles followed by their mirror images across the walls within R of them,
// then across the solids' faces.
struct SurfaceParticles {
  std::vector<real> x, y, z;
  std::vector<std::uint32_t> source;  // the cloud's particle (itself, or the one mirrored)
  std::vector<std::uint8_t> flips;    // the axes an image is reflected along (bit a)
  std::size_t originals = 0;
  // The images across the solids' faces, from `solid_images` on: each one's face normal.
  std::size_t solid_images = 0;
  std::vector<std::array<double, 3>> solid_normals;
  std::size_t size() const { return x.size(); }
};
SurfaceParticles with_images(const SurfaceCloud& cloud, const SurfaceSettings& s);

// A particle's smoothing kernel: A (1 - d.Q.d)^3 at offset d where d.Q.d < 1, times V.
struct ParticleKernel {
  float q[6];       // Q: xx, yy, zz, xy, xz, yz (1/m^2)
  float weight;     // V A (dimensionless: phi's unit)
  float extent[3];  // the half-widths of its support's bounding box (m)
  float radius;     // the smoothed spheres' particle radius r_j (m)
  bool interior;    // a full neighbourhood: phi is well above iso wherever this kernel reaches
  bool isolated;    // fewer neighbours than isolated_below: a droplet's sphere
};
// Bins the particles in `cells` (R wide) and gives each its kernel (an image its original's,
// reflected).
std::vector<ParticleKernel> particle_kernels(const SurfaceParticles& p, const SurfaceCloud& cloud,
                                             const SurfaceSettings& s, NeighborGrid& cells);

// phi on a lattice of voxels aligned with the domain (voxel i's centre at lo + (i + 1/2) v
// along each axis), stored in cubic blocks of kBlock^3 voxels where the surface can be: the
// band that the kernels of particles without a full neighbourhood reach. The blocks only
// particles inside the fluid reach hold `inside` (not stored), the others 0.
class VoxelBlocks {
 public:
  static constexpr int kBlock = 16;
  static constexpr int kBlockVoxels = kBlock * kBlock * kBlock;

  double lo[3] = {0, 0, 0}, v[3] = {1, 1, 1};  // the domain's lower corner and the voxel edges
  long n[3] = {1, 1, 1};                       // voxels across the domain
  long block_lo[3] = {0, 0, 0}, block_dims[3] = {0, 0, 0};  // the blocks held, in block units
  static constexpr std::int32_t kEmpty = -1, kFull = -2;
  float inside = 1;                      // phi in a kFull block
  std::vector<std::int32_t> block_slot;  // per block of the box: its slot, kEmpty (phi = 0) or kFull
  std::vector<float> values;             // kBlockVoxels per slot, x fastest
  std::vector<long> slot_block[3];       // per slot: its block's coordinates

  std::size_t slots() const { return slot_block[0].size(); }
  // The slot of block (bx, by, bz), or kEmpty or kFull.
  std::int32_t slot(long bx, long by, long bz) const {
    const long i = bx - block_lo[0], j = by - block_lo[1], k = bz - block_lo[2];
    if (i < 0 || j < 0 || k < 0 || i >= block_dims[0] || j >= block_dims[1] || k >= block_dims[2]) return kEmpty;
    return block_slot[static_cast<std::size_t>((k * block_dims[1] + j) * block_dims[0] + i)];
  }
  // phi at voxel (i, j, k).
  float at(long i, long j, long k) const;
  // Voxel i's centre along `axis`.
  double centre(int axis, long i) const { return lo[axis] + (static_cast<double>(i) + 0.5) * v[axis]; }
  // Copies phi over the voxels [corner - 1, corner + kBlock + 2) of each axis into `out`
  // ((kBlock + 3)^3, x fastest): a block and the halo its cubes and gradients read.
  void padded(long bx, long by, long bz, float* out) const;
  static constexpr int kPadded = kBlock + 3;
};
// The part's blocks and the ring of one block around them along its axis (what their cubes,
// gradients and smoothing read): the blocks beyond are not held.
VoxelBlocks voxel_blocks(const SurfaceParticles& p, const std::vector<ParticleKernel>& kernels,
                         const SurfaceSettings& s, const SurfacePart& part, SurfaceStats& stats);

// The voxels beyond the walls (after each round again: a full block computed since holds other
// values at their mirrors). With `as_mirror`, the first layer takes its mirror voxel's phi
// instead (what the smoothing reads beyond a wall: the fluid as if it went on), or beyond a
// periodic face the far side's first layer (the fluid there).
void close_walls(VoxelBlocks& f, const SurfaceSettings& s, bool as_mirror);
// Smoothing: passes of the binomial filter (1 2 1) / 4 along each axis over the computed
// blocks (a voxel's neighbours in the next block through the halo), beyond a wall reading the
// mirror voxels.
void smooth_blocks(VoxelBlocks& f, const SurfaceSettings& s);

// Marching cubes over the part's blocks: vertices with normals, outward triangles.
SurfacePiece march_blocks(const VoxelBlocks& field, const SurfaceSettings& s, const SurfacePart& part);

// Each vertex's attributes: the particles' values averaged with their kernels' weights there
// (the kernels reach no further than `radius`, R).
void vertex_values(const SurfaceParticles& p, const std::vector<ParticleKernel>& kernels, const SurfaceCloud& cloud,
                   const NeighborGrid& cells, double radius, SurfacePiece& piece);

}  // namespace pbf
