// A restart written by every rank of a distributed run together, in the one-process format
// (engine/io/restart.hpp) with the particles in id order, so that any number of ranks, or one
// process, reads it. No rank holds more than its share: each particle's saved values go to the
// rank that writes its block of ids (engine/distributed/id_blocks.hpp), and each rank writes
// its block of every array at its offset (MPI-IO). Rank 0 writes the header, the scene, the
// fields' names and the fixes' states (the same on every rank). The CRC-32 of the payload is
// combined on rank 0 from the CRCs of every rank's pieces, in file order (zlib's crc32_combine).
#include <algorithm>
#include <cstring>
#include <fmt/format.h>
#include <omp.h>
#include <zlib.h>

#include "engine/core/error.hpp"
#include "engine/core/simulation.hpp"
#include "engine/distributed/comm.hpp"
#include "engine/distributed/id_blocks.hpp"
#include "engine/io/restart.hpp"
#include "engine/io/restart_format.hpp"

namespace pbf {

namespace {

template <class Value>
void put_value(std::vector<char>& out, real v) {
  const Value stored = static_cast<Value>(v);
  const char* bytes = reinterpret_cast<const char*>(&stored);
  out.insert(out.end(), bytes, bytes + sizeof stored);
}

}  // namespace

RestartSummary write_restart_distributed(Simulation& sim, const std::string& path, std::uint32_t real_bytes) {
  const double start = omp_get_wtime();
  const Particles& P = sim.particles();
  const int R = comm::ranks(), me = comm::rank();
  const std::uint64_t total = sim.global_count();
  const std::vector<FieldId> saved = restart_fields(P);
  std::size_t components = 0;
  for (FieldId f : saved) components += static_cast<std::size_t>(P.spec(f).components);
  const std::size_t record = sizeof(std::int64_t) + components * real_bytes;

  // Each particle's id and saved values, to the rank of its block of ids.
  const IdBlocks blocks(std::span<const std::int64_t>(P.ids(), P.size()), P.next_id());
  std::vector<std::vector<char>> send(static_cast<std::size_t>(R));
  for (std::size_t i = 0; i < P.size(); ++i) {
    auto& out = send[static_cast<std::size_t>(blocks.rank_of(P.ids()[i]))];
    const char* id = reinterpret_cast<const char*>(P.ids() + i);
    out.insert(out.end(), id, id + sizeof(std::int64_t));
    for (FieldId f : saved)
      for (int c = 0; c < P.spec(f).components; ++c) {
        if (real_bytes == 4) put_value<float>(out, P.data(f, c)[i]);
        else put_value<double>(out, P.data(f, c)[i]);
      }
  }
  std::vector<std::vector<char>> received;
  comm::all_to_all_bytes(send, received);
  send.clear();

  // This rank's block: the ids, then each component's values, in id order.
  std::vector<const char*> records;
  for (const auto& from : received)
    for (std::size_t at = 0; at + record <= from.size(); at += record) records.push_back(from.data() + at);
  const auto id_of = [](const char* rec) {
    std::int64_t id = 0;
    std::memcpy(&id, rec, sizeof id);
    return id;
  };
  std::sort(records.begin(), records.end(), [&](const char* a, const char* b) { return id_of(a) < id_of(b); });
  const std::uint64_t first = blocks.before(me), count = records.size();
  if (count != blocks.count(me)) throw Error(fmt::format("{}: {} particles sent to rank {}, {} expected", path, count, me, blocks.count(me)));
  std::vector<std::vector<char>> arrays(1 + components);
  arrays[0].resize(count * sizeof(std::int64_t));
  for (std::size_t k = 1; k < arrays.size(); ++k) arrays[k].resize(count * real_bytes);
  for (std::uint64_t slot = 0; slot < count; ++slot) {
    const char* rec = records[slot];
    if (slot > 0 && id_of(rec) == id_of(records[slot - 1]))
      throw Error(fmt::format("{}: particle id {} held twice", path, id_of(rec)));
    std::memcpy(arrays[0].data() + slot * sizeof(std::int64_t), rec, sizeof(std::int64_t));
    for (std::size_t k = 1; k < arrays.size(); ++k)
      std::memcpy(arrays[k].data() + slot * real_bytes, rec + sizeof(std::int64_t) + (k - 1) * real_bytes, real_bytes);
  }

  // The file: header, scene, N, ids, each field (name, components, one array per component),
  // the fixes' states. Rank 0's pieces are the ones every rank knows alike.
  ByteWriter scene;
  put_restart_scene(scene, sim);
  scene.put(total);
  std::vector<ByteWriter> field_heads(saved.size());
  for (std::size_t k = 0; k < saved.size(); ++k) {
    if (k == 0) field_heads[k].put(static_cast<std::uint32_t>(saved.size()));
    field_heads[k].put_string(P.spec(saved[k]).name);
    field_heads[k].put(static_cast<std::uint32_t>(P.spec(saved[k]).components));
  }
  ByteWriter states;
  if (saved.empty()) states.put(std::uint32_t{0});
  put_restart_states(states, sim);

  // Offsets of every piece, and the payload's CRC: rank 0 combines its pieces' and the blocks'.
  std::vector<comm::FilePiece> pieces;
  std::vector<std::int64_t> block_crcs;  // this rank's: one per array
  auto as_chars = [](const std::vector<unsigned char>& b) {
    return std::span<const char>(reinterpret_cast<const char*>(b.data()), b.size());
  };
  std::int64_t at = static_cast<std::int64_t>(kHeaderBytes);
  std::vector<std::pair<std::int64_t, std::span<const char>>> shared;  // rank 0's, with their offsets
  std::vector<int> order;  // file order: -1 - k for shared piece k, else the array index
  shared.push_back({at, as_chars(scene.bytes())});
  order.push_back(-1);
  at += static_cast<std::int64_t>(scene.bytes().size());
  std::size_t array = 0;
  auto add_array = [&](std::size_t bytes_per_value) {
    pieces.push_back({at + static_cast<std::int64_t>(first * bytes_per_value), arrays[array]});
    block_crcs.push_back(static_cast<std::int64_t>(restart_checksum(
        reinterpret_cast<const unsigned char*>(arrays[array].data()), arrays[array].size())));
    order.push_back(static_cast<int>(array));
    at += static_cast<std::int64_t>(total * bytes_per_value);
    ++array;
  };
  add_array(sizeof(std::int64_t));
  for (std::size_t k = 0; k < saved.size(); ++k) {
    shared.push_back({at, as_chars(field_heads[k].bytes())});
    order.push_back(-static_cast<int>(shared.size()));
    at += static_cast<std::int64_t>(field_heads[k].bytes().size());
    for (int c = 0; c < P.spec(saved[k]).components; ++c) add_array(real_bytes);
  }
  shared.push_back({at, as_chars(states.bytes())});
  order.push_back(-static_cast<int>(shared.size()));
  at += static_cast<std::int64_t>(states.bytes().size());
  const std::uint64_t payload = static_cast<std::uint64_t>(at) - kHeaderBytes;

  const std::vector<std::int64_t> all_crcs = comm::gather_all(block_crcs);  // rank by rank
  std::vector<unsigned char> header;
  if (me == 0) {
    uLong crc = crc32_z(0L, Z_NULL, 0);
    for (int piece : order) {
      if (piece < 0) {
        const auto& bytes = shared[static_cast<std::size_t>(-1 - piece)].second;
        crc = crc32_z(crc, reinterpret_cast<const unsigned char*>(bytes.data()), bytes.size());
        continue;
      }
      const std::size_t value_bytes = piece == 0 ? sizeof(std::int64_t) : real_bytes;
      for (int r = 0; r < R; ++r) {
        const std::uint64_t length = blocks.count(r) * value_bytes;
        const auto block_crc = static_cast<uLong>(all_crcs[static_cast<std::size_t>(r) * block_crcs.size() +
                                                           static_cast<std::size_t>(piece)]);
        crc = crc32_combine64(crc, block_crc, static_cast<z_off64_t>(length));
      }
    }
    header = restart_header(real_bytes, static_cast<std::uint32_t>(crc), payload);
    pieces.push_back({0, as_chars(header)});
    for (const auto& s : shared) pieces.push_back({s.first, s.second});
  }
  comm::write_file(path, pieces);
  sim.set_last_restart({path, sim.step()});
  return {sim.step(), sim.time(), static_cast<std::size_t>(total), kHeaderBytes + payload, omp_get_wtime() - start};
}

}  // namespace pbf
