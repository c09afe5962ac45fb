#include "engine/distributed/comm.hpp"

#include <mpi.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <fmt/format.h>

#include "engine/core/error.hpp"
#include "engine/core/exact_sum.hpp"

namespace pbf::comm {

namespace {

bool started = false;
bool owner = false;  // this code initialised MPI, so finalises it
int my_rank = 0, world_size = 1;


int count_of(std::size_t n) {
  if (n > static_cast<std::size_t>(INT32_MAX))
    throw Error(fmt::format("MPI: a message of {} bytes is larger than MPI's int counts allow", n));
  return static_cast<int>(n);
}

}  // namespace

bool launched_by_mpi() {
  for (const char* name : {"OMPI_COMM_WORLD_SIZE", "PMIX_RANK", "PMI_SIZE", "PMI_RANK"})
    if (std::getenv(name)) return true;
  return false;
}

void start(int& argc, char**& argv) {
  if (started || !launched_by_mpi()) return;
  int initialized = 0;
  MPI_Initialized(&initialized);
  if (initialized) {
    owner = false;  // started by another library of this process (Python's mpi4py): its to finalize
  } else {
    int provided = 0;
    MPI_Init_thread(&argc, &argv, MPI_THREAD_FUNNELED, &provided);
    owner = true;
  }
  started = true;
  MPI_Comm_rank(MPI_COMM_WORLD, &my_rank);
  MPI_Comm_size(MPI_COMM_WORLD, &world_size);
}

void stop() {
  if (!started) return;
  int finalized = 0;
  MPI_Finalized(&finalized);
  if (owner && !finalized) MPI_Finalize();
  started = false;
}

int rank() { return my_rank; }
int ranks() { return world_size; }

int ranks_on_node() {
  if (!started) return 1;
  MPI_Comm node;
  MPI_Comm_split_type(MPI_COMM_WORLD, MPI_COMM_TYPE_SHARED, 0, MPI_INFO_NULL, &node);
  int size = 1;
  MPI_Comm_size(node, &size);
  MPI_Comm_free(&node);
  return size;
}

void barrier() {
  if (started) MPI_Barrier(MPI_COMM_WORLD);
}

void sum(std::span<std::int64_t> values) {
  if (started && world_size > 1)
    MPI_Allreduce(MPI_IN_PLACE, values.data(), count_of(values.size()), MPI_INT64_T, MPI_SUM, MPI_COMM_WORLD);
}

void max(std::span<double> values) {
  if (started && world_size > 1)
    MPI_Allreduce(MPI_IN_PLACE, values.data(), count_of(values.size()), MPI_DOUBLE, MPI_MAX, MPI_COMM_WORLD);
}

void sum(std::span<double> values) {
  if (started && world_size > 1)
    MPI_Allreduce(MPI_IN_PLACE, values.data(), count_of(values.size()), MPI_DOUBLE, MPI_SUM, MPI_COMM_WORLD);
}

void min(std::span<double> values) {
  if (started && world_size > 1)
    MPI_Allreduce(MPI_IN_PLACE, values.data(), count_of(values.size()), MPI_DOUBLE, MPI_MIN, MPI_COMM_WORLD);
}

std::int64_t sum(std::int64_t value) {
  sum(std::span<std::int64_t>(&value, 1));
  return value;
}

double max(double value) {
  max(std::span<double>(&value, 1));
  return value;
}

double min(double value) {
  min(std::span<double>(&value, 1));
  return value;
}

void sum(ExactSum& accumulator) {
  if (!started || world_size < 2) return;
  // The digits and the counts of NaNs and infinities, summed as integers: exact.
  std::vector<std::int64_t> words(ExactSum::kWords + 3);
  const auto digits = accumulator.words();
  std::copy(digits.begin(), digits.end(), words.begin());
  const auto specials = accumulator.specials();
  for (int k = 0; k < 3; ++k) words[ExactSum::kWords + k] = specials[k];
  sum(std::span<std::int64_t>(words));
  std::array<std::int64_t, ExactSum::kWords> total{};
  std::copy(words.begin(), words.begin() + ExactSum::kWords, total.begin());
  accumulator.set_words(total);
  accumulator.set_specials({static_cast<std::uint32_t>(words[ExactSum::kWords]),
                            static_cast<std::uint32_t>(words[ExactSum::kWords + 1]),
                            static_cast<std::uint32_t>(words[ExactSum::kWords + 2])});
}

std::vector<std::int64_t> gather_all(std::span<const std::int64_t> values) {
  std::vector<std::int64_t> all(values.size() * static_cast<std::size_t>(world_size));
  if (!started || world_size < 2) {
    std::copy(values.begin(), values.end(), all.begin());
    return all;
  }
  MPI_Allgather(values.data(), count_of(values.size()), MPI_INT64_T, all.data(), count_of(values.size()), MPI_INT64_T,
                MPI_COMM_WORLD);
  return all;
}

std::vector<std::int64_t> gather_all_varying(std::span<const std::int64_t> values) {
  if (!started || world_size < 2) return {values.begin(), values.end()};
  const std::int64_t mine = static_cast<std::int64_t>(values.size());
  const std::vector<std::int64_t> sizes = gather_all(std::span<const std::int64_t>(&mine, 1));
  std::vector<int> counts(sizes.size()), displs(sizes.size());
  std::size_t total = 0;
  for (std::size_t r = 0; r < sizes.size(); ++r) {
    counts[r] = count_of(static_cast<std::size_t>(sizes[r]));
    displs[r] = count_of(total);
    total += static_cast<std::size_t>(sizes[r]);
  }
  std::vector<std::int64_t> all(total);
  MPI_Allgatherv(values.data(), count_of(values.size()), MPI_INT64_T, all.data(), counts.data(), displs.data(),
                 MPI_INT64_T, MPI_COMM_WORLD);
  return all;
}

std::vector<std::vector<char>> gather_bytes(std::span<const char> bytes) {
  std::vector<std::vector<char>> all;
  if (!started || world_size < 2) {
    all.emplace_back(bytes.begin(), bytes.end());
    return all;
  }
  int mine = count_of(bytes.size());
  std::vector<int> counts(static_cast<std::size_t>(world_size)), displs(counts.size());
  MPI_Gather(&mine, 1, MPI_INT, counts.data(), 1, MPI_INT, 0, MPI_COMM_WORLD);
  std::vector<char> joined;
  if (my_rank == 0) {
    std::size_t total = 0;
    for (std::size_t r = 0; r < counts.size(); ++r) {
      displs[r] = count_of(total);
      total += static_cast<std::size_t>(counts[r]);
    }
    joined.resize(total);
  }
  MPI_Gatherv(bytes.data(), mine, MPI_CHAR, joined.data(), counts.data(), displs.data(), MPI_CHAR, 0, MPI_COMM_WORLD);
  if (my_rank == 0)
    for (std::size_t r = 0; r < counts.size(); ++r)
      all.emplace_back(joined.begin() + displs[r], joined.begin() + displs[r] + counts[r]);
  return all;
}

void broadcast(std::vector<char>& bytes) {
  if (!started || world_size < 2) return;
  std::int64_t size = static_cast<std::int64_t>(bytes.size());
  MPI_Bcast(&size, 1, MPI_INT64_T, 0, MPI_COMM_WORLD);
  bytes.resize(static_cast<std::size_t>(size));
  MPI_Bcast(bytes.data(), count_of(bytes.size()), MPI_CHAR, 0, MPI_COMM_WORLD);
}

std::vector<std::int64_t> all_to_all(std::span<const std::int64_t> counts) {
  std::vector<std::int64_t> received(counts.begin(), counts.end());
  if (started && world_size > 1)
    MPI_Alltoall(counts.data(), 1, MPI_INT64_T, received.data(), 1, MPI_INT64_T, MPI_COMM_WORLD);
  return received;
}

void exchange_known(std::span<const int> peers, const std::vector<std::vector<char>>& send,
                    std::vector<std::vector<char>>& recv) {
  if (peers.empty()) return;
  std::vector<MPI_Request> requests(2 * peers.size());
  for (std::size_t k = 0; k < peers.size(); ++k)
    MPI_Irecv(recv[k].data(), count_of(recv[k].size()), MPI_CHAR, peers[k], 1, MPI_COMM_WORLD, &requests[k]);
  for (std::size_t k = 0; k < peers.size(); ++k)
    MPI_Isend(send[k].data(), count_of(send[k].size()), MPI_CHAR, peers[k], 1, MPI_COMM_WORLD,
              &requests[peers.size() + k]);
  MPI_Waitall(static_cast<int>(requests.size()), requests.data(), MPI_STATUSES_IGNORE);
}

void exchange(std::span<const int> peers, const std::vector<std::vector<char>>& send,
              std::vector<std::vector<char>>& recv) {
  recv.resize(peers.size());
  if (peers.empty()) return;
  // The sizes first, then the bytes.
  std::vector<std::int64_t> out(peers.size()), in(peers.size());
  std::vector<MPI_Request> requests(2 * peers.size());
  for (std::size_t k = 0; k < peers.size(); ++k) {
    out[k] = static_cast<std::int64_t>(send[k].size());
    MPI_Irecv(&in[k], 1, MPI_INT64_T, peers[k], 0, MPI_COMM_WORLD, &requests[k]);
  }
  for (std::size_t k = 0; k < peers.size(); ++k)
    MPI_Isend(&out[k], 1, MPI_INT64_T, peers[k], 0, MPI_COMM_WORLD, &requests[peers.size() + k]);
  MPI_Waitall(static_cast<int>(requests.size()), requests.data(), MPI_STATUSES_IGNORE);
  for (std::size_t k = 0; k < peers.size(); ++k) recv[k].resize(static_cast<std::size_t>(in[k]));
  exchange_known(peers, send, recv);
}

void all_to_all_bytes(const std::vector<std::vector<char>>& send, std::vector<std::vector<char>>& received) {
  const std::size_t R = static_cast<std::size_t>(world_size), me = static_cast<std::size_t>(my_rank);
  std::vector<std::int64_t> counts(R);
  for (std::size_t r = 0; r < R; ++r) counts[r] = static_cast<std::int64_t>(send[r].size());
  const std::vector<std::int64_t> incoming = all_to_all(counts);
  received.resize(R);
  received[me].assign(send[me].begin(), send[me].end());
  // Straight from and into the callers' buffers, only with the ranks there is something for.
  std::vector<MPI_Request> requests;
  for (std::size_t r = 0; r < R; ++r) {
    if (r == me) continue;
    received[r].resize(static_cast<std::size_t>(incoming[r]));
    if (incoming[r] > 0) {
      requests.emplace_back();
      MPI_Irecv(received[r].data(), count_of(received[r].size()), MPI_CHAR, static_cast<int>(r), 2, MPI_COMM_WORLD,
                &requests.back());
    }
  }
  for (std::size_t r = 0; r < R; ++r) {
    if (r == me || counts[r] == 0) continue;
    requests.emplace_back();
    MPI_Isend(send[r].data(), count_of(send[r].size()), MPI_CHAR, static_cast<int>(r), 2, MPI_COMM_WORLD,
              &requests.back());
  }
  if (!requests.empty()) MPI_Waitall(static_cast<int>(requests.size()), requests.data(), MPI_STATUSES_IGNORE);
}

std::int64_t exclusive_sum(std::int64_t value) {
  if (!started || world_size < 2) return 0;
  std::int64_t before = 0;
  MPI_Exscan(&value, &before, 1, MPI_INT64_T, MPI_SUM, MPI_COMM_WORLD);
  return my_rank == 0 ? 0 : before;
}

void write_file(const std::string& path, std::int64_t offset, std::span<const char> bytes) {
  write_file(path, std::vector<FilePiece>{{offset, bytes}});
}

void write_file(const std::string& path, const std::vector<FilePiece>& pieces) {
  if (!started) throw Error(fmt::format("internal: '{}' written by ranks without MPI", path));
  const std::string temporary = path + ".writing";
  auto check = [&](int code, const char* what) {
    int failed = code != MPI_SUCCESS;
    MPI_Allreduce(MPI_IN_PLACE, &failed, 1, MPI_INT, MPI_MAX, MPI_COMM_WORLD);
    if (!failed) return;
    char text[MPI_MAX_ERROR_STRING] = "";
    int length = 0;
    if (code != MPI_SUCCESS) MPI_Error_string(code, text, &length);
    throw Error(fmt::format("cannot {} '{}'{}", what, path, length ? fmt::format(" ({})", text) : std::string()));
  };
  MPI_File file;
  check(MPI_File_open(MPI_COMM_WORLD, temporary.c_str(), MPI_MODE_CREATE | MPI_MODE_WRONLY, MPI_INFO_NULL, &file),
        "open for writing");
  int code = MPI_File_set_size(file, 0);
  // Each piece in parts MPI's int counts can hold.
  constexpr std::size_t kPart = std::size_t(1) << 30;
  for (const FilePiece& piece : pieces)
    for (std::size_t first = 0; first < piece.bytes.size() && code == MPI_SUCCESS; first += kPart) {
      const std::size_t count = std::min(kPart, piece.bytes.size() - first);
      code = MPI_File_write_at(file, piece.offset + static_cast<std::int64_t>(first), piece.bytes.data() + first,
                               static_cast<int>(count), MPI_CHAR, MPI_STATUS_IGNORE);
    }
  const int synced = MPI_File_sync(file);  // on disk before the rename makes it the file
  if (code == MPI_SUCCESS) code = synced;
  MPI_File_close(&file);
  check(code, "write");
  int renamed = 0;
  if (my_rank == 0) renamed = std::rename(temporary.c_str(), path.c_str()) == 0;
  MPI_Bcast(&renamed, 1, MPI_INT, 0, MPI_COMM_WORLD);
  if (!renamed) throw Error(fmt::format("cannot rename '{}' to '{}'", temporary, path));
}

void abort(int code) {
  if (started && world_size > 1) MPI_Abort(MPI_COMM_WORLD, code);
  std::exit(code);
}

}  // namespace pbf::comm
