"""The Python module under mpirun (docs/python.md#mpi): each rank holds its share of the
particles, gather() brings every rank's to rank 0 in id order, and the run gives the same bits
as one process. Skipped where mpirun or mpi4py is missing."""
import os
import shutil
import subprocess
import sys

import numpy as np
import pytest

import pbfengine

PROGRAM = """
from mpi4py import MPI   # started first: the engine joins it
import sys, numpy as np, pbfengine
sim = pbfengine.Simulation(log=None, threads=1)
sim.domain(lo=(0, 0, 0), hi=(0.3, 0.05, 0.3))
sim.kernel_radius(0.02)
sim.timestep(0.002)
sim.lattice(lo=(0, 0, 0), hi=(0.1, 0.05, 0.2), spacing=0.01)
sim.fix("gravity", "gravity")
sim.fix("solver", "pbf", iterations=4)
sim.fix("walls", "box")
sim.run(40)
counts = MPI.COMM_WORLD.gather(sim.rank_count, root=0)
gathered = sim.gather("position")
if pbfengine.rank() == 0:
    assert pbfengine.ranks() == MPI.COMM_WORLD.Get_size()
    np.save(sys.argv[1], gathered["position"])
    np.save(sys.argv[2], np.array(counts))
"""


@pytest.mark.skipif(shutil.which("mpirun") is None, reason="no mpirun")
def test_ranks_share_the_particles_and_gather_the_same_bits(tmp_path):
    pytest.importorskip("mpi4py")
    (tmp_path / "program.py").write_text(PROGRAM)
    module_dir = os.path.dirname(os.path.dirname(os.path.abspath(pbfengine.__file__)))
    env = dict(os.environ, PYTHONPATH=module_dir, OMPI_ALLOW_RUN_AS_ROOT="1", OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1", OMPI_MCA_rmaps_base_oversubscribe="1")
    subprocess.run(["mpirun", "-np", "2", sys.executable, "program.py", "gathered.npy", "counts.npy"], cwd=tmp_path,
                   env=env, check=True, timeout=300)
    counts = np.load(tmp_path / "counts.npy")
    assert len(counts) == 2 and counts.sum() == 1000 and counts.min() > 0  # shared, not copied
    # One process, the same scene.
    sim = pbfengine.Simulation(log=None, threads=1)
    sim.domain(lo=(0, 0, 0), hi=(0.3, 0.05, 0.3))
    sim.kernel_radius(0.02)
    sim.timestep(0.002)
    sim.lattice(lo=(0, 0, 0), hi=(0.1, 0.05, 0.2), spacing=0.01)
    sim.fix("gravity", "gravity")
    sim.fix("solver", "pbf", iterations=4)
    sim.fix("walls", "box")
    sim.run(40)
    one = sim.gather("position")
    assert np.array_equal(one["id"], np.arange(1000))
    assert np.array_equal(np.load(tmp_path / "gathered.npy"), one["position"])
