#pragma once
// The arrays that hold particle fields, and pins that keep one's memory alive after the
// engine lets go of it.
//
// The Python module hands out NumPy arrays that view these arrays without copying
// (python/module_arrays.cpp). The engine moves the arrays under them: the particles are
// re-sorted every 20 steps (each field's array trades places with a scratch array), ghosts
// and new particles grow them, a field no pipeline declares is freed. A view that outlives
// the memory it was taken from would read freed memory. So each view holds a pin on the
// block it views: the allocator frees a pinned block only when its last pin goes. A stale
// view then reads a block the engine no longer uses as that field (its values are old, or
// another field's after a sort), never freed memory.
//
// Freeing checks one counter while no block is pinned (always, outside Python): the engine
// frees these arrays rarely (growth, a field freed), never in a hot loop.
#include <cstddef>
#include <cstdint>
#include <new>
#include <vector>

#include "engine/core/real.hpp"

namespace pbf {

namespace buffer_pins {
// Pins the block starting at `block` (the address an array's data() gave) once more.
void pin(const void* block);
// Removes one pin; frees the block if the engine let go of it meanwhile.
void unpin(const void* block);
// Frees the block, or leaves that to its last pin (FieldAllocator::deallocate).
void release(void* block);
// Blocks pinned now (for tests).
std::size_t pinned_blocks();
}  // namespace buffer_pins

template <class T>
struct FieldAllocator {
  using value_type = T;
  FieldAllocator() = default;
  template <class U>
  FieldAllocator(const FieldAllocator<U>&) {}
  T* allocate(std::size_t n) { return static_cast<T*>(::operator new(n * sizeof(T))); }
  void deallocate(T* p, std::size_t) { buffer_pins::release(p); }
  template <class U>
  bool operator==(const FieldAllocator<U>&) const { return true; }
};

// One component of a particle field, the ids, and the scratch arrays that trade places with them.
using RealArray = std::vector<real, FieldAllocator<real>>;
using IdArray = std::vector<std::int64_t, FieldAllocator<std::int64_t>>;

}  // namespace pbf
