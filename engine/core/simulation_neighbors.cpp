// The simulation's neighbour service (engine/core/simulation.hpp): particles placed on their
// ranks, the neighbour lists, the ghosts a rank's pair loops read (other ranks' particles,
// periodic images, the ghost check's copies) and their refreshes, periodic wrapping, and the
// point cells of probes and gauges.
#include <omp.h>

#include <algorithm>
#include <limits>

#include <fmt/format.h>

#include "engine/core/error.hpp"
#include "engine/core/parallel.hpp"
#include "engine/core/simulation.hpp"
#include "engine/distributed/comm.hpp"

namespace pbf {

void Simulation::place_particles() {
  auto& P = particles_;
  if (!P.distributed()) return;
  if (h_ <= 0) throw Error("the kernel radius h is not set");
  // The cells are the whole domain's (its extent and h alone), so that every rank lists
  // neighbours alike (engine/distributed/decomposition.hpp); a domain or h changed between
  // runs re-cuts the boxes.
  const GridGeometry cells = GridGeometry::of(domain_, h_);
  if (P.unplaced() == 0 && cells == geometry_) return;
  geometry_ = cells;
  decomposition_.distribute(P, geometry_);
  positions_changed();
}

void Simulation::refresh_neighbors() {
  place_particles();
  if (lists_valid_ && grid_version_ == positions_version_ && grid_.particle_count() == particles_.size()) return;
  if (h_ <= 0) throw Error("the kernel radius h is not set");
  if (!particles_.distributed()) geometry_ = GridGeometry::of(domain_, h_);
  bin_and_list();
}

Simulation::ListTimes Simulation::bin_and_list() {
  auto& P = particles_;
  ListTimes times;
  double t = omp_get_wtime();
  auto lap = [&](double& seconds) {
    const double now = omp_get_wtime();
    seconds = now - t;
    t = now;
  };
  rebuild_ghosts();
  lap(times.ghosts);
  // Each list in cell order, then id: memory order plays no part. The copies of
  // check_ghosts() are not binned: the lists name them in place of the particles.
  grid_.bin(P.x(), P.y(), P.z(), copies_first(), geometry_, ghost_range_, P.ids());
  lap(times.binning);
  grid_.build_lists(P.x(), P.y(), P.z(), h_, P.size());
  if (copies() > 0)
    grid_.offset_neighbors(static_cast<std::uint32_t>(P.size()), static_cast<std::uint32_t>(copies_first()));
  lap(times.lists);
  grid_version_ = positions_version_;
  lists_valid_ = true;
  return times;
}

void Simulation::rebuild_ghosts() {
  auto& P = particles_;
  ghost_range_ = CellRange::all(geometry_);
  if (P.distributed()) {
    ghost_range_ = decomposition_.build_ghosts(P, geometry_, domain_);
    images_.build(P, domain_, geometry_, ghost_range_);
  } else if (has_ghosts()) {
    P.drop_ghosts();
    if (domain_.any_periodic()) {  // the cells of the domain and of the particles, grown by one
      CellRange cells = cells_holding(P, geometry_);
      for (int a = 0; a < 3; ++a) {
        cells.lo[a] = std::min(cells.lo[a], 0L);
        cells.hi[a] = std::max(cells.hi[a], geometry_.dims[a]);
      }
      ghost_range_ = geometry_.grown(cells);
      images_.build(P, domain_, geometry_, ghost_range_);
    }
    if (check_ghosts_) copy_particles_as_ghosts();
  }
  if (has_ghosts()) {
    ghost_positions_version_ = positions_version_;
    lists_valid_ = false;  // the lists' ghost indices name other particles now
  }
  ghosts_version_ = positions_version_;
  point_grid_version_ = 0;
  // The density over the lists is computed afresh (with the ghosts, which are others now).
  density_version_ = volume_version_ = 0;
}

// Particle i's ghost is particle copies_first() + i, with every field's value: what a
// distributed run's ghost build carries. The scratch arrays' contents are undefined now (a
// distributed run's ghosts are other particles than before), so they become NaN.
void Simulation::copy_particles_as_ghosts() {
  auto& P = particles_;
  const std::size_t n = P.size();
  const std::size_t first = P.add_ghosts(std::span<const std::int64_t>(P.ids(), n));
  for (FieldId f : P.fields())
    for (int c = 0; c < P.spec(f).components; ++c) {
      real* values = P.data(f, c);
      std::copy(values, values + n, values + first);
    }
  poison_scratch();
}

void Simulation::wrap_periodic() {
  if (!domain_.any_periodic()) return;
  auto& P = particles_;
  real* const x[3] = {P.x(), P.y(), P.z()};
  for_particles(P.size(), [&](std::size_t i) {
    for (int a = 0; a < 3; ++a)
      if (domain_.periodic[a]) x[a][i] = domain_.wrapped(a, x[a][i]);
  });
  positions_changed();
}

void Simulation::poison_scratch() {
  for (auto& array : scratch_) {
    array.resize(particles_.size_with_ghosts());
    std::fill(array.begin(), array.end(), std::numeric_limits<real>::quiet_NaN());
  }
}

const NeighborGrid& Simulation::point_cells() {
  if (h_ <= 0) throw Error("the kernel radius h is not set (pbf.kernel_radius): a probe has no kernel");
  auto& P = particles_;
  place_particles();
  if (!P.distributed()) {
    const GridGeometry cells = GridGeometry::of(domain_, h_);
    if (!(cells == geometry_)) ghosts_version_ = 0;
    geometry_ = cells;
    if (!domain_.any_periodic()) ghost_range_ = CellRange::all(geometry_);
  }
  if ((P.distributed() || domain_.any_periodic()) && (ghosts_version_ != positions_version_ || !images_.current(P)))
    rebuild_ghosts();  // (images_ is empty, hence current, without periodic axes)
  // The particles, the other ranks' ghosts and the images (not the copies of check_ghosts()).
  const std::size_t binned = copies_first();
  if (point_grid_version_ != positions_version_ || point_grid_.binned_count() != binned) {
    point_grid_.bin(P.x(), P.y(), P.z(), binned, geometry_, ghost_range_, P.ids());
    point_grid_version_ = positions_version_;
  }
  return point_grid_;
}

bool Simulation::measures_at(double x, double y, double z) const {
  if (!particles_.distributed()) return true;
  const long cell[3] = {geometry_.cell_along(0, x), geometry_.cell_along(1, y), geometry_.cell_along(2, z)};
  return decomposition_.owner(cell) == comm::rank();
}

void Simulation::update_ghosts(std::initializer_list<real*> arrays) {
  const std::span<real* const> all(arrays.begin(), arrays.size());
  if (particles_.distributed()) decomposition_.update(all);
  if (images_.current(particles_)) images_.update(all);
  if (const std::size_t n = copies(); n > 0)  // each copy from its particle
    for (real* values : arrays) std::copy(values, values + n, values + copies_first());
}

void Simulation::update_ghost_positions() {
  if (!has_ghosts() || ghost_positions_version_ == positions_version_) return;
  auto& P = particles_;
  real* const x[3] = {P.x(), P.y(), P.z()};
  if (P.distributed()) decomposition_.update(std::span<real* const>(x, 3), true);
  if (images_.current(P)) images_.update_positions(domain_, x);
  if (const std::size_t n = copies(); n > 0)
    for (real* values : x) std::copy(values, values + n, values + copies_first());
  ghost_positions_version_ = positions_version_;
}

}  // namespace pbf
