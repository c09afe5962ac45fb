-- output_cost.lua: what output costs, measured on the dam break (vorticity and XSPH on).
-- Without -v style, it builds the scene, lets the column start to fall and writes a restart
-- (its size and write time are results). With -v style=K, it reads that restart and runs
-- `steps` steps with output K alone writing a frame every `every` steps (K = 0: no output,
-- the baseline), so every measurement runs exactly the same steps. Each output's line of
-- the timing table over its frames is its cost per frame; the run's wall time against the
-- baseline's shows work done elsewhere (ffmpeg encodes in its own process).
-- share/benchmarks/output_cost.sh runs it all and prints medians.
--
--   pbfengine run share/benchmarks/output_cost.lua -v out=DIR [-v particles=30000]
--   pbfengine run share/benchmarks/output_cost.lua -v out=DIR -v style=K
local out = var.out or "/tmp/pbf-output-cost"
local steps = var.steps or 100
local every = var.every or 10
local start = out .. "/start.restart"

local outputs = {
  {"dump/text", {path = out .. "/text/frame_*.txt"}, "dump/text"},
  {"dump/text", {path = out .. "/text-all/frame_*.txt", fields = {"id", "position", "velocity", "density", "speed"}},
   "dump/text with density"},
  {"dump/vtk", {path = out .. "/vtk/frame_*.vtu", fields = {"id", "velocity"}}, "dump/vtk id+velocity"},
  {"dump/vtk", {path = out .. "/vtk-density/frame_*.vtu"}, "dump/vtk default fields (with density)"},
  {"dump/image", {path = out .. "/image/image_*.png"}, "dump/image"},
  {"dump/movie", {path = out .. "/movie.mp4"}, "dump/movie"},
  {"restart", {path = out .. "/periodic/r.*.restart"}, "restart fix"},
}

local function pipeline()
  pbf.fix("gravity", "gravity", {})
  pbf.fix("pbf", "pbf", {})
  pbf.fix("walls", "box", {})
  pbf.fix("vorticity", "vorticity", {})
  pbf.fix("xsph", "xsph", {})
end

if not var.style then
  local N = var.particles or 30000
  local a, g = 0.1, 9.81
  local layers = math.floor(N ^ (1 / 3) + 0.5)
  local s = a / layers
  local h = 2 * s
  pbf.domain{lo = {0, 0, 0}, hi = {5 * a, layers // 2 * s, 4 * a}}
  pbf.kernel_radius(h)
  pbf.timestep(0.4 * h / math.sqrt(2 * g * 2 * a))
  pbf.lattice{lo = {0, 0, 0}, hi = {a, layers // 2 * s, 2 * a}, spacing = s}
  pipeline()
  pbf.run(100)   -- frames of a moving fluid
  local r = pbf.write_restart(start)
  print(string.format("RESULT restart write %.6f s (%d particles, %d bytes, %.1f bytes/particle)",
                      r.seconds, r.particles, r.bytes, r.bytes / r.particles))
  return
end

local r = pbf.read_restart(start)
print(string.format("RESULT restart read %.6f s", r.seconds))
pipeline()
local k = math.tointeger(var.style)
local name = "no output"
if k > 0 then
  local style, params
  style, params, name = table.unpack(outputs[k])
  params.every = every
  pbf.fix("out", style, params)
end
pbf.run(steps)
local t = pbf.timing()
print(string.format("RESULT %s wall %.6f s", name, t.wall))
if k > 0 then
  local frames = steps // every   -- in the run; frame 0 is written by init, outside the table
  for _, row in ipairs(t.rows) do
    if row.label:find("^out ") then print(string.format("RESULT %s fix %.6f s/frame", name, row.seconds / frames)) end
  end
end
