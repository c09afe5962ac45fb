# read_restart(pathlib.Path('nope.restart')) of a missing file
# Expected: refused, Error: nope.restart && no such file
import pathlib
import pbfengine
sim = pbfengine.Simulation(log=None, log_level="warn")
sim.read_restart(pathlib.Path("nope.restart"))
