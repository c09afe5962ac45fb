// How many OpenMP threads a run uses, and how they wait (engine/core/threads.hpp).
#include "engine/core/threads.hpp"

#include <fmt/format.h>
#include <sched.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <sstream>

namespace pbf {

namespace {

// The spin before a waiting thread sleeps: GOMP_SPINCOUNT counts polls of the flag it waits
// on (about 20 microseconds here), long enough for the other thread of a balanced pass to
// arrive, short enough that a thread waiting for one that is not running gives its core up at
// once (docs/performance/shared.md measures 1,000 against others). LLVM's runtime counts in
// milliseconds: its shortest spin, 0, sleeps at once.
constexpr const char* kSpinCount = "1000";
constexpr const char* kBlockTime = "0";
// Set in the restarted process: what set the waiting ("pbfengine"), so that it restarts once.
constexpr const char* kMarker = "PBF_WAITING";
// An OMP_NUM_THREADS that is not a thread count, moved aside before the restart so that the
// OpenMP runtime of the restarted process does not complain about it a second time.
constexpr const char* kGivenThreads = "PBF_GIVEN_OMP_NUM_THREADS";
constexpr const char* kPolicyVariables[] = {"OMP_WAIT_POLICY", "GOMP_SPINCOUNT", "KMP_BLOCKTIME"};

std::string read_file(const std::string& path) {
  std::ifstream in(path);
  std::stringstream text;
  text << in.rdbuf();
  return in ? text.str() : std::string();
}

// A whole number of at most 9 digits (after trimming blanks), or nothing.
std::optional<long> whole_number(std::string text) {
  const auto first = text.find_first_not_of(" \t\n"), last = text.find_last_not_of(" \t\n");
  if (first == std::string::npos) return {};
  text = text.substr(first, last - first + 1);
  if (text.size() > 9 || text.find_first_not_of("0123456789") != std::string::npos) return {};
  return std::stol(text);
}

// The quota a cgroup directory sets, in cores (0: none there).
double quota_in(const std::string& dir) {
  std::istringstream v2(read_file(dir + "/cpu.max"));  // "max 100000" or "150000 100000"
  std::string quota, period;
  if (v2 >> quota >> period) {
    const auto q = whole_number(quota), p = whole_number(period);
    return q && p && *p > 0 ? double(*q) / double(*p) : 0;
  }
  const auto q = whole_number(read_file(dir + "/cpu.cfs_quota_us")),  // -1: none
      p = whole_number(read_file(dir + "/cpu.cfs_period_us"));
  return q && p && *p > 0 ? double(*q) / double(*p) : 0;
}

// The smallest quota on the way from `path` (a cgroup) up to the hierarchy's root, mounted at
// `mount`. In a container the mount may show only the container's own subtree: the path's
// tail is tried too, down to the mount itself.
double smallest_quota(const std::string& mount, std::string path) {
  double smallest = 0;
  for (;;) {
    const double q = quota_in(mount + path);
    if (q > 0 && (smallest == 0 || q < smallest)) smallest = q;
    if (path.empty() || path == "/") break;
    path = path.substr(0, path.find_last_of('/'));
  }
  return smallest;
}

int online_cpus() { return std::max(1, static_cast<int>(sysconf(_SC_NPROCESSORS_ONLN))); }

std::string plural(int n, const char* word) { return fmt::format("{} {}{}", n, word, n == 1 ? "" : "s"); }

}  // namespace

int thread_limit() { return 4 * online_cpus(); }

double cgroup_cpu_quota(const std::string& root) {
  std::istringstream lines(read_file(root + "/proc/self/cgroup"));
  double smallest = 0;
  auto take = [&](double q) {
    if (q > 0 && (smallest == 0 || q < smallest)) smallest = q;
  };
  for (std::string line; std::getline(lines, line);) {
    // "ID:controllers:path"; cgroup v2 has ID 0 and no controllers.
    const auto a = line.find(':'), b = line.find(':', a + 1);
    if (a == std::string::npos || b == std::string::npos) continue;
    const std::string path = line.substr(b + 1);
    std::string controllers(1, ',');  // ",cpu,cpuacct,": each name between commas
    controllers.append(line, a + 1, b - a - 1).push_back(',');
    const std::string fs = root + "/sys/fs/cgroup";
    if (controllers == ",,") {
      take(smallest_quota(fs, path));
      take(smallest_quota(fs + "/unified", path));
    } else if (controllers.find(",cpu,") != std::string::npos) {
      for (const char* mount : {"/cpu", "/cpu,cpuacct", "/cpuacct,cpu"}) take(smallest_quota(fs + mount, path));
    }
  }
  return smallest;
}

Cores cores_of_this_process(int ranks_on_node) {
  Cores c;
  c.machine = online_cpus();
  cpu_set_t set;
  CPU_ZERO(&set);
  c.affinity = sched_getaffinity(0, sizeof set, &set) == 0 ? std::max(1, CPU_COUNT(&set)) : c.machine;
  c.quota = cgroup_cpu_quota();
  c.ranks_on_node = std::max(1, ranks_on_node);
  return c;
}

int Cores::usable() const {
  int n = affinity;
  if (quota > 0) n = std::min(n, std::max(1, static_cast<int>(std::floor(quota + 1e-9))));
  if (ranks_on_node > 1) n = std::min(n, std::max(1, machine / ranks_on_node));
  return std::max(1, n);
}

std::string Cores::why() const {
  const int n = usable();
  const int by_quota = quota > 0 ? std::max(1, static_cast<int>(std::floor(quota + 1e-9))) : affinity;
  if (ranks_on_node > 1 && n == std::max(1, machine / ranks_on_node) && n < std::min(affinity, by_quota))
    return fmt::format("{} ranks share this node's {}", ranks_on_node, plural(machine, "hardware thread"));
  if (quota > 0 && n == by_quota && by_quota < affinity)
    return fmt::format("a CPU quota of {:g} core{} (cgroup), on {}", quota, quota == 1 ? "" : "s",
                       plural(affinity, "hardware thread"));
  if (affinity < machine && ranks_on_node > 1)  // an MPI launcher's binding
    return fmt::format("each rank's binding allows {} of this node's {}", affinity, plural(machine, "hardware thread"));
  if (affinity < machine)
    return fmt::format("its CPU affinity allows {} of this machine's {}", affinity, plural(machine, "hardware thread"));
  return fmt::format("this machine's {}", plural(machine, "hardware thread"));
}

ThreadChoice choose_threads(const Cores& cores, std::optional<int> requested, const char* omp_num_threads) {
  ThreadChoice c;
  const int usable = cores.usable();
  c.threads = usable;
  c.why = fmt::format("one per core {} may use: {}", cores.ranks_on_node > 1 ? "each rank" : "this process", cores.why());
  if (!omp_num_threads) omp_num_threads = std::getenv(kGivenThreads);  // moved aside by the restart
  if (requested) {
    c.threads = *requested;
    c.why = "as --threads asks";
  } else if (omp_num_threads) {
    // OpenMP's syntax is a list, one count per nesting level: the first is the run's.
    const std::string text = omp_num_threads;
    const auto n = whole_number(text.substr(0, text.find(',')));
    if (n && *n >= 1 && *n <= thread_limit()) {
      c.threads = static_cast<int>(*n);
      c.why = "as OMP_NUM_THREADS asks";
    } else {
      c.warnings.push_back(
          fmt::format("OMP_NUM_THREADS='{}' is not a thread count from 1 to {}: ignored; the run "
                      "uses {}, {}",
                      text, thread_limit(), plural(usable, "thread"), c.why));
    }
  }
  if (cores.quota > 0 && cores.quota < 1)
    c.warnings.push_back(fmt::format("this process's CPU quota is {:g} of a core (cgroup): its threads run at most "
                                     "that share of the time",
                                     cores.quota));
  const int node = cores.ranks_on_node * c.threads;
  if (cores.ranks_on_node > 1 && node > cores.machine)
    c.warnings.push_back(fmt::format(
        "{} ranks of {} each on this node's {}: oversubscribed, so every parallel loop and every exchange waits for "
        "processes that are not running; {} fit the node",
        cores.ranks_on_node, plural(c.threads, "thread"), plural(cores.machine, "hardware thread"),
        cores.ranks_on_node > cores.machine
            ? fmt::format("at most {} of 1 thread", plural(cores.machine, "rank"))
            : fmt::format("{} per rank", plural(std::max(1, cores.machine / cores.ranks_on_node), "thread"))));
  else if (c.threads > usable)
    c.warnings.push_back(fmt::format(
        "{} on the {} this process may use ({}): oversubscribed, so every parallel loop waits for threads that are "
        "not running; leave out --threads and OMP_NUM_THREADS to run {}",
        plural(c.threads, "thread"), plural(usable, "core"), cores.why(), plural(usable, "thread")));
  return c;
}

void restart_with_polite_waiting(char** argv) {
  if (std::getenv(kMarker)) return;  // this is the restarted process
  for (const char* name : kPolicyVariables)
    if (std::getenv(name)) return;  // the user's choice
  // Under valgrind a restart would run the program outside it.
  if (const char* preload = std::getenv("LD_PRELOAD"); preload && std::strstr(preload, "vgpreload")) return;
  if (const char* given = std::getenv("OMP_NUM_THREADS")) {
    const std::string text = given;
    const auto n = whole_number(text.substr(0, text.find(',')));
    if (!n || *n < 1 || *n > thread_limit()) {
      setenv(kGivenThreads, given, 1);
      unsetenv("OMP_NUM_THREADS");
    }
  }
  setenv("GOMP_SPINCOUNT", kSpinCount, 1);
  setenv("KMP_BLOCKTIME", kBlockTime, 1);
  setenv(kMarker, "pbfengine", 1);
  execv("/proc/self/exe", argv);
  // Failed (no /proc): the run goes on with the runtime's default, and says so.
  setenv(kMarker, fmt::format("restart failed: {}", std::strerror(errno)).c_str(), 1);
  unsetenv("GOMP_SPINCOUNT");
  unsetenv("KMP_BLOCKTIME");
  if (const char* given = std::getenv(kGivenThreads)) setenv("OMP_NUM_THREADS", given, 1);
}

std::string waiting_policy(int threads) {
  const char* marker = std::getenv(kMarker);
  if (marker && std::string(marker) == "pbfengine")
    return fmt::format("spin briefly, then sleep (GOMP_SPINCOUNT={}, KMP_BLOCKTIME={}, set by pbfengine)", kSpinCount,
                       kBlockTime);
  std::string set;
  for (const char* name : kPolicyVariables)
    if (const char* value = std::getenv(name)) set += fmt::format("{}{}={}", set.empty() ? "" : ", ", name, value);
  if (!set.empty()) return fmt::format("as the environment says ({})", set);
  if (threads == 1 && !marker) return "one thread, which never waits for another";
  return fmt::format("the OpenMP runtime's default (threads may spin for milliseconds){}",
                     marker ? fmt::format(": {}", marker) : std::string());
}

}  // namespace pbf
