#pragma once
// Particle data as structure-of-arrays. Every per-particle array is a declared field
// (name, components, doc, restart); position, velocity and mass always exist, fixes declare the
// rest when they join a run. That one declaration lets the engine reorder, dump and
// save every field without a second list.
#include <cstddef>
#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "engine/core/field_array.hpp"
#include "engine/core/real.hpp"

namespace pbf {

struct FieldSpec {
  std::string name;
  int components = 1;
  std::string doc;
  // Whether the field carries state into the next step (saved in restarts); false for
  // values a fix recomputes every step before reading them.
  bool restart = true;
};

// A field's id stays the same for as long as the field lives (fields freed later leave
// their slot empty, they do not move the others), so a fix may keep the ids it declared.
// The field the force styles add to and an integrator of accelerations (leapfrog)
// integrates: the state one step hands to the next, so it is saved in restarts.
inline const FieldSpec kAccelerationField{
    "acceleration", 3, "acceleration the forces stage accumulates for the integrator (m/s^2)", true};

using FieldId = std::size_t;

class Particles {
 public:
  static constexpr FieldId kPosition = 0, kVelocity = 1, kMass = 2;

  Particles();

  // The particles this process owns (all of them, unless the run is distributed).
  std::size_t size() const { return ids_.size() - ghosts_; }
  // With the ghosts: copies of other ranks' particles near this rank's, after its own in every
  // array, which the pair loops read as neighbours (engine/distributed/decomposition.hpp).
  std::size_t size_with_ghosts() const { return ids_.size(); }
  std::size_t ghosts() const { return ghosts_; }

  // Appends one particle; its id is its creation index (the input order).
  void add(const real position[3], const real velocity[3], real mass);

  // Within a run's step, particles may be added and removed only at the exchange stage: the
  // run loop freezes the set for every other stage, and add, remove and append refuse then.
  void freeze(bool frozen) { frozen_ = frozen; }
  bool frozen() const { return frozen_; }

  // A distributed run (under an MPI launcher, from the start): each rank holds a part of the
  // particles; the ids stay those of the whole set. A source of particles (a lattice, a file)
  // is created in shares: each rank creates the candidates share(count) names, in order, with
  // add(), and finish_source() gives them the ids one process gives them. The shares are
  // placed by space (engine/distributed/decomposition.hpp) at the next run's start, or when
  // neighbours are first needed.
  bool distributed() const { return distributed_; }
  void set_distributed(bool distributed) { distributed_ = distributed; }
  struct Share {
    std::size_t first = 0, end = 0;
  };
  // This rank's candidates of a source of `count`: [first, end), a block of count / ranks in
  // rank order (all of them in one process).
  Share share(std::size_t count) const { return share_of(count, distributed_); }
  static Share share_of(std::size_t count, bool distributed);
  // Gives the particles added from index `first` on their ids: the next ids after those of
  // the lower ranks' shares, as one process creating every candidate in order numbers them.
  // Returns how many every rank added together. Collective in a distributed run.
  std::size_t finish_source(std::size_t first);
  // The particles of every rank (no communication: kept up to date by every change).
  std::size_t global_size() const { return distributed_ ? global_ : size(); }
  // Particles created since the decomposition last placed them (on all ranks: the same on each).
  std::size_t unplaced() const { return distributed_ ? unplaced_ : 0; }
  // The decomposition put every particle on the rank that owns its cell.
  void mark_placed() { unplaced_ = 0; }
  // The id the next particle added takes: the count of particles ever created on all ranks.
  // Part of the scene's state (restarts keep it): ids are never reused.
  std::int64_t next_id() const { return next_id_; }
  void set_next_id(std::int64_t id) { next_id_ = id; }
  // Particles with ids from this one on were created since the last run started (their
  // fields are zero until the fixes set them: Fix::init_new_particles); settle() marks
  // every particle there now as started.
  std::int64_t first_new_id() const { return settled_; }
  void settle() { settled_ = next_id_; }
  // Zeroed particles with these ids after this rank's own (no ghosts may be there).
  void append(std::span<const std::int64_t> ids);
  // Removes this rank's particles whose `drop` entry is non-zero, keeping the others' order
  // and ids, without counting them gone (migration: they live on on another rank).
  void erase(const std::vector<char>& drop);
  // Zeroed ghosts with these ids after those there are; returns the index of the first.
  std::size_t add_ghosts(std::span<const std::int64_t> ids);
  // Removes every ghost (their arrays keep their memory for the next step's).
  void drop_ghosts();

  // Declares a field, zero-filled when new; the same name (with the same component count)
  // gives the same id. Declaring marks the field as used in this declaration round.
  FieldId declare(const FieldSpec& spec);
  // A live field by name.
  std::optional<FieldId> find(const std::string& name) const;
  const FieldSpec& spec(FieldId field) const { return fields_[field].spec; }
  // The live fields' ids, in the order they were first declared.
  std::vector<FieldId> fields() const;

  // Declaration rounds, one per run: after begin_declarations(), the fixes' init() declare
  // what they use, and free_undeclared() frees every other field (position, velocity and
  // mass always stay), so a scene pays only for the fields its pipeline uses.
  void begin_declarations();
  void free_undeclared();

  // The mean particle mass (a deterministic sum: the same bits at any thread and rank count).
  double mean_mass() const;

  real* data(FieldId field, int component = 0) { return fields_[field].data[component].data(); }
  const real* data(FieldId field, int component = 0) const { return fields_[field].data[component].data(); }

  // Exchanges a field component's values (ghosts included) with `values`, of the same
  // length: a pass that computes a whole new array from the old one (new positions from the
  // neighbours' old ones) writes it elsewhere and swaps, instead of copying it back. Pointers
  // taken to either before are to the other afterwards.
  void swap_values(FieldId field, int component, RealArray& values);

  real* x() { return data(kPosition, 0); }
  real* y() { return data(kPosition, 1); }
  real* z() { return data(kPosition, 2); }
  real* vx() { return data(kVelocity, 0); }
  real* vy() { return data(kVelocity, 1); }
  real* vz() { return data(kVelocity, 2); }
  real* mass() { return data(kMass); }
  const real* x() const { return data(kPosition, 0); }
  const real* y() const { return data(kPosition, 1); }
  const real* z() const { return data(kPosition, 2); }
  const real* vx() const { return data(kVelocity, 0); }
  const real* vy() const { return data(kVelocity, 1); }
  const real* vz() const { return data(kVelocity, 2); }
  const real* mass() const { return data(kMass); }
  const std::int64_t* ids() const { return ids_.data(); }

  // Replaces every particle by `ids.size()` zeroed ones with these ids (a restart fills in
  // the fields): distinct, in 0..next_id-1, where next_id is the id the next particle created
  // takes (ids are never reused, so removed particles leave gaps).
  void reset(std::vector<std::int64_t> ids, std::int64_t next_id);
  // A distributed run's reset: this rank's share of a set of `global` particles (ids in
  // 0..next_id-1, each on one rank), not yet placed.
  void reset_share(std::vector<std::int64_t> ids, std::size_t global, std::int64_t next_id);

  // Removes the particles whose `drop` entry is non-zero, keeping the others' order and ids:
  // an id, once given, names one particle for the whole life of the scene, and is never
  // given again. Collective in a distributed run (the global count; ghosts are dropped).
  // Returns how many this rank removed.
  std::size_t remove(const std::vector<char>& drop);

  // Reorders every field: particle i of the result is particle order[i] of before.
  // `buffer`: an array to gather into, which trades places with each field's array in turn
  // (else permute takes its own); it holds one of them, reordered, afterwards.
  void permute(std::span<const std::uint32_t> order, RealArray* buffer = nullptr);
  // This process's particles in ascending id order: order_by_id()[k] is the memory index of
  // the particle with the k-th smallest id (what files written in id order follow).
  std::vector<std::uint32_t> order_by_id() const;
  // index_of_id()[id]: the current index of the particle with that id, kNoIndex for an id
  // no particle has now (removed); one entry per id ever given, so for tests and checks.
  static constexpr std::uint32_t kNoIndex = 0xffffffffu;
  std::vector<std::uint32_t> index_of_id() const;

 private:
  struct Field {
    FieldSpec spec;
    std::vector<RealArray> data;  // one array per component; empty once freed
    bool live = true;
    bool declared = true;  // declared in the current round
  };
  void fill(Field& field) const;  // zeroed arrays for every particle
  std::vector<Field> fields_;
  IdArray ids_;
  std::size_t ghosts_ = 0, global_ = 0, unplaced_ = 0;
  std::int64_t next_id_ = 0, settled_ = 0;
  bool distributed_ = false;
  bool frozen_ = false;
  void check_not_frozen(const char* what) const;
  void resize_all(std::size_t n);  // every live field and the ids
  // permute()'s buffer for the ids, kept so that reordering allocates nothing.
  IdArray id_scratch_;
};

// Throws unless the ids are distinct and in 0..next_id-1 (what a restart's must be).
void check_ids(std::span<const std::int64_t> ids, std::int64_t next_id);

// Throws, before anything is allocated, when `count` more particles (on top of those there
// are) would not fit in this machine's memory at 300 bytes each in single precision and 400 in
// double, the budgets of the PBF dam break measured at a million particles (docs/performance.md).
// `what` names the request.
void check_memory_for(const Particles& particles, double count, const std::string& what);

}  // namespace pbf
