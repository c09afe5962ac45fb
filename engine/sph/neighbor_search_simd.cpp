// The distance tests of the neighbour-list build (engine/sph/neighbor_search_simd.hpp),
// written once with Highway's portable vectors and compiled for each x86-64 vector width
// (SSE4, AVX2, AVX-512, and a scalar fallback); the widest the machine has is chosen at run
// time. A row of three cells holds its candidates in consecutive slots, so each vector
// step loads the next N packed positions, compares their squared distances with h^2 and
// counts the lanes that pass (first pass) or writes their particle indices (second pass);
// or, when the previous build's sizes say where each block of particles' lists will fit,
// writes them in one pass.
// The result does not depend on the vector width: the same test, the same order.
#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "engine/sph/neighbor_search_simd.cpp"
#include <hwy/foreach_target.h>  // IWYU pragma: keep
#include <hwy/highway.h>

#include <algorithm>
#include <cstring>

#include "engine/sph/neighbor_search_simd.hpp"

HWY_BEFORE_NAMESPACE();
namespace pbf {
namespace HWY_NAMESPACE {
namespace hn = hwy::HWY_NAMESPACE;

// Calls visit(first, last, own) for the slot range of each of the 9 rows of three cells around
// particle i's cell (cells are numbered x fastest, so the three cells along x of a row are
// one run of slots); `own` is true for the row that holds particle i itself.
template <class Visit>
HWY_INLINE void for_each_row(const CellSearch& s, std::size_t i, Visit&& visit) {
  const long c = s.cell[i], nx = s.dims[0], ny = s.dims[1], nz = s.dims[2];
  const long cx = c % nx, cy = (c / nx) % ny, cz = c / (nx * ny);
  const long x0 = std::max(0L, cx - 1), x1 = std::min(nx - 1, cx + 1);
  for (long z = std::max(0L, cz - 1); z <= std::min(nz - 1, cz + 1); ++z)
    for (long y = std::max(0L, cy - 1); y <= std::min(ny - 1, cy + 1); ++y) {
      const std::size_t row = static_cast<std::size_t>((z * ny + y) * nx);
      visit(s.cell_start[row + x0], s.cell_start[row + x1 + 1], z == cz && y == cy);
    }
}

// The lanes of slots [slot, slot + N) that do not hold particle i.
template <class D>
HWY_INLINE hn::Mask<D> not_particle(D d, const std::uint32_t* sorted, std::size_t i) {
  const hn::RebindToUnsigned<D> du;
  if constexpr (sizeof(hn::TFromD<D>) == 4) {
    return hn::RebindMask(d, hn::Ne(hn::LoadU(du, sorted), hn::Set(du, static_cast<std::uint32_t>(i))));
  } else {
    const hn::Rebind<std::uint32_t, D> d32;
    return hn::RebindMask(d, hn::Ne(hn::PromoteTo(du, hn::LoadU(d32, sorted)), hn::Set(du, i)));
  }
}

// The lanes of slots [slot, slot + N) that are neighbours of particle i: within h, before
// `last`, and, in particle i's own row, not i itself.
template <class D>
HWY_INLINE hn::Mask<D> within(D d, const CellSearch& s, std::size_t i, std::size_t slot, std::size_t last, bool own) {
  const auto dx = hn::Sub(hn::Set(d, s.x[i]), hn::LoadU(d, s.xs + slot));
  const auto dy = hn::Sub(hn::Set(d, s.y[i]), hn::LoadU(d, s.ys + slot));
  const auto dz = hn::Sub(hn::Set(d, s.z[i]), hn::LoadU(d, s.zs + slot));
  const auto r2 = hn::Add(hn::Add(hn::Mul(dx, dx), hn::Mul(dy, dy)), hn::Mul(dz, dz));
  const auto near = hn::And(hn::Lt(r2, hn::Set(d, s.h2)), hn::FirstN(d, last - slot));
  return own ? hn::And(near, not_particle(d, s.sorted + slot, i)) : near;
}

void CountNeighbors(const CellSearch& s, std::uint32_t* counts) {
  const hn::ScalableTag<real> d;
  const std::size_t N = hn::Lanes(d);
#pragma omp parallel for schedule(static, 256)
  for (std::size_t i = 0; i < s.n; ++i) {
    std::size_t count = 0;
    for_each_row(s, i, [&](std::size_t first, std::size_t last, bool own) {
      for (std::size_t slot = first; slot < last; slot += N) count += hn::CountTrue(d, within(d, s, i, slot, last, own));
    });
    counts[i] = static_cast<std::uint32_t>(count);  // at most the particle count
  }
}

void FillNeighbors(const CellSearch& s, const std::uint32_t* offset, std::uint32_t* list) {
  const hn::ScalableTag<real> d;
  const std::size_t N = hn::Lanes(d);
#pragma omp parallel for schedule(static, 256)
  for (std::size_t i = 0; i < s.n; ++i) {
    std::uint32_t* out = list + offset[i];
    for_each_row(s, i, [&](std::size_t first, std::size_t last, bool own) {
      for (std::size_t slot = first; slot < last; slot += N) {
        std::uint8_t bytes[8] = {};  // lane k in bit k (little-endian bytes)
        hn::StoreMaskBits(d, within(d, s, i, slot, last, own), bytes);
        std::uint64_t bits;
        std::memcpy(&bits, bytes, sizeof bits);
        for (; bits; bits &= bits - 1) *out++ = s.sorted[slot + static_cast<std::size_t>(__builtin_ctzll(bits))];
      }
    });
  }
}

std::uint64_t FillNeighborBlock(const CellSearch& s, std::size_t begin, std::size_t end, std::uint32_t* list,
                                std::uint64_t first, std::uint64_t last, std::uint32_t* offset, std::uint32_t& most) {
  const hn::ScalableTag<real> d;
  const std::size_t N = hn::Lanes(d);
  std::uint32_t* out = list + first;
  const std::uint32_t* const stop = list + last;
  bool full = false;
  most = 0;
  for (std::size_t i = begin; i < end && !full; ++i) {
    const std::uint32_t* const start = out;
    offset[i] = static_cast<std::uint32_t>(out - list);  // below the last segment's end, checked to fit
    for_each_row(s, i, [&](std::size_t first_slot, std::size_t last_slot, bool own) {
      for (std::size_t slot = first_slot; slot < last_slot && !full; slot += N) {
        std::uint8_t bytes[8] = {};
        hn::StoreMaskBits(d, within(d, s, i, slot, last_slot, own), bytes);
        std::uint64_t bits;
        std::memcpy(&bits, bytes, sizeof bits);
        if (static_cast<std::ptrdiff_t>(__builtin_popcountll(bits)) > stop - out) {
          full = true;
          break;
        }
        for (; bits; bits &= bits - 1) *out++ = s.sorted[slot + static_cast<std::size_t>(__builtin_ctzll(bits))];
      }
    });
    most = std::max(most, static_cast<std::uint32_t>(out - start));
  }
  return full ? kBlockFull : static_cast<std::uint64_t>(out - (list + first));
}

}  // namespace HWY_NAMESPACE
}  // namespace pbf
HWY_AFTER_NAMESPACE();

#if HWY_ONCE
namespace pbf {

HWY_EXPORT(CountNeighbors);
HWY_EXPORT(FillNeighbors);
HWY_EXPORT(FillNeighborBlock);

void count_neighbors(const CellSearch& search, std::uint32_t* counts) {
  HWY_DYNAMIC_DISPATCH(CountNeighbors)(search, counts);
}

void fill_neighbors(const CellSearch& search, const std::uint32_t* offset, std::uint32_t* list) {
  HWY_DYNAMIC_DISPATCH(FillNeighbors)(search, offset, list);
}

std::uint64_t fill_neighbor_block(const CellSearch& search, std::size_t begin, std::size_t end, std::uint32_t* list,
                                  std::uint64_t first, std::uint64_t last, std::uint32_t* offset, std::uint32_t& most) {
  return HWY_DYNAMIC_DISPATCH(FillNeighborBlock)(search, begin, end, list, first, last, offset, most);
}

}  // namespace pbf
#endif
