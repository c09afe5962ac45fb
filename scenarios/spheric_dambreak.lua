-- spheric_dambreak.lua: the SPHERIC benchmark Test 2 (Kleefsman et al. 2005, J. Comput. Phys.
-- 206:363-393; the MARIN experiment): a 3D dam break against a box. A water column 1.228 m
-- long and 0.55 m high, as wide as the tank (3.22 x 1 x 1 m), stands against the wall x = 3.22
-- and is released at t = 0; it runs along the floor towards x = 0, hits a 0.161 x 0.403 x
-- 0.161 m box (its face x = 0.8245 towards the water), is thrown over and around it, and
-- reaches the wall x = 0. Pressure probes P1-P8 sit on the box (P1-P4 on the face the water
-- hits, P5-P8 on its top) and water-height gauges at x = 0.496, 0.992, 1.488 and 2.638 m,
-- y = 0.5, as in the experiment (../shared/validation/spheric_test2_geometry.csv: x from the
-- wall on the obstacle's side, y across, z up). share/validation/spheric_dambreak.sh runs it
-- and share/validation/spheric_compare.py compares it with the measurements
-- (docs/validation/spheric.md).
--
--   pbfengine run scenarios/spheric_dambreak.lua [-v solver=pbf] [-v spacing=0.03] [-v t_end=2]
--                                                [-v out=out/spheric]
--
-- Variables:
--   solver        "pbf" (default) or "wcsph" (weakly compressible SPH, share/lua/solvers.lua;
--                 alpha passes to sph_viscosity, default 0.1, and density, "continuity" by
--                 default or "summation", and diffusion (delta-SPH, default 0.1 with the
--                 continuity density), to wcsph), or "dfsph" (divergence-free SPH: error,
--                 divergence_error, max_iterations, nu and courant pass to it)
--   spacing       particle spacing (m), default 0.03; adjusted to the nearest spacing that
--                 divides the column's height 0.55 m into whole layers (0.04 -> 0.03929,
--                 0.03 -> 0.03056, 0.02 -> 0.01964); h = support x spacing
--   support       the kernel's radius in spacings, default 2
--   lid           the height of the tank's closed top (m), default 1 (the experiment's tank
--                 is open: a higher lid lets a splash rise as it would there)
--   friction      the walls' and the box's friction, a tangential velocity decay rate (1/s,
--                 default 0: free slip); no_slip = 1 stops the fluid's tangential motion at
--                 the box (the box fix has no no-slip)
--   t_end         simulated time (s), default 2
--   out           output directory, default "out/spheric" (created)
--   probes        1 (default): the probe, gauge and sample styles; 0 leaves them out
--   probe_offset  how far in front of the box's faces the pressure probes sit, into the
--                 fluid, in spacings (default 0.5: on the first layer of particles; 0 puts
--                 them on the faces, where the probe's Shepard normalisation averages over
--                 the fluid side: noisier, docs/validation/spheric.md compares the two)
--   interval      seconds between rows of OUT/probes.csv (default 0.001)
--   error, max_iterations   pbf's accuracy target, the mean compression (default 0.002,
--                 reached within at most 40 iterations); iterations: a fixed count instead
--   vorticity, xsph  pbf's vorticity confinement epsilon and XSPH c (the styles' defaults,
--                 0.05 and 0.01; 0 leaves the style out)
--   dt            PBF time step (s), default 0.4 h / sqrt(2 g 0.55); with wcsph the largest
--                 step cfl may take
--   images, movie, vtk  pictures, a movie, ParaView frames (share/lua/outputs.lua)
-- Writes OUT/probes.csv (time, P.P1..P.P8 in Pa, H.x0496, H.x0992, H.x1488, H.x2638 in m: the
-- gauges named by their x in mm) and OUT/thermo.csv (thermo every ~0.02 s: time, dt, the
-- surge front (1st percentile of x), the x force on the box, err.max, v.max).
-- The probes read the solver's pressure field: wcsph's equation of state, or with pbf the
-- pressure of its multipliers (docs/physics.md, "Pressure in PBF"). Should the probe style
-- refuse it, the run goes on with the gauges only, and says so.
local here = debug.getinfo(1, "S").source:match("^@(.*[/\\])") or "./"
package.path = here .. "../share/lua/?.lua;" .. package.path
local solver = var.solver or "pbf"
assert(solver == "pbf" or solver == "wcsph" or solver == "dfsph",
       "solver must be pbf, wcsph or dfsph, got " .. tostring(solver))
local t_end = var.t_end or 2.0
local out = var.out or "out/spheric"
local probes = require("flag")(var.probes, true, "probes")
local g = 9.81

-- The experiment (spheric_test2_geometry.csv).
local L, W = 3.22, 1.0                            -- the tank
local Ht = var.lid or 1.0                         -- its lid (the experiment's tank is open)
local col_x0, col_len, col_h = 1.992, 1.228, 0.55 -- the water column, against the wall x = L
local box_lo, box_hi = {0.6635, 0.2955, 0.0}, {0.8245, 0.6985, 0.161}
local sensors = {                                 -- x, y, z, and the normal into the fluid
  P1 = {0.8245, 0.471, 0.021, {1, 0, 0}}, P2 = {0.8245, 0.471, 0.061, {1, 0, 0}},
  P3 = {0.8245, 0.471, 0.101, {1, 0, 0}}, P4 = {0.8245, 0.471, 0.141, {1, 0, 0}},
  P5 = {0.8035, 0.471, 0.161, {0, 0, 1}}, P6 = {0.7635, 0.471, 0.161, {0, 0, 1}},
  P7 = {0.7235, 0.471, 0.161, {0, 0, 1}}, P8 = {0.6835, 0.471, 0.161, {0, 0, 1}},
}
local gauges = {{"x0496", 0.496}, {"x0992", 0.992}, {"x1488", 1.488}, {"x2638", 2.638}}

-- Spacing: whole layers in the column's height, so that it starts exactly 0.55 m high.
local nz = math.max(3, math.floor(col_h / (var.spacing or 0.03) + 0.5))
local s = col_h / nz
local nx = math.floor(col_len / s + 0.5)          -- the column's length to the nearest layer
local ny = math.floor(W / s)                      -- as many layers as fit across, centred
local h = (var.support or 2) * s
local dt = var.dt or 0.4 * h / math.sqrt(2 * g * col_h)
local dt_typical = solver == "wcsph" and 0.15 * h / (10 * math.sqrt(2 * g * col_h)) or dt

pbf.domain{lo = {0, 0, 0}, hi = {L, W, Ht}}
pbf.kernel_radius(h)
pbf.timestep(dt)
local y0 = (W - ny * s) / 2
pbf.lattice{lo = {L - nx * s, y0, 0}, hi = {L, y0 + ny * s, nz * s}, spacing = s}

pbf.fix("gravity", "gravity", {acceleration = {0, 0, -g}})
if solver == "dfsph" then  -- its steps by the CFL bound, dt the largest
  require("solvers").dfsph{error = var.error, divergence_error = var.divergence_error, nu = var.nu,
                           max_iterations = var.max_iterations, courant = var.courant}
elseif solver == "wcsph" then
  -- The continuity density with delta-SPH diffusion: the summed density lets the reservoir's
  -- level fall early and rings after the impact (docs/validation/spheric.md).
  local density = var.density or "continuity"
  require("solvers").wcsph{alpha = var.alpha, density = density,
                           diffusion = var.diffusion or (density == "continuity" and 0.1 or nil)}
else
  -- An accuracy target, not a fixed count: at 4 iterations the 0.55 m column settles by about
  -- 3% as it is released, and the reservoir's level falls 0.07 s early (spheric.md).
  local target = var.iterations == nil and var.error == nil
  pbf.fix("pbf", "pbf", {iterations = var.iterations, error = var.error or (target and 0.002 or nil),
                         max_iterations = var.max_iterations or (target and 40 or nil)})
  if (var.vorticity or 1) ~= 0 then pbf.fix("vorticity", "vorticity", {epsilon = var.vorticity}) end
  if (var.xsph or 1) ~= 0 then pbf.fix("xsph", "xsph", {c = var.xsph}) end
end
-- The tank (closed at z = lid) and the obstacle (fluid outside): free slip unless friction says.
local no_slip = require("flag")(var.no_slip, false, "no_slip")
pbf.fix("walls", "box", {friction = var.friction})
pbf.fix("obstacle", "solid", {shape = "box", lo = box_lo, hi = box_hi, friction = var.friction,
                              no_slip = no_slip})

if out ~= "" then os.execute(string.format("mkdir -p '%s'", out)) end
require("outputs").add(out, {color = "speed", min = 0, max = 4, direction = {1, 1.6, -1.2}})

if probes then
  local samples = {}
  -- Pressure probes, probe_offset spacings in front of the box's faces, in the fluid.
  local off = (var.probe_offset or 0.5) * s
  local points, labels = {}, {}
  for i = 1, 8 do
    local p = sensors["P" .. i]
    points[i] = {p[1] + off * p[4][1], p[2] + off * p[4][2], p[3] + off * p[4][3]}
    labels[i] = "P" .. i
  end
  local ok, err = pcall(pbf.compute, "P", "probe", {points = points, field = "pressure", labels = labels})
  if ok then
    samples[#samples + 1] = "P"
  else
    print("spheric: no pressure probes with solver " .. solver .. " (" .. tostring(err) .. ")")
  end
  -- Water-height gauges: the depth above the floor at y = 0.5.
  local gp, gl = {}, {}
  for i, gauge in ipairs(gauges) do gp[i], gl[i] = {gauge[2], 0.5, 0}, gauge[1] end
  pbf.compute("H", "gauge", {points = gp, labels = gl})
  samples[#samples + 1] = "H"
  pbf.fix("probes_out", "sample", {computes = samples, interval = var.interval or 0.001,
                                   file = out .. "/probes.csv"})
end

pbf.compute("front", "front", {axis = "x", percentile = 1})   -- the surge runs towards x = 0
pbf.compute("load", "load", {solid = "obstacle"})
pbf.compute("err", "density_error")
pbf.compute("v", "speed")
pbf.thermo{every = math.max(1, math.floor(0.02 / dt_typical)), csv = out ~= "" and out .. "/thermo.csv" or nil,
           columns = {"step", "time", "dt", "front", "load.fx", "err.max", "v.max"}}

print(string.format("spheric (%s): %d particles, spacing %.5g m (%d x %d x %d), h %.4g m, dt %s%.4g s, to t = %g s",
                    solver, pbf.count(), s, nx, ny, nz, h, solver ~= "pbf" and "<= " or "", dt, t_end))
pbf.run_until(t_end)
