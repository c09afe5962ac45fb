#pragma once
// How many OpenMP threads a run uses, and how they wait (docs/design.md, "Threads").
//
// A run's threads meet at the end of every parallel region; a thread that arrives first
// waits for the others. On a machine the run shares (another run, a build, a browser), the
// one it waits for may not be running, and a thread that spins while it waits takes the core
// that thread needs: two runs at once took three times as long as one after the other. So:
//
// - The default thread count is what the process was given, not the machine's core count:
//   its CPU affinity (taskset, Slurm, a cgroup cpuset), a container's CPU quota, and under
//   MPI its share of the node's cores.
// - Threads spin only briefly at a barrier, then sleep. OpenMP runtimes read how long from the
//   environment as they load, before main (GCC's libgomp: GOMP_SPINCOUNT; LLVM's and Intel's:
//   KMP_BLOCKTIME), so the command line sets it and starts itself again (execv of the same
//   binary with the same arguments), unless the user chose a wait policy.
// - More threads than usable cores, or more ranks times threads than the node's cores, is
//   allowed (it is how oversubscription is tested) but warned, once.
#include <optional>
#include <string>
#include <vector>

namespace pbf {

// The CPUs this process may use.
struct Cores {
  int machine = 1;        // the machine's (node's) online hardware threads
  int affinity = 1;       // those in the process's CPU affinity mask
  double quota = 0;       // its cgroup CPU quota, in cores (0: none)
  int ranks_on_node = 1;  // the ranks of this run on the node (1 without MPI)
  // The cores one process of the run may keep busy: the affinity, the quota rounded down
  // (at least 1), and under MPI its share of the node (at least 1).
  int usable() const;
  // Why usable() is what it is, for the run's first line.
  std::string why() const;
};

// This process's cores; ranks_on_node from the MPI launch (comm::ranks_on_node()).
Cores cores_of_this_process(int ranks_on_node);

// The CPU quota of this process's cgroup, in cores: the smallest over its cgroup and the
// cgroups above it, of cgroup v2's cpu.max or v1's cpu.cfs_quota_us / cpu.cfs_period_us;
// 0 when none is set. `root` is prefixed to /proc and /sys (a test's own tree).
double cgroup_cpu_quota(const std::string& root = "");

// The thread count of a run, why, and what to warn about.
struct ThreadChoice {
  int threads = 1;
  std::string why;                    // "the 2 cores this process may use", "--threads", ...
  std::vector<std::string> warnings;  // each said once, at the start
};

// `requested`: --threads when given; `omp_num_threads`: that variable's text, null when unset.
// A value that is not a thread count is warned about and the default used.
ThreadChoice choose_threads(const Cores& cores, std::optional<int> requested, const char* omp_num_threads);

// The most threads a run may ask for: 4 per hardware thread (enough to test a run
// oversubscribed; a very large count crashes the OpenMP runtime, which cannot start them).
int thread_limit();

// Good-neighbour waiting, before anything else in main: unless the user chose a wait policy
// (OMP_WAIT_POLICY, GOMP_SPINCOUNT or KMP_BLOCKTIME set) or this process already is the
// restarted one, sets the short spin and execs the binary again with the same arguments.
// Returns when no restart is needed, or when it failed (then the run goes on with the
// runtime's default and waiting_policy() says so).
void restart_with_polite_waiting(char** argv);
// How the `threads` threads of this process wait, for the log.
std::string waiting_policy(int threads);

}  // namespace pbf
