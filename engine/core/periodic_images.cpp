#include "engine/core/periodic_images.hpp"

#include <algorithm>

#include "engine/core/parallel.hpp"

namespace pbf {

std::vector<Shift> image_shifts(const Domain& domain) {
  std::vector<Shift> shifts;
  if (!domain.any_periodic()) return shifts;
  for (int sz = -1; sz <= 1; ++sz)
    for (int sy = -1; sy <= 1; ++sy)
      for (int sx = -1; sx <= 1; ++sx) {
        const Shift s{std::int8_t(sx), std::int8_t(sy), std::int8_t(sz)};
        bool valid = s != Shift{0, 0, 0};
        for (int a = 0; a < 3; ++a) valid = valid && (domain.periodic[a] || s[a] == 0);
        if (valid) shifts.push_back(s);
      }
  return shifts;
}

bool image_in(const Domain& domain, const GridGeometry& grid, const CellRange& range, const real* const x[3],
              std::size_t i, const Shift& shift, const long* own_cell) {
  for (int a = 0; a < 3; ++a) {
    if (shift[a] == 0 && !own_cell) continue;  // the range holds the particle's own cell
    const long cell = shift[a] == 0 ? own_cell[a] : grid.cell_along(a, domain.image(a, x[a][i], shift[a]));
    if (cell < range.lo[a] || cell >= range.hi[a]) return false;
  }
  return true;
}

void PeriodicImages::build(Particles& P, const Domain& domain, const GridGeometry& grid, const CellRange& range) {
  clear();
  shifts_ = image_shifts(domain);
  if (shifts_.empty()) return;
  const std::size_t n = P.size();
  const real* const x[3] = {P.x(), P.y(), P.z()};
  // In parallel, in blocks of particles: each block's images counted, then written after the
  // blocks before it (in particle order, whichever thread takes a block).
  constexpr std::size_t kBlock = 4096;
  const std::size_t blocks = (n + kBlock - 1) / kBlock;
  std::vector<std::size_t> first(blocks + 1, 0);
  auto for_each_image = [&](std::size_t b, auto&& image) {
    for (std::size_t i = b * kBlock; i < std::min(n, (b + 1) * kBlock); ++i)
      for (const Shift& s : shifts_)
        if (image_in(domain, grid, range, x, i, s)) image(i, s);
  };
#pragma omp parallel for schedule(dynamic)
  for (std::size_t b = 0; b < blocks; ++b) for_each_image(b, [&](std::size_t, const Shift&) { ++first[b + 1]; });
  for (std::size_t b = 0; b < blocks; ++b) first[b + 1] += first[b];
  owner_.resize(first[blocks]);
  shift_.resize(first[blocks]);
  std::vector<std::int64_t> ids(first[blocks]);
#pragma omp parallel for schedule(dynamic)
  for (std::size_t b = 0; b < blocks; ++b) {
    std::size_t k = first[b];
    for_each_image(b, [&](std::size_t i, const Shift& s) {
      owner_[k] = static_cast<std::uint32_t>(i);
      shift_[k] = s;
      ids[k++] = P.ids()[i];
    });
  }
  first_ = P.add_ghosts(ids);
  std::vector<real*> components;  // every field's, copied in one pass
  for (FieldId f : P.fields())
    for (int c = 0; c < P.spec(f).components; ++c) components.push_back(P.data(f, c));
  update(components);
  real* const positions[3] = {P.x(), P.y(), P.z()};
  update_positions(domain, positions);
}

void PeriodicImages::update(std::span<real* const> arrays) const {
  if (owner_.empty()) return;
  for_particles(owner_.size(), [&](std::size_t k) {
    for (real* values : arrays) values[first_ + k] = values[owner_[k]];
  });
}

void PeriodicImages::update_positions(const Domain& domain, real* const x[3]) const {
  if (owner_.empty()) return;
  for_particles(owner_.size(), [&](std::size_t k) {
    for (int a = 0; a < 3; ++a) x[a][first_ + k] = domain.image(a, x[a][owner_[k]], shift_[k][a]);
  });
}

}  // namespace pbf
