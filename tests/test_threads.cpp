// How many threads a run takes and how they wait (engine/core/threads.hpp, issue 29): the
// cores a process may use (affinity, a cgroup's CPU quota, a node shared by MPI ranks), the
// choice and its warnings, the restart that sets a short spin, and threads that sleep while
// they wait instead of taking the core of the thread they wait for.
#include <gtest/gtest.h>
#include <omp.h>
#include <sys/resource.h>
#include <unistd.h>

#include <chrono>
#include <cstdlib>
#include <thread>

#include "engine/core/threads.hpp"
#include "test_util.hpp"

using pbf::test::read_file;
using pbf::test::TempDir;
using pbf::test::write_file;

namespace {

using pbf::choose_threads;
using pbf::Cores;

Cores cores(int machine, int affinity, double quota = 0, int ranks = 1) { return {machine, affinity, quota, ranks}; }

TEST(Threads, UsableCoresFollowAffinityQuotaAndTheNodesRanks) {
  EXPECT_EQ(cores(8, 8).usable(), 8);
  EXPECT_EQ(cores(8, 2).usable(), 2);        // taskset -c 0,1
  EXPECT_EQ(cores(8, 8, 2.5).usable(), 2);   // a container's 2.5 cores keep 2 threads busy
  EXPECT_EQ(cores(8, 8, 0.5).usable(), 1);   // a quota below one core still runs one
  EXPECT_EQ(cores(8, 8, 0, 4).usable(), 2);  // 4 ranks share the node
  EXPECT_EQ(cores(2, 2, 0, 3).usable(), 1);  // more ranks than cores: one thread each
  EXPECT_EQ(cores(8, 1, 0, 4).usable(), 1);  // each rank bound to a core
}

TEST(Threads, TheDefaultIsOnePerUsableCoreAndSaysWhy) {
  auto c = choose_threads(cores(2, 2), std::nullopt, nullptr);
  EXPECT_EQ(c.threads, 2);
  EXPECT_EQ(c.why, "one per core this process may use: this machine's 2 hardware threads");
  EXPECT_TRUE(c.warnings.empty());
  c = choose_threads(cores(16, 4), std::nullopt, nullptr);
  EXPECT_EQ(c.threads, 4);
  EXPECT_EQ(c.why,
            "one per core this process may use: its CPU affinity allows 4 of this machine's 16 hardware threads");
  c = choose_threads(cores(16, 16, 1.5), std::nullopt, nullptr);
  EXPECT_EQ(c.threads, 1);
  EXPECT_EQ(c.why, "one per core this process may use: a CPU quota of 1.5 cores (cgroup), on 16 hardware threads");
  // A quota below one core: one thread, and a word on what it gets.
  c = choose_threads(cores(16, 16, 0.5), std::nullopt, nullptr);
  EXPECT_EQ(c.threads, 1);
  ASSERT_EQ(c.warnings.size(), 1u);
  EXPECT_EQ(c.warnings[0], "this process's CPU quota is 0.5 of a core (cgroup): its threads run at most that share "
                           "of the time");
  c = choose_threads(cores(16, 16, 0, 4), std::nullopt, nullptr);
  EXPECT_EQ(c.threads, 4);
  EXPECT_EQ(c.why, "one per core each rank may use: 4 ranks share this node's 16 hardware threads");
  EXPECT_TRUE(c.warnings.empty());
  // Ranks bound one to a core (Open MPI's default for 2 ranks): the rank's, and the node's, counts.
  c = choose_threads(cores(2, 1, 0, 2), std::nullopt, nullptr);
  EXPECT_EQ(c.threads, 1);
  EXPECT_EQ(c.why, "one per core each rank may use: each rank's binding allows 1 of this node's 2 hardware threads");
}

TEST(Threads, MoreThreadsThanCoresRunButAreWarnedOnce) {
  auto c = choose_threads(cores(2, 2), 4, nullptr);
  EXPECT_EQ(c.threads, 4);
  EXPECT_EQ(c.why, "as --threads asks");
  ASSERT_EQ(c.warnings.size(), 1u);
  EXPECT_EQ(c.warnings[0].rfind("4 threads on the 2 cores this process may use (this machine's 2 hardware threads): "
                                "oversubscribed",
                                0),
            0u)
      << c.warnings[0];
  c = choose_threads(cores(2, 2), std::nullopt, "3");
  EXPECT_EQ(c.threads, 3);
  EXPECT_EQ(c.why, "as OMP_NUM_THREADS asks");
  EXPECT_EQ(c.warnings.size(), 1u);
  // Ranks times threads beyond the node: one warning, naming what fits.
  c = choose_threads(cores(8, 8, 0, 4), 4, nullptr);
  ASSERT_EQ(c.warnings.size(), 1u);
  EXPECT_NE(c.warnings[0].find("4 ranks of 4 threads each on this node's 8 hardware threads: oversubscribed"),
            std::string::npos)
      << c.warnings[0];
  EXPECT_NE(c.warnings[0].find("2 threads per rank fit the node"), std::string::npos) << c.warnings[0];
  c = choose_threads(cores(2, 2, 0, 3), std::nullopt, nullptr);
  ASSERT_EQ(c.warnings.size(), 1u);
  EXPECT_NE(c.warnings[0].find("at most 2 ranks of 1 thread fit the node"), std::string::npos) << c.warnings[0];
}

TEST(Threads, AnOmpNumThreadsThatIsNoCountIsWarnedAndTheDefaultUsed) {
  for (const char* bad : {"0", "abc", "-1", "", "1.5", "100000"}) {
    const auto c = choose_threads(cores(2, 2), std::nullopt, bad);
    EXPECT_EQ(c.threads, 2) << bad;
    ASSERT_EQ(c.warnings.size(), 1u) << bad;
    EXPECT_EQ(c.warnings[0].rfind(std::string("OMP_NUM_THREADS='") + bad + "' is not a thread count from 1 to ", 0), 0u)
        << c.warnings[0];
  }
  // OpenMP's list, one count per nesting level: the first is the run's.
  EXPECT_EQ(choose_threads(cores(2, 2), std::nullopt, "2,1").threads, 2);
  EXPECT_EQ(choose_threads(cores(2, 2), std::nullopt, " 1 ").threads, 1);
  // --threads wins over the variable.
  EXPECT_EQ(choose_threads(cores(2, 2), 1, "2").threads, 1);
}

// A file of a cgroup tree under a temporary root, its folders made.
void put(const std::filesystem::path& path, const std::string& text) {
  std::filesystem::create_directories(path.parent_path());
  write_file(path, text);
}

// A cgroup tree under a temporary root: /proc/self/cgroup and the files under /sys/fs/cgroup.
TEST(Threads, TheCpuQuotaIsTheSmallestOnTheWayUpTheCgroupTree) {
  {  // cgroup v2: the parent's quota is the smaller one
    const TempDir root("cgroup-v2");
    put(root / "proc/self/cgroup", "0::/user.slice/job\n");
    put(root / "sys/fs/cgroup/user.slice/job/cpu.max", "max 100000\n");
    put(root / "sys/fs/cgroup/user.slice/cpu.max", "150000 100000\n");
    EXPECT_DOUBLE_EQ(pbf::cgroup_cpu_quota(root.string()), 1.5);
  }
  {  // cgroup v1, cpu and cpuacct mounted together
    const TempDir root("cgroup-v1");
    put(root / "proc/self/cgroup", "5:memory:/docker/abc\n4:cpu,cpuacct:/docker/abc\n");
    put(root / "sys/fs/cgroup/cpu,cpuacct/docker/abc/cpu.cfs_quota_us", "50000\n");
    put(root / "sys/fs/cgroup/cpu,cpuacct/docker/abc/cpu.cfs_period_us", "100000\n");
    EXPECT_DOUBLE_EQ(pbf::cgroup_cpu_quota(root.string()), 0.5);
  }
  {  // inside a container the mount shows the container's own group at its root
    const TempDir root("cgroup-container");
    put(root / "proc/self/cgroup", "1:cpu:/kubepods/pod1/c2\n");
    put(root / "sys/fs/cgroup/cpu/cpu.cfs_quota_us", "200000\n");
    put(root / "sys/fs/cgroup/cpu/cpu.cfs_period_us", "100000\n");
    EXPECT_DOUBLE_EQ(pbf::cgroup_cpu_quota(root.string()), 2.0);
  }
  {  // no quota anywhere (-1 in v1), and files that are not numbers
    const TempDir root("cgroup-none");
    put(root / "proc/self/cgroup", "1:cpu:/\n0::/\n");
    put(root / "sys/fs/cgroup/cpu/cpu.cfs_quota_us", "-1\n");
    put(root / "sys/fs/cgroup/cpu/cpu.cfs_period_us", "100000\n");
    put(root / "sys/fs/cgroup/cpu.max", "lots of\n");
    EXPECT_DOUBLE_EQ(pbf::cgroup_cpu_quota(root.string()), 0.0);
  }
  EXPECT_DOUBLE_EQ(pbf::cgroup_cpu_quota("/nonexistent"), 0.0);
}

// pbfengine sets the short spin and starts itself again, once; the Lua script of the
// restarted process sees the variables the OpenMP runtime read as it loaded. A user's choice
// of a wait policy is left alone, and a run of one thread does not restart.
TEST(Threads, ARunStartsAgainWithAShortSpinUnlessTheUserChoseAPolicy) {
  const TempDir dir("threads-restart");
  write_file(dir / "a.lua",
             "print(os.getenv('GOMP_SPINCOUNT'), os.getenv('KMP_BLOCKTIME'), os.getenv('PBF_WAITING'))\n");
  const std::string clean = "env -u GOMP_SPINCOUNT -u KMP_BLOCKTIME -u PBF_WAITING -u OMP_WAIT_POLICY ";
  // Two threads unless told: a run of one never waits for another, and does not restart.
  auto run = [&](const std::string& env, const std::string& options = "--threads 2") {
    const std::string command = "cd '" + dir.string() + "' && " + clean + env + " " + PBF_BINARY + " run a.lua " +
                                options + " --log log.txt > out.txt 2>&1";
    EXPECT_EQ(std::system(command.c_str()), 0) << read_file(dir / "out.txt");
    return read_file(dir / "out.txt");
  };
  std::string out = run("");
  EXPECT_NE(out.find("\n1000\t0\tpbfengine\n"), std::string::npos) << out;
  EXPECT_NE(read_file(dir / "log.txt")
                .find("waiting: spin briefly, then sleep (GOMP_SPINCOUNT=1000, KMP_BLOCKTIME=0, "
                      "set by pbfengine)\n"),
            std::string::npos);
  // ctest gives the test processes the same policy (tests/CMakeLists.txt): it must stay the engine's.
  if (const char* marker = std::getenv("PBF_WAITING"); marker && std::string(marker) == "pbfengine") {
    EXPECT_STREQ(std::getenv("GOMP_SPINCOUNT"), "1000");
    EXPECT_STREQ(std::getenv("KMP_BLOCKTIME"), "0");
  }
  out = run("", "--threads 1");
  EXPECT_NE(out.find("\nnil\tnil\tnil\n"), std::string::npos) << out;
  EXPECT_NE(read_file(dir / "log.txt").find("waiting: one thread, which never waits for another\n"),
            std::string::npos);
  out = run("OMP_WAIT_POLICY=passive");
  EXPECT_NE(out.find("\nnil\tnil\tnil\n"), std::string::npos) << out;
  EXPECT_NE(read_file(dir / "log.txt").find("waiting: as the environment says (OMP_WAIT_POLICY=passive)\n"),
            std::string::npos);
  // An OMP_NUM_THREADS that is no count: one warning, the default count, and the OpenMP
  // runtime of the restarted process does not complain about it again.
  out = run("OMP_NUM_THREADS=0", "");
  EXPECT_NE(out.find("warning: OMP_NUM_THREADS='0' is not a thread count"), std::string::npos) << out;
  const auto complaint = out.find("libgomp: Invalid value");
  if (complaint != std::string::npos)
    EXPECT_EQ(out.find("libgomp: Invalid value", complaint + 1), std::string::npos) << out;
}

double cpu_seconds() {
  rusage r{};
  getrusage(RUSAGE_SELF, &r);
  return double(r.ru_utime.tv_sec + r.ru_stime.tv_sec) + 1e-6 * double(r.ru_utime.tv_usec + r.ru_stime.tv_usec);
}

// A thread that waits at the end of a region for another sleeps after a short spin: 100
// waits of 3 ms cost the waiting thread far less than 0.3 s of processor time (with libgomp's
// default it spins for milliseconds each time). This process's OpenMP runtime was set up as
// pbfengine's is (the restart of tests/main.cpp, or the environment ctest gives it).
TEST(Threads, AWaitingThreadSleepsInsteadOfSpinning) {
  constexpr int kWaits = 100;
  constexpr auto kLate = std::chrono::milliseconds(3);
  omp_set_num_threads(2);
  const double cpu0 = cpu_seconds();
  const auto t0 = std::chrono::steady_clock::now();
  for (int k = 0; k < kWaits; ++k) {
#pragma omp parallel num_threads(2)
    if (omp_get_thread_num() == 0) std::this_thread::sleep_for(kLate);  // the other waits for it
  }
  const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  const double cpu = cpu_seconds() - cpu0;
  omp_set_num_threads(1);
  ASSERT_GE(wall, kWaits * 0.003);
  // A spinning waiter would use about the whole wait; a sleeping one a small part (its short
  // spin and the wake-ups). A quarter leaves room for a loaded machine's scheduling; spinning is 1.
  EXPECT_LT(cpu, 0.25 * kWaits * 0.003) << cpu << " s of processor time in " << wall << " s";
}

}  // namespace
