#include "engine/core/particle_flow.hpp"

#include "engine/core/particles.hpp"
#include "engine/distributed/comm.hpp"
#include "engine/io/bytes.hpp"

namespace pbf {

// (Few particles pass in a step: a plain loop.)
void ParticleFlow::count_marked(const Particles& P, const std::vector<char>& flag) {
  std::int64_t count = 0;
  ExactSum mass;
  for (std::size_t i = 0; i < P.size(); ++i)
    if (flag[i]) {
      ++count;
      mass.add(double(P.mass()[i]));
    }
  add(count, mass, P.distributed());
}

void ParticleFlow::count_from(const Particles& P, std::size_t first) {
  ExactSum mass;
  for (std::size_t i = first; i < P.size(); ++i) mass.add(double(P.mass()[i]));
  add(static_cast<std::int64_t>(P.size() - first), mass, P.distributed());
}

void ParticleFlow::add(std::int64_t count, ExactSum& mass, bool distributed) {
  if (distributed) {
    count = comm::sum(count);
    comm::sum(mass);
  }
  count_ += count;
  mass_.merge(mass);
}

void ParticleFlow::save(ByteWriter& w) const {
  w.put(count_);
  w.put(mass_.words());
  w.put(mass_.specials());
}

void ParticleFlow::restore(ByteReader& r) {
  count_ = r.get<std::int64_t>();
  mass_.set_words(r.get<std::array<std::int64_t, ExactSum::kWords>>());
  mass_.set_specials(r.get<std::array<std::uint32_t, 3>>());
}

}  // namespace pbf
