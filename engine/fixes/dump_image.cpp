// dump/image: PNG pictures rendered by the engine itself (no Python in the loop), as
// LAMMPS's dump image does: shaded spheres coloured by a field, a labelled colour bar, the
// domain's edges, the simulated time. Rendering is parallel; its cost is this fix's line of
// the timing table.
#include "engine/distributed/comm.hpp"
#include "engine/registry/builtin_styles.hpp"
#include "engine/output/dump.hpp"
#include "engine/render/particle_images.hpp"

namespace pbf {

namespace {

class DumpImage : public Dump {
 public:
  DumpImage(const std::string& id, const Params& p) : Dump(id, "dump/image", p), images_(p) {}
  bool runs_distributed() const override { return true; }  // the particles gathered on rank 0

  void init(Simulation& sim) override {
    images_.init(sim);
    Dump::init(sim);
  }

 private:
  void write_frame(Simulation& sim, const std::string& path, std::int64_t) override {
    const auto& rgb = images_.render(sim);  // every rank: a distributed run gathers on rank 0
    if (comm::root()) write_png(path, images_.width(), images_.height(), rgb);
  }

  ParticleImages images_;
};

}  // namespace

void register_dump_image(StyleRegistry& r) {
  auto params = Dump::params("out/image_*.png", {});
  for (auto& p : ParticleImages::params()) params.push_back(std::move(p));
  r.add({"dump/image", StyleKind::fix, "PNG pictures of the particles: shaded spheres coloured by a field",
         std::move(params), [](const std::string& id, const Params& p) { return std::make_unique<DumpImage>(id, p); },
         nullptr});
}

}  // namespace pbf
