-- read.lua: reads a restart (-v file=PATH), declares the pipeline it was written with and runs a step.
pbf.read_restart(var.file)
pbf.fix("gravity", "gravity", {})
pbf.fix("pbf", "pbf", {})
pbf.fix("walls", "box", {})
pbf.fix("frames", "dump/text", {path = "out/f_*.txt", every = 1})
pbf.run(1)
