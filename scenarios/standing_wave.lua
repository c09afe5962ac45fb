-- standing_wave.lua: the first sloshing mode of a rectangular tank. Water H deep in a tank L
-- long starts at rest with its surface at H + A cos(k x), k = pi / L, and sloshes: the
-- surface rises at one end as it falls at the other, with the period of linear theory,
--
--   omega^2 = g k tanh(k H),   period = 2 pi / omega,
--
-- for an amplitude A small against H (5% by default). A slab a few spacings thick between
-- free-slip walls makes it two-dimensional. Gauges (water heights) at both ends (`left`,
-- `right`) and an eighth of the tank from each (`in.left`, `in.right`) every 0.005 s;
-- share/validation/standing_wave.py measures the period and the decay per period from the
-- difference of the inner two (docs/validation/standing_wave.md).
--
--   pbfengine run scenarios/standing_wave.lua [-v spacing=0.005] [-v csv=FILE]
--
-- Variables: spacing (m, default 0.005), length (L, default 0.4 m), depth (H, default 0.2 m),
-- amplitude (A, default 0.05 H), periods (how long to run, default 5 linear periods),
-- thickness (the slab's, in spacings, default 4), iterations (pbf, default the style's),
-- xsph (XSPH c, default 0.01), contact and wall_density (the box's, default the style's),
-- support (the kernel radius h in spacings, default 2; 2.5 keeps the period within 1% of
-- linear theory, 2 runs it 7 to 10% fast: docs/validation/standing_wave.md),
-- dt (default 0.4 h / sqrt(2 g H)), csv (thermo CSV, default none), out (frame directory,
-- default none), solver ("pbf", the default, "wcsph": share/lua/solvers.lua, with its alpha,
-- density, diffusion and negative_pressure, or "dfsph", with its error, divergence_error,
-- max_iterations and nu: default 1e-4 m^2/s here, whose own decay of the wave is 1% a period
-- against solvers.lua's 1e-3's 9%, docs/validation/dfsph.md).
local here = debug.getinfo(1, "S").source:match("^@(.*[/\\])") or "./"
package.path = here .. "../share/lua/?.lua;" .. package.path
local g = 9.81
local s = var.spacing or 0.005
local L = var.length or 0.4
local H = var.depth or 0.2
local A = var.amplitude or 0.05 * H
local W = (var.thickness or 4) * s          -- the slab's thickness
local h = (var.support or 2) * s          -- the kernel radius, in spacings
local k = math.pi / L
local period = 2 * math.pi / math.sqrt(g * k * math.tanh(k * H))
local dt = var.dt or 0.4 * h / math.sqrt(2 * g * H)
assert(A > 0 and A < 0.5 * H, "amplitude must be between 0 and half the depth")

pbf.domain{lo = {0, 0, 0}, hi = {L, W, 2 * H}}
pbf.kernel_radius(h)
pbf.timestep(dt)
-- Column by column: the lattice's sites up to the inclined surface (to the nearest layer).
local columns = math.floor(L / s + 1e-9)       -- each at least a spacing wide: one site across
for i = 0, columns - 1 do
  local x = (i + 0.5) * L / columns
  local top = H + A * math.cos(k * x)
  pbf.lattice{lo = {i * L / columns, 0, 0}, hi = {(i + 1) * L / columns, W, math.floor(top / s + 0.5) * s},
              spacing = s}
end

pbf.fix("gravity", "gravity", {})
local solver = var.solver or "pbf"
if solver == "wcsph" then
  require("solvers").wcsph{alpha = var.alpha, density = var.density, diffusion = var.diffusion,
                              negative_pressure = var.negative_pressure}
elseif solver == "dfsph" then
  require("solvers").dfsph{error = var.error, divergence_error = var.divergence_error, nu = var.nu or 1e-4,
                           max_iterations = var.max_iterations}
else
  pbf.fix("pbf", "pbf", {iterations = var.iterations})
  pbf.fix("xsph", "xsph", {c = var.xsph or 0.01})
end
pbf.fix("walls", "box", {contact_distance = var.contact, wall_density = require("flag")(var.wall_density, true, "wall_density")})
if var.out then pbf.fix("frames", "dump/text", {path = var.out .. "/frame_*.txt", interval = 0.02}) end

pbf.compute("left", "gauge", {points = {{0, W / 2, 0}}})
pbf.compute("right", "gauge", {points = {{L, W / 2, 0}}})
pbf.compute("in", "gauge", {points = {{L / 8, W / 2, 0}, {7 * L / 8, W / 2, 0}}, labels = {"left", "right"}})
pbf.compute("ke", "kinetic_energy")
local dt_typical = solver == "wcsph" and 0.15 * h / (10 * math.sqrt(2 * g * H)) or dt
pbf.thermo{every = math.max(1, math.floor(0.005 / dt_typical + 0.5)), csv = var.csv,
           columns = {"step", "time", "left", "right", "in.left", "in.right", "ke"}}

print(string.format("standing wave (%s): %d particles, L = %g m, H = %g m, A = %g m, linear period %.4f s",
                    solver, pbf.count(), L, H, A, period))
pbf.run_until((var.periods or 5) * period)
