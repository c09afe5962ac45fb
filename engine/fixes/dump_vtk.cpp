// dump/vtk: one VTK XML unstructured grid (.vtu) per frame, binary appended data, and a
// ParaView collection (.pvd) listing every frame with its simulated time, so ParaView opens
// the whole run as an animation on the right time axis. Positions are the points; the
// chosen fields are point data, in id order.
#include <filesystem>
#include <fmt/format.h>

#include "engine/core/error.hpp"
#include "engine/registry/builtin_styles.hpp"
#include "engine/io/bytes.hpp"
#include "engine/output/dump.hpp"
#include "engine/io/vtu.hpp"
#include "engine/core/simulation.hpp"

namespace pbf {

namespace {

constexpr VtuType kRealType = sizeof(real) == 4 ? VtuType::Float32 : VtuType::Float64;

class DumpVtk : public Dump {
 public:
  DumpVtk(const std::string& id, const Params& p) : Dump(id, "dump/vtk", p), collection_(p.string("collection")) {
    if (collection_.empty()) {  // out/frame_*.vtu -> out/frame.pvd
      std::string stem = std::filesystem::path(pattern()).filename().string();
      stem = stem.substr(0, stem.find('*'));
      while (!stem.empty() && (stem.back() == '_' || stem.back() == '-' || stem.back() == '.')) stem.pop_back();
      collection_ = (std::filesystem::path(pattern()).parent_path() / ((stem.empty() ? "frames" : stem) + ".pvd")).string();
    }
  }

  void save_state(ByteWriter& w) const override {
    Dump::save_state(w);
    w.put<std::uint64_t>(frames_.size());
    for (const auto& [time, file] : frames_) {
      w.put(time);
      w.put_string(file);
    }
  }

  void restore_state(ByteReader& r) override {
    Dump::restore_state(r);
    const auto count = r.get<std::uint64_t>();
    r.require(count, 2 * sizeof(std::uint64_t));
    frames_.resize(count);
    for (auto& [time, file] : frames_) {
      time = r.get<double>();
      file = r.get_string();
    }
  }

 private:
  void write_frame(Simulation& sim, const std::string& path, std::int64_t) override {
    const std::size_t n = sim.particles().size();
    values_.resize(fields().size());
    std::vector<VtuArray> arrays;
    for (std::size_t k = 0; k < fields().size(); ++k) {
      if (fields().is_id(k)) {
        fields().gather_ids(sim, ids_);
        arrays.push_back({"id", 1, VtuType::Int64, ids_.data()});
      } else {
        fields().gather(sim, k, values_[k]);
        arrays.push_back({fields().names()[k], fields().components(k), kRealType, values_[k].data()});
      }
    }
    DumpFields position({"position"});
    position.resolve(sim);
    position.gather(sim, 0, points_);
    write_vtu(path, n, {"Points", 3, kRealType, points_.data()}, arrays);

    // The collection names frames relative to its own directory, as ParaView expects.
    const auto base = std::filesystem::path(collection_).parent_path();
    frames_.emplace_back(sim.time(), std::filesystem::path(path).lexically_relative(base.empty() ? "." : base).string());
    write_pvd(collection_, frames_);
  }

  std::string collection_;
  std::vector<std::pair<double, std::string>> frames_;  // (time, file) of every frame so far
  std::vector<std::vector<real>> values_;
  std::vector<real> points_;
  std::vector<std::int64_t> ids_;
};

}  // namespace

void register_dump_vtk(StyleRegistry& r) {
  auto params = Dump::params("out/frame_*.vtu", {"id", "velocity", "speed", "density"});
  params.push_back({"collection", ParamType::String, std::string(""), "",
                    "the .pvd collection file (default: beside the frames, named after the pattern)"});
  r.add({"dump/vtk", StyleKind::fix, "VTK XML frames (.vtu, binary) and a .pvd collection with their times, for ParaView",
         std::move(params), [](const std::string& id, const Params& p) { return std::make_unique<DumpVtk>(id, p); },
         nullptr});
}

}  // namespace pbf
