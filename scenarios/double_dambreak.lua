-- double_dambreak.lua: two water columns, a wide and 2a high, stand at both ends of a tank
-- 5a long and are released together. The two surges meet in the middle and throw up a jet
-- higher than either column, which falls back and sends waves to both walls.
-- Symmetric by construction: how symmetric the run stays is a test of the solver.
--
--   pbfengine run scenarios/double_dambreak.lua [-v particles=30000] [-v t_end=1.0] [-v images=0.02]
--
-- Variables: particles (about how many in both columns, default 30000), t_end (default
-- 1.0 s), a (column width, default 0.1 m), out (directory, default "out/double_dambreak"),
-- images (seconds between PNG pictures), movie (an mp4 path), vtk (seconds between
-- ParaView frames); none of the three by default.
package.path = (debug.getinfo(1, "S").source:match("^@(.*[/\\])") or "./") .. "../share/lua/?.lua;" .. package.path
local N = var.particles or 30000
local t_end = var.t_end or 1.0
local a = var.a or 0.1
local out = var.out or "out/double_dambreak"
local g = 9.81

-- Each column a x (a/2) x 2a holds N/2 = (a/s)^3 particles.
local layers = math.max(4, math.floor((N / 2) ^ (1 / 3) + 0.5))
local s = a / layers
local h = 2 * s
local depth = layers // 2 * s
local dt = 0.4 * h / math.sqrt(2 * g * 2 * a)

pbf.domain{lo = {0, 0, 0}, hi = {5 * a, depth, 6 * a}}   -- room for the jet
pbf.kernel_radius(h)
pbf.timestep(dt)
pbf.lattice{lo = {0, 0, 0}, hi = {a, depth, 2 * a}, spacing = s}
pbf.lattice{lo = {4 * a, 0, 0}, hi = {5 * a, depth, 2 * a}, spacing = s}

pbf.fix("gravity", "gravity", {acceleration = {0, 0, -g}})
pbf.fix("pbf", "pbf", {})
pbf.fix("walls", "box", {})
pbf.fix("vorticity", "vorticity", {})
pbf.fix("xsph", "xsph", {})

require("outputs").add(out, {color = "speed", min = 0, max = 2.5, direction = {0.6, 2.2, -0.7}, zoom = 1.4})

pbf.compute("err", "density_error")
pbf.compute("top", "front", {axis = "z", percentile = 99.9})
pbf.compute("box", "extent")
pbf.thermo{every = math.max(1, math.floor(0.01 / dt)), csv = out .. "/thermo.csv",
           columns = {"step", "time", "top", "box.xmin", "box.xmax", "err.avg", "err.max"}}

print(string.format("double dam break: %d particles, a = %g m, spacing %.4g m, dt %.4g s", pbf.count(), a, s, dt))
pbf.run(math.ceil(t_end / dt - 1e-9))
