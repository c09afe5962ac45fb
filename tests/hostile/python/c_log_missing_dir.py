# a log in a directory that does not exist: the run goes on without it
# Expected: warned, nodir/x.log
import pbfengine
pbfengine.Simulation(log="nodir/x.log", log_level="warn")
