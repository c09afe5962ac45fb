-- run.lua: reads a scene file (-v file=PATH) and runs it to its final time with the standard PBF
-- pipeline, writing text frames at its output interval (what scenarios/init_file.lua does).
local s = pbf.read_scene(var.file)
pbf.fix("gravity", "gravity", {})
pbf.fix("pbf", "pbf", {})
pbf.fix("walls", "box", {})
pbf.fix("frames", "dump/text", {path = "out/f_*.txt", interval = s.interval})
pbf.run_until(s.t_final)
