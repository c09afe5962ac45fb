// Pins on the blocks of field arrays (engine/core/field_array.hpp).
#include "engine/core/field_array.hpp"

#include <atomic>
#include <mutex>
#include <unordered_map>

namespace pbf::buffer_pins {

namespace {

struct Pin {
  std::size_t count = 0;
  bool released = false;  // the engine let go of the block: the last unpin frees it
};

std::mutex& guard() {
  static std::mutex m;
  return m;
}
std::unordered_map<const void*, Pin>& pins() {
  static std::unordered_map<const void*, Pin> p;
  return p;
}
// Blocks with a pin: while none, release() frees without taking the lock.
std::atomic<std::size_t> pinned{0};

}  // namespace

void pin(const void* block) {
  if (!block) return;
  std::lock_guard lock(guard());
  Pin& p = pins()[block];
  if (p.count++ == 0) pinned.fetch_add(1);
}

void unpin(const void* block) {
  if (!block) return;
  bool free_it = false;
  {
    std::lock_guard lock(guard());
    auto it = pins().find(block);
    if (it == pins().end()) return;
    if (--it->second.count == 0) {
      free_it = it->second.released;
      pins().erase(it);
      pinned.fetch_sub(1);
    }
  }
  if (free_it) ::operator delete(const_cast<void*>(block));
}

void release(void* block) {
  if (pinned.load() != 0) {
    std::lock_guard lock(guard());
    auto it = pins().find(block);
    if (it != pins().end()) {
      it->second.released = true;
      return;
    }
  }
  ::operator delete(block);
}

std::size_t pinned_blocks() { return pinned.load(); }

}  // namespace pbf::buffer_pins
