#pragma once
// The processes of a distributed run (MPI ranks) and what they say to one another. The only
// file that includes mpi.h is comm.cpp: the rest of the engine calls these functions, which
// are plain no-ops in a run of one process, so that a run started without an MPI launcher
// neither starts MPI nor pays for it.
//
// MPI starts only when the process was launched by an MPI launcher (mpirun, mpiexec, srun:
// they set OMPI_COMM_WORLD_SIZE, PMIX_RANK or PMI_SIZE). Only the main thread calls MPI
// (MPI_THREAD_FUNNELED): OpenMP threads work between the calls.
#include <cstddef>
#include <cstdint>
#include <span>
#include <string>
#include <vector>

namespace pbf {

class ExactSum;

namespace comm {

// Whether an MPI launcher started this process (start() will start MPI).
bool launched_by_mpi();
// Starts MPI when launched by an MPI launcher; call once, first thing in main.
void start(int& argc, char**& argv);
// Ends MPI (after every rank's last collective call); a no-op when it never started.
void stop();
int rank();   // this process, 0 when MPI did not start
int ranks();  // how many there are, 1 when MPI did not start
inline bool distributed() { return ranks() > 1; }
// The ranks that share this rank's node (its memory and cores), itself included; 1 when MPI
// did not start. Collective.
int ranks_on_node();
inline bool root() { return rank() == 0; }

// Collective calls: every rank makes them, in the same order.
void barrier();
// In place, element by element over the ranks.
void sum(std::span<std::int64_t> values);
void max(std::span<double> values);
// Doubles summed in rank order: exact only where at most one rank's value is not zero (values
// that one rank measured and the others left at 0).
void sum(std::span<double> values);
void min(std::span<double> values);
std::int64_t sum(std::int64_t value);
double max(double value);
double min(double value);
// The exact sum of every rank's accumulator (exactly, as integers: the same bits at any rank count).
void sum(ExactSum& accumulator);
// values of every rank, rank by rank (each rank gives the same count).
std::vector<std::int64_t> gather_all(std::span<const std::int64_t> values);
// The same where each rank gives a count of its own.
std::vector<std::int64_t> gather_all_varying(std::span<const std::int64_t> values);
// Bytes of every rank, rank by rank, on rank 0 (elsewhere: empty).
std::vector<std::vector<char>> gather_bytes(std::span<const char> bytes);
// Rank 0's bytes to every rank.
void broadcast(std::vector<char>& bytes);
// counts[r]: what this rank sends to rank r; returns what each rank sends to this one.
std::vector<std::int64_t> all_to_all(std::span<const std::int64_t> counts);

// Point-to-point exchange of bytes with a set of peers (each peer lists this rank too, and
// the two sides call this together): send[k] goes to peers[k], and recv[k] is resized to what
// peers[k] sent. Buffers keep their capacity between calls.
void exchange(std::span<const int> peers, const std::vector<std::vector<char>>& send,
              std::vector<std::vector<char>>& recv);
// The same, where each side knows how much it receives (recv[k] already has the right size).
void exchange_known(std::span<const int> peers, const std::vector<std::vector<char>>& send,
                    std::vector<std::vector<char>>& recv);

// send[r] to rank r, for every rank (empty ones cost nothing but their count); received[r] is
// what rank r sent to this one (the buffers keep their capacity between calls). The counts go
// all to all, the bytes only where there are some.
void all_to_all_bytes(const std::vector<std::vector<char>>& send, std::vector<std::vector<char>>& received);
// The sum of `value` over the ranks before this one.
std::int64_t exclusive_sum(std::int64_t value);
// Writes one file together: each rank its bytes at its offset (MPI-IO), into a temporary
// file that rank 0 renames to `path` when all are done, so that a failed write leaves no cut
// file behind. Throws naming the file when the file system refuses.
void write_file(const std::string& path, std::int64_t offset, std::span<const char> bytes);
// The same with several pieces a rank (each at its offset), flushed to disk before the rename.
struct FilePiece {
  std::int64_t offset;
  std::span<const char> bytes;
};
void write_file(const std::string& path, const std::vector<FilePiece>& pieces);

// Ends every rank at once, with this exit code (after this rank wrote its message).
[[noreturn]] void abort(int code);

}  // namespace comm
}  // namespace pbf
