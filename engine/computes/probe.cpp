// probe: pressure, velocity or density at fixed points, SPH-interpolated with Shepard's
// normalisation (the kernel sum in the denominator):
//
//   A(x) = sum_j V_j A_j W(x - x_j) / sum_j V_j W(x - x_j),   V_j = m_j / rho0,  W the kernel (Wendland C2)
//
// over the particles j within h of x. The normalisation makes a probe that sees only part of
// a full neighbourhood (near the free surface, on a wall: an obstacle's pressure sensor) the
// weighted mean of the particles it sees, instead of a sum short of the empty part of the
// kernel. V_j = m_j / rho0 rather than m_j / rho_j: the summed density is low at a free
// surface only because the kernel misses neighbours there, which would overweight surface
// particles; with uniform masses V cancels anyway. A probe with no particle within h reads 0
// (dry).
//
// A is the solver's "pressure" field (gauge pressure, 0 at a free surface: wcsph's equation
// of state, pbf's from its multipliers, docs/physics.md "Pressure in PBF"), the velocity, or
// the density the solver uses (Simulation::solver_density). Each point's sum runs serially in
// the fixed order of PointQuery, so the values have the same bits at any thread count. Near a
// periodic face the sum reaches the particles across it (their images, in the point cells).
#include <fmt/format.h>

#include "engine/computes/point_compute.hpp"
#include "engine/core/error.hpp"
#include "engine/core/simulation.hpp"
#include "engine/registry/builtin_styles.hpp"
#include "engine/distributed/comm.hpp"
#include "engine/sph/point_query.hpp"

namespace pbf {

namespace {

class Probe : public PointCompute {
 public:
  Probe(const std::string& id, const Params& p)
      : PointCompute(id, "probe", p), field_(p.string("field")),
        unit_(field_ == "pressure" ? "Pa" : field_ == "velocity" ? "m/s" : "kg/m^3") {
    // Names: the label itself for a scalar field when labels are given (a sensor's name),
    // else the field's symbol and the point's number; '.' is thermo's separator, hence "_vx".
    for (const auto& label : labels_) {
      if (field_ == "velocity") {
        for (const char* c : {"vx", "vy", "vz"})
          names_.push_back(labelled_ ? fmt::format("{}_{}", label, c) : fmt::format("{}{}", c, label));
      } else {
        names_.push_back(labelled_ ? label : (field_ == "pressure" ? "p" : "rho") + label);
      }
    }
  }

  std::vector<std::string> names() const override { return names_; }
  std::vector<std::string> units() const override { return std::vector<std::string>(names_.size(), unit_); }
  bool runs_distributed() const override { return true; }  // each point measured by the rank whose box holds it
  bool reads_pressure() const { return field_ == "pressure"; }

  void evaluate(Simulation& sim, std::vector<double>& values) override {
    check_inside(sim.domain());  // a domain changed since the last check
    const auto& P = sim.particles();
    // The density first: its sums may rebuild the ghosts, which moves every array; the point
    // cells then find them current. Pointers into the particles only after both (a density
    // field's too: the point cells may rebuild the ghosts, periodic images included).
    if (field_ == "density") sim.solver_density();
    const NeighborGrid& cells = sim.point_cells();
    const real* density = field_ == "density" ? sim.solver_density() : nullptr;  // current: no rebuild
    const real* a[3] = {nullptr, nullptr, nullptr};
    int components = 1;
    if (field_ == "velocity") {
      a[0] = P.vx(), a[1] = P.vy(), a[2] = P.vz();
      components = 3;
    } else if (field_ == "density") {
      a[0] = density;
    } else {
      const auto pressure = P.find("pressure");
      if (!pressure)
        throw Error(fmt::format("compute '{}' (probe): parameter 'field' is \"pressure\", but no fix keeps a "
                                "pressure field (pbf and wcsph declare one when a run starts: run first)",
                                id()));
      a[0] = P.data(*pressure);
    }
    const Kernels& K = sim.kernels();
    const real* m = P.mass();
    const PointQuery query(cells, P.x(), P.y(), P.z(), sim.kernel_radius());
    const std::size_t n = points_.size();
    values.assign(n * static_cast<std::size_t>(components), 0.0);
#pragma omp parallel for schedule(dynamic)
    for (std::size_t k = 0; k < n; ++k) {
      if (!sim.measures_at(points_[k][0], points_[k][1], points_[k][2])) continue;  // another rank's
      double weight = 0, sum[3] = {0, 0, 0};
      query.for_each_near(points_[k][0], points_[k][1], points_[k][2],
                          [&](std::uint32_t j, double, double, double, double r2) {
                            const double w = double(m[j]) * K.W(real(r2));  // rho0 V_j W
                            weight += w;
                            for (int c = 0; c < components; ++c) sum[c] += w * a[c][j];
                          });
      if (weight > 0)  // else dry: 0
        for (int c = 0; c < components; ++c) values[k * components + c] = sum[c] / weight;
    }
    if (P.distributed()) comm::sum(std::span<double>(values));  // each value from the one rank that measured it
  }

 private:
  const char* inside_solid_reads() const override { return "it reads 0"; }

  std::string field_, unit_;
  std::vector<std::string> names_;
};

}  // namespace

bool computes_read_pressure(const Simulation& sim) {
  for (const auto& c : sim.computes())
    if (const auto* probe = dynamic_cast<const Probe*>(c.get()); probe && probe->reads_pressure()) return true;
  return false;
}

void register_compute_probe(StyleRegistry& r) {
  r.add({"probe",
         StyleKind::compute,
         "pressure (Pa), velocity (m/s) or density (kg/m^3) at points, kernel-interpolated (Shepard)",
         {{"points", ParamType::PointList, std::nullopt, "m", "the probe points {{x, y, z}, ...} (inside the domain)"},
          ParamSpec{"field", ParamType::String, std::string("pressure"), "",
                    "what to sample: pressure (gauge, the solver's), velocity, density (the solver's)"}
              .one_of({"pressure", "velocity", "density"}),
          ParamSpec{"labels", ParamType::StringList, std::nullopt, "",
                    "one name per point (default: the values are p1.., rho1.., vx1, vy1, vz1, ..)", true}},
         nullptr, make_compute<Probe>(),
         "one per point: `p1`, `p2`, ... (Pa), `rho1`, ... (kg/m^3) or `vx1`, `vy1`, `vz1`, ... (m/s); with "
         "`labels`, `LABEL` (`LABEL_vx`, ...); near a periodic face the sums take in the particles across it"});
}

}  // namespace pbf
