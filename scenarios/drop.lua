-- drop.lua: a drop falls into a pool. A sphere of water, radius R, starts above a pool of
-- depth D in a square tank with an initial downward speed, hits the surface, makes a crater
-- and a crown, and the pool sloshes. A test of the free surface and of splashes (thin sheets
-- and single particles flying apart) that the dam break does not have.
--
--   pbfengine run scenarios/drop.lua [-v spacing=0.006] [-v t_end=0.6] [-v images=0.02]
--
-- Variables: spacing (particle spacing in m, default 0.006: about 40,000 particles), t_end
-- (default 0.6 s), out (directory, default "out/drop"), images (seconds between PNG
-- pictures, default none), movie (an mp4 path, default none), vtk (seconds between
-- ParaView frames, default none), speed (initial speed of the drop, default 1 m/s).
package.path = (debug.getinfo(1, "S").source:match("^@(.*[/\\])") or "./") .. "../share/lua/?.lua;" .. package.path
local s = var.spacing or 0.006
local t_end = var.t_end or 0.6
local out = var.out or "out/drop"
local L, D, R = 0.3, 0.1, 0.045          -- tank side, pool depth, drop radius
local zc = 0.2                          -- drop centre height
local h = 2 * s
local v_impact = math.sqrt((var.speed or 1) ^ 2 + 2 * 9.81 * (zc - D))
local dt = 0.4 * h / v_impact

pbf.domain{lo = {0, 0, 0}, hi = {L, L, L}}
pbf.kernel_radius(h)
pbf.timestep(dt)
pbf.lattice{lo = {0, 0, 0}, hi = {L, L, D}, spacing = s}
pbf.lattice{lo = {L / 2 - R, L / 2 - R, zc - R}, hi = {L / 2 + R, L / 2 + R, zc + R}, spacing = s,
            center = {L / 2, L / 2, zc}, radius = R, velocity = {0, 0, -(var.speed or 1)}}

pbf.fix("gravity", "gravity", {})
pbf.fix("pbf", "pbf", {})
pbf.fix("walls", "box", {})
pbf.fix("vorticity", "vorticity", {})
pbf.fix("xsph", "xsph", {})

require("outputs").add(out, {color = "speed", min = 0, max = 2, direction = {1, 2, -1.2}, zoom = 1.25})

pbf.compute("err", "density_error")
pbf.compute("top", "front", {axis = "z", percentile = 99.9})
pbf.compute("ke", "kinetic_energy")
pbf.thermo{every = math.max(1, math.floor(0.01 / dt)), csv = out .. "/thermo.csv",
           columns = {"step", "time", "top", "err.avg", "err.max", "ke"}}

print(string.format("drop into a pool: %d particles, spacing %g m, dt %.4g s", pbf.count(), s, dt))
pbf.run(math.ceil(t_end / dt - 1e-9))
