// gauge: water-level gauges, as DualSPHysics's MeasureTool measures them. Each point (x, y, z0)
// is the foot of a vertical line up to the domain top; along it, the kernel-normalised fluid
// fraction
//
//   f(z) = sum_j V_j W((x, y, z) - x_j),   V_j = m_j / rho0,  W the kernel (Wendland C2)
//
// is 1 inside the fluid (the mass rule makes sum_j m_j W = rho0 for a full neighbourhood)
// and 1/2 on a flat free surface, which lies half a spacing above the top particles' centres.
// Within h of a wall the kernel reaches behind it, where no particle can be: there f is taken
// over the kernel's share on the fluid side, f / (1 - w) with w = rho_wall / rho0 the walls'
// density share (DensityBoundary, as the solvers see it), so that a gauge along a wall or in
// a corner reads like one in the open (w = 0 where the pipeline has no wall density). Where
// 1 - w < 0.1 (inside a solid) the line holds no water.
// The level is the highest z where f reaches 1/2: f is sampled every quarter spacing (s, the
// lattice spacing of the particles' mean mass) from the top down, and the crossing is refined
// linearly between the samples around it. The value is the level minus z0 (m); 0 when f stays
// below 1/2 on the whole line (dry). A lone droplet has f = V W(0) ~ 0.2 at h = 2s, so spray
// above the surface does not count; a thick enough sheet does.
//
// Near a periodic face the sums reach the particles across it (their periodic images, which the
// point cells hold), so a gauge there reads as one in the middle.
// Each sum runs serially in PointQuery's fixed order: the same bits at any thread count, and on
// any number of ranks (each sample is measured by the rank whose box holds it).
#include <algorithm>
#include <cmath>

#include "engine/computes/point_compute.hpp"
#include "engine/core/simulation.hpp"
#include "engine/registry/builtin_styles.hpp"
#include "engine/sph/mass.hpp"
#include "engine/distributed/comm.hpp"
#include "engine/sph/point_query.hpp"

namespace pbf {

namespace {

class Gauge : public PointCompute {
 public:
  Gauge(const std::string& id, const Params& p) : PointCompute(id, "gauge", p) {
    for (const auto& label : labels_) names_.push_back(labelled_ ? label : "h" + label);
  }

  std::vector<std::string> names() const override { return names_; }
  std::vector<std::string> units() const override { return std::vector<std::string>(names_.size(), "m"); }
  bool runs_distributed() const override { return true; }  // each sample measured by the rank whose box holds it

  void evaluate(Simulation& sim, std::vector<double>& values) override {
    check_inside(sim.domain());  // a domain changed since the last check
    const auto& P = sim.particles();
    values.assign(points_.size(), 0.0);
    if (sim.global_count() == 0) return;  // all dry (and no mean mass to take a spacing from)
    const Kernels& K = sim.kernels();
    const double inv_rho0 = 1 / sim.rest_density(), top = sim.domain().hi[2];
    const double spacing = lattice_spacing(sim.particle_mass(), K, sim.rest_density());
    const NeighborGrid& cells = sim.point_cells();  // may rebuild the ghosts: pointers after it
    const PointQuery query(cells, P.x(), P.y(), P.z(), sim.kernel_radius());
    const real* m = P.mass();
    const auto& walls = sim.density_boundaries();
    // Samples z0 + i dz along each line, i = 0..count, the last exactly at the top, at most a
    // quarter spacing apart; the fluid fraction at each, by the rank that measures there.
    std::vector<std::size_t> first(points_.size() + 1, 0);
    for (std::size_t k = 0; k < points_.size(); ++k)
      first[k + 1] = first[k] + samples(points_[k][2], top, spacing) + 1;
    std::vector<double> f(first.back(), 0.0);
#pragma omp parallel for schedule(dynamic)
    for (std::size_t s = 0; s < f.size(); ++s) {
      const std::size_t k = static_cast<std::size_t>(std::upper_bound(first.begin(), first.end(), s) - first.begin()) - 1;
      const double x = points_[k][0], y = points_[k][1];
      const double z = sample_z(points_[k][2], top, spacing, s - first[k]);
      if (!sim.measures_at(x, y, z)) continue;  // another rank's
      double sum = 0;
      query.for_each_near(x, y, z, [&](std::uint32_t j, double, double, double, double r2) {
        sum += double(m[j]) * inv_rho0 * K.W(real(r2));
      });
      if (!walls.empty()) {
        real wall = 0, grad[3] = {0, 0, 0};
        for (const DensityBoundary* b : walls)
          b->add_density(sim, real(x), real(y), real(z), DensityBoundary::kNoParticle, wall, grad);
        const double room = 1 - wall * inv_rho0;  // the kernel's share on the fluid side
        sum = room < 0.1 ? 0.0 : sum / room;
      }
      f[s] = sum;
    }
    if (P.distributed()) comm::sum(std::span<double>(f));  // each sample from the one rank that measured it
    for (std::size_t k = 0; k < points_.size(); ++k) {
      const double z0 = points_[k][2];
      const std::size_t count = first[k + 1] - first[k] - 1;
      if (count == 0) continue;  // a foot on the top face: no line
      // From the top down: the first sample that reaches 1/2 is the highest one.
      double above = f[first[k] + count];
      if (above >= 0.5) {  // full to the top
        values[k] = top - z0;
        continue;
      }
      const double dz = (top - z0) / static_cast<double>(count);
      for (std::size_t i = count; i-- > 0;) {
        const double z = sample_z(z0, top, spacing, i), fi = f[first[k] + i];
        if (fi >= 0.5) {
          values[k] = z + dz * (fi - 0.5) / (fi - above) - z0;
          break;
        }
        above = fi;
      }
    }
  }

 private:
  // The samples along a line from z0 to the top: count + 1 of them (none above a foot on the top).
  static std::size_t samples(double z0, double top, double spacing) {
    const double count = std::ceil((top - z0) / (0.25 * spacing));
    return count > 0 ? static_cast<std::size_t>(count) : 0;
  }
  static double sample_z(double z0, double top, double spacing, std::size_t i) {
    const std::size_t count = samples(z0, top, spacing);
    if (i == count) return top;
    return z0 + static_cast<double>(i) * ((top - z0) / static_cast<double>(count));
  }

  const char* inside_solid_reads() const override {
    return "the depth it reads is measured from inside the solid";
  }

  std::vector<std::string> names_;
};

}  // namespace

void register_compute_gauge(StyleRegistry& r) {
  r.add({"gauge",
         StyleKind::compute,
         "water depth (m) along vertical lines: the highest z where the fluid fraction reaches 1/2, above each foot",
         {{"points", ParamType::PointList, std::nullopt, "m",
           "the foot {x, y, z} of each gauge line, which runs up to the domain top"},
          ParamSpec{"labels", ParamType::StringList, std::nullopt, "",
                    "one name per gauge (default: the values are h1, h2, ..)", true}},
         nullptr, make_compute<Gauge>(),
         "one per point: `h1`, `h2`, ..., or `LABEL` with `labels` (m); near a periodic face the fraction counts "
         "the fluid across it, so a gauge there reads as one in the middle"});
}

}  // namespace pbf
