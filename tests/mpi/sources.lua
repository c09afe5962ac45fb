-- tests/mpi/sources.lua: a scene built from every kind of particle source, for the
-- distributed-run tests (tests/mpi/run.py, case "sources"): particle files (-v file=CSV, -v
-- vtu=VTU, a dump/vtk frame), a
-- lattice, a second lattice on some of its sites (coincident particles, moved apart at the
-- start), a lattice filling a sphere, and a solid across the fluid that leaves particles out
-- (ids renumbered across the ranks). After the first run a second solid leaves more out (the
-- particles are placed by then), and after the second a lattice is added. Every rank creates its
-- share of each source: the script prints each rank's count before the first run.
-- Writes OUT/f_*.txt (id, position, velocity, density) and OUT/thermo.csv.
local s = 0.02
local out = var.out or "out/sources"
pbf.domain{lo = {0, 0, 0}, hi = {0.8, 0.3, 0.5}}
pbf.kernel_radius(2 * s)
pbf.timestep(0.002)
pbf.read_particles(var.file)                                          -- x < 0.2
pbf.read_particles(var.vtu)                                           -- x > 0.62, z < 0.1
pbf.lattice{lo = {0.2, 0, 0}, hi = {0.36, 0.3, 0.2}, spacing = s}
pbf.lattice{lo = {0.3, 0, 0}, hi = {0.34, 0.04, 0.04}, spacing = s}   -- on the last one's sites
pbf.lattice{lo = {0.42, 0.07, 0.22}, hi = {0.58, 0.23, 0.38}, center = {0.5, 0.15, 0.3}, radius = 0.08,
            spacing = s}
pbf.fix("gravity", "gravity", {acceleration = {0, 0, -9.81}})
pbf.fix("pbf", "pbf", {iterations = 4})
pbf.fix("walls", "box", {})
pbf.fix("post", "solid", {shape = "box", lo = {0.15, 0.1, 0}, hi = {0.25, 0.2, 0.3}})
pbf.compute("ke", "kinetic_energy")
pbf.compute("err", "density_error")
pbf.fix("dump", "dump/text", {path = out .. "/f_*.txt", every = 40, fields = {"id", "position", "velocity", "density"}})
pbf.thermo{every = 10, csv = out .. "/thermo.csv", columns = {"step", "particles", "ke", "err.avg", "err.max"}}
pbf.print_all(string.format("created: %d of %d", pbf.rank_count(), pbf.count()))
pbf.run(80)
pbf.fix("pillar", "solid", {shape = "box", lo = {0.28, 0.0, 0}, hi = {0.32, 0.06, 0.5}})  -- in the fluid
pbf.run(40)
pbf.lattice{lo = {0.6, 0.1, 0.3}, hi = {0.7, 0.2, 0.4}, spacing = s}
pbf.run(40)
print(string.format("sources: %d particles at the end", pbf.count()))
