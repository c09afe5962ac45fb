#!/usr/bin/env bash
# The original study's MPI tables on this machine (strong and weak scaling at 1 and 2 ranks,
# 2 ranks x 1 thread against 1 process x 2 threads, the per-phase profile with
# communication): share/benchmarks/mpi_scaling.py says what each is. About 5 minutes on 2 cores.
#
#   share/benchmarks/mpi_scaling.sh [--repeats 5] [--out docs/performance] [--binary build/pbfengine]
set -euo pipefail
here="$(cd "$(dirname "$0")" && pwd)"
exec python3 "$here/mpi_scaling.py" "$@"
