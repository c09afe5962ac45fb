#include "engine/distributed/decomposition.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <numeric>
#include <omp.h>

#include "engine/distributed/comm.hpp"

namespace pbf {

namespace {

// Rebalance when the largest rank holds more than this times the mean, at most every kBalanceEvery steps.
constexpr double kImbalance = 1.1;
constexpr std::int64_t kBalanceEvery = 20;

bool overlap(const CellRange& a, const CellRange& b) {
  if (a.empty() || b.empty()) return false;
  for (int k = 0; k < 3; ++k)
    if (a.hi[k] <= b.lo[k] || b.hi[k] <= a.lo[k]) return false;
  return true;
}

class Timer {
 public:
  explicit Timer(double& total) : total_(total), start_(omp_get_wtime()) {}
  ~Timer() { total_ += omp_get_wtime() - start_; }

 private:
  double& total_;
  double start_;
};

}  // namespace

bool Decomposition::wanted() { return comm::distributed(); }

CellRange cells_holding(const Particles& P, const GridGeometry& grid) {
  const std::size_t n = P.size();
  if (n == 0) return CellRange{{0, 0, 0}, {1, 1, 1}};
  const real* x[3] = {P.x(), P.y(), P.z()};
  long lo[3] = {grid.dims[0], grid.dims[1], grid.dims[2]}, hi[3] = {-1, -1, -1};
#pragma omp parallel for schedule(static) reduction(min : lo[:3]) reduction(max : hi[:3])
  for (std::size_t i = 0; i < n; ++i)
    for (int a = 0; a < 3; ++a) {
      const long c = grid.cell_along(a, x[a][i]);
      lo[a] = std::min(lo[a], c);
      hi[a] = std::max(hi[a], c);
    }
  CellRange r;
  for (int a = 0; a < 3; ++a) {
    r.lo[a] = lo[a];
    r.hi[a] = hi[a] + 1;
  }
  return r;
}

void Decomposition::cells_of(const Particles& P, const GridGeometry& grid, std::size_t n) {
  cells_.resize(3 * n);
  const real* x[3] = {P.x(), P.y(), P.z()};
#pragma omp parallel for schedule(static)
  for (std::size_t i = 0; i < n; ++i)
    for (int a = 0; a < 3; ++a) cells_[3 * i + a] = grid.cell_along(a, x[a][i]);
}

// Cuts the boxes anew from the first `counted` particles of this rank (every rank's together).
void Decomposition::balance(const Particles& P, const GridGeometry& grid, std::size_t counted) {
  cells_of(P, grid, counted);
  std::vector<std::uint32_t> mine(counted);
  std::iota(mine.begin(), mine.end(), 0u);
  tree_.clear();
  cut_for_ = grid;
  split(0, comm::ranks(), CellRange::all(grid), mine, cells_);
  steps_since_balance_ = 0;
}

// Cuts `box` between `ranks` ranks (from first_rank on), across the longest side of the cells its
// particles fill (the smallest cut, so the fewest ghosts), at the cell plane where the particles
// below and above are in proportion to the ranks on each side. Every rank calls it in the same
// order, with its own particles in the box (`mine`), and sums the histograms.
int Decomposition::split(int first_rank, int ranks, const CellRange& box, std::vector<std::uint32_t>& mine,
                         const std::vector<long>& cells) {
  const int node = static_cast<int>(tree_.size());
  tree_.emplace_back();
  if (ranks == 1) {
    tree_[node].rank = first_rank;
    if (first_rank == comm::rank()) box_ = box;
    return node;
  }
  // The cells the box's particles fill, over every rank (an empty box: the box).
  double low[3], high[3];
  for (int a = 0; a < 3; ++a) low[a] = HUGE_VAL, high[a] = -HUGE_VAL;
  for (std::uint32_t i : mine)
    for (int a = 0; a < 3; ++a) {
      low[a] = std::min(low[a], double(cells[3 * i + a]));
      high[a] = std::max(high[a], double(cells[3 * i + a] + 1));
    }
  comm::min(low);
  comm::max(high);
  CellRange filled = box;
  if (low[0] <= high[0])
    for (int a = 0; a < 3; ++a) filled.lo[a] = long(low[a]), filled.hi[a] = long(high[a]);
  int axis = 0;
  for (int a = 1; a < 3; ++a)
    if (filled.hi[a] - filled.lo[a] > filled.hi[axis] - filled.lo[axis]) axis = a;
  const long length = std::max(0L, filled.hi[axis] - filled.lo[axis]);
  std::vector<std::int64_t> histogram(static_cast<std::size_t>(length), 0);
  for (std::uint32_t i : mine) ++histogram[static_cast<std::size_t>(cells[3 * i + axis] - filled.lo[axis])];
  comm::sum(std::span<std::int64_t>(histogram));
  const int below_ranks = ranks / 2;
  const std::int64_t total = std::accumulate(histogram.begin(), histogram.end(), std::int64_t{0});
  // The first plane with at least its share below (each side keeps a cell when there are two).
  long cut = std::min(1L, length);
  std::int64_t below = length > 0 ? histogram[0] : 0;
  while (cut < length - 1 && below * ranks < total * below_ranks) below += histogram[static_cast<std::size_t>(cut++)];
  const long at = filled.lo[axis] + cut;
  tree_[node].axis = axis;
  tree_[node].at = at;
  CellRange lower = box, upper = box;
  lower.hi[axis] = at;
  upper.lo[axis] = at;
  std::vector<std::uint32_t> mine_upper;
  auto middle = std::stable_partition(mine.begin(), mine.end(), [&](std::uint32_t i) { return cells[3 * i + axis] < at; });
  mine_upper.assign(middle, mine.end());
  mine.erase(middle, mine.end());
  const int lower_node = split(first_rank, below_ranks, lower, mine, cells);
  const int upper_node = split(first_rank + below_ranks, ranks - below_ranks, upper, mine_upper, cells);
  tree_[node].below = lower_node;
  tree_[node].above = upper_node;
  return node;
}

int Decomposition::owner(const long cell[3]) const {
  int node = 0;
  while (tree_[static_cast<std::size_t>(node)].rank < 0) {
    const Node& n = tree_[static_cast<std::size_t>(node)];
    node = cell[n.axis] < n.at ? n.below : n.above;
  }
  return tree_[static_cast<std::size_t>(node)].rank;
}

void Decomposition::pack(const Particles& P, std::size_t i, std::vector<char>& out, const Shift& shift) const {
  const std::int64_t id = P.ids()[i];
  const char* bytes = reinterpret_cast<const char*>(&id);
  out.insert(out.end(), bytes, bytes + sizeof id);
  for (FieldId f : fields_)
    for (int c = 0; c < P.spec(f).components; ++c) {
      const real v = f == Particles::kPosition ? domain_.image(c, P.data(f, c)[i], shift[c]) : P.data(f, c)[i];
      bytes = reinterpret_cast<const char*>(&v);
      out.insert(out.end(), bytes, bytes + sizeof v);
    }
}

namespace {

// Reads particles packed by Decomposition::pack: ids first, then appended by `add`, then fields.
template <class Add>
void unpack(Particles& P, const std::vector<FieldId>& fields, const std::vector<char>& in, std::size_t record,
            Add&& add) {
  const std::size_t count = in.size() / record;
  std::vector<std::int64_t> ids(count);
  for (std::size_t k = 0; k < count; ++k) std::memcpy(&ids[k], in.data() + k * record, sizeof(std::int64_t));
  const std::size_t first = add(ids);
  for (std::size_t k = 0; k < count; ++k) {
    const char* at = in.data() + k * record + sizeof(std::int64_t);
    for (FieldId f : fields)
      for (int c = 0; c < P.spec(f).components; ++c) {
        std::memcpy(P.data(f, c) + first + k, at, sizeof(real));
        at += sizeof(real);
      }
  }
}

std::size_t record_size(const Particles& P, const std::vector<FieldId>& fields) {
  std::size_t values = 0;
  for (FieldId f : fields) values += static_cast<std::size_t>(P.spec(f).components);
  return sizeof(std::int64_t) + values * sizeof(real);
}

}  // namespace

// Sends each particle whose destination is another rank there, and takes in those sent here.
// Sends each particle whose destination is another rank there, and takes in those sent here.
void Decomposition::send_away(Particles& P, const std::vector<int>& destination) {
  const int me = comm::rank();
  fields_ = P.fields();
  const std::size_t record = record_size(P, fields_), n = P.size();
  outgoing_.resize(static_cast<std::size_t>(comm::ranks()));
  for (auto& out : outgoing_) out.clear();
  std::vector<char> drop(n, 0);
  for (std::size_t i = 0; i < n; ++i)
    if (destination[i] != me) {
      pack(P, i, outgoing_[static_cast<std::size_t>(destination[i])]);
      drop[i] = 1;
    }
  comm::all_to_all_bytes(outgoing_, incoming_);
  P.erase(drop);
  for (const auto& in : incoming_)
    if (&in != &incoming_[static_cast<std::size_t>(me)])
      unpack(P, fields_, in, record, [&](const std::vector<std::int64_t>& ids) {
        const std::size_t first = P.size();
        P.append(ids);
        return first;
      });
}

void Decomposition::distribute(Particles& P, const GridGeometry& grid) {
  P.drop_ghosts();
  // The first time, the tree is cut from every rank's particles (shares of the sources, which
  // together are the whole set); later the particles created since join those placed.
  if (tree_.empty() || !(grid == cut_for_)) balance(P, grid, P.size());  // (more particles may widen the cells)
  migrate(P, grid);  // and the load line
  P.mark_placed();
}

void Decomposition::migrate(Particles& P, const GridGeometry& grid) {
  Timer timer(seconds_);
  P.drop_ghosts();
  ++steps_since_balance_;
  // The counts the last migration left decide (one gathering a step).
  if (load_.most > kImbalance * load_.mean && steps_since_balance_ >= kBalanceEvery) balance(P, grid, P.size());
  const std::size_t n = P.size();
  cells_of(P, grid, n);
  std::vector<int> destination(n);
  for (std::size_t i = 0; i < n; ++i) destination[i] = owner(&cells_[3 * i]);
  send_away(P, destination);
  const std::int64_t mine = static_cast<std::int64_t>(P.size());
  const std::vector<std::int64_t> all = comm::gather_all(std::span<const std::int64_t>(&mine, 1));
  load_.least = static_cast<double>(*std::min_element(all.begin(), all.end()));
  load_.most = static_cast<double>(*std::max_element(all.begin(), all.end()));
  load_.mean = static_cast<double>(std::accumulate(all.begin(), all.end(), std::int64_t{0})) / double(all.size());
}

namespace {
// The cells `r` covers `shift` periods away (a cell more on each side along a shifted axis: an
// image's cell, from its shifted position, may round to the next one).
CellRange shifted(const CellRange& r, const GridGeometry& grid, const Shift& shift) {
  CellRange s = r;
  for (int a = 0; a < 3; ++a)
    if (shift[a] != 0) {
      s.lo[a] += shift[a] * grid.dims[a] - 1;
      s.hi[a] += shift[a] * grid.dims[a] + 1;
    }
  return s;
}
}  // namespace

CellRange Decomposition::build_ghosts(Particles& P, const GridGeometry& grid, const Domain& domain) {
  Timer timer(seconds_);
  P.drop_ghosts();
  domain_ = domain;
  const std::size_t n = P.size();
  cells_of(P, grid, n);
  CellRange mine = box_;  // the box, and the cells of particles that left it since the step began
  if (mine.empty()) mine = CellRange{{grid.dims[0], grid.dims[1], grid.dims[2]}, {0, 0, 0}};
  for (std::size_t i = 0; i < n; ++i)
    for (int a = 0; a < 3; ++a) {
      mine.lo[a] = std::min(mine.lo[a], cells_[3 * i + a]);
      mine.hi[a] = std::max(mine.hi[a], cells_[3 * i + a] + 1);
    }
  // Every rank's cells: the peers are the ranks whose cells come within one cell of this
  // one's, or of its cells a period away (the same test both ways round: peers agree).
  std::int64_t box[6];
  for (int a = 0; a < 3; ++a) {
    box[a] = mine.lo[a];
    box[3 + a] = mine.hi[a];
  }
  const std::vector<std::int64_t> boxes = comm::gather_all(std::span<const std::int64_t>(box, 6));
  const int me = comm::rank();
  std::vector<Shift> shifts = image_shifts(domain);
  shifts.insert(shifts.begin(), Shift{0, 0, 0});
  peers_.clear();
  std::vector<CellRange> reach;  // each peer's cells, grown by one
  for (int r = 0; r < comm::ranks(); ++r) {
    if (r == me) continue;
    CellRange theirs;
    for (int a = 0; a < 3; ++a) {
      theirs.lo[a] = boxes[6 * static_cast<std::size_t>(r) + a];
      theirs.hi[a] = boxes[6 * static_cast<std::size_t>(r) + 3 + a];
    }
    const CellRange near = grid.grown(theirs);
    if (!std::any_of(shifts.begin(), shifts.end(), [&](const Shift& s) { return overlap(near, shifted(mine, grid, s)); }))
      continue;
    peers_.push_back(r);
    reach.push_back(near);
  }
  fields_ = P.fields();
  const std::size_t record = record_size(P, fields_);
  send_index_.resize(peers_.size());
  send_shift_.resize(peers_.size());
  send_.resize(peers_.size());
  const real* const x[3] = {P.x(), P.y(), P.z()};
  for (std::size_t k = 0; k < peers_.size(); ++k) {
    send_index_[k].clear();
    send_shift_[k].clear();
    send_[k].clear();
    for (std::size_t i = 0; i < n; ++i)
      for (const Shift& s : shifts)
        if (image_in(domain, grid, reach[k], x, i, s, &cells_[3 * i])) {
          send_index_[k].push_back(static_cast<std::uint32_t>(i));
          send_shift_[k].push_back(s);
          pack(P, i, send_[k], s);
        }
  }
  comm::exchange(peers_, send_, recv_);
  ghost_first_.resize(peers_.size());
  ghost_count_.resize(peers_.size());
  for (std::size_t k = 0; k < peers_.size(); ++k) {
    ghost_count_[k] = recv_[k].size() / record;
    unpack(P, fields_, recv_[k], record, [&](const std::vector<std::int64_t>& ids) {
      ghost_first_[k] = P.add_ghosts(ids);
      return ghost_first_[k];
    });
  }
  ghost_sum_ += static_cast<double>(P.ghosts());
  ++ghost_builds_;
  if (mine.empty()) return CellRange{{0, 0, 0}, {1, 1, 1}};
  return grid.grown(mine);
}

void Decomposition::update(std::span<real* const> arrays, bool positions) {
  if (peers_.empty()) return;
  Timer timer(seconds_);
  const std::size_t A = arrays.size();
  for (std::size_t k = 0; k < peers_.size(); ++k) {
    const auto& index = send_index_[k];
    const auto& shift = send_shift_[k];
    send_[k].resize(index.size() * A * sizeof(real));
    real* out = reinterpret_cast<real*>(send_[k].data());
    for (std::size_t a = 0; a < A; ++a)
      for (std::size_t i = 0; i < index.size(); ++i)
        *out++ = positions ? domain_.image(int(a), arrays[a][index[i]], shift[i][int(a)]) : arrays[a][index[i]];
    recv_[k].resize(ghost_count_[k] * A * sizeof(real));
  }
  comm::exchange_known(peers_, send_, recv_);
  for (std::size_t k = 0; k < peers_.size(); ++k) {
    const real* in = reinterpret_cast<const real*>(recv_[k].data());
    for (std::size_t a = 0; a < A; ++a)
      for (std::size_t i = 0; i < ghost_count_[k]; ++i) arrays[a][ghost_first_[k] + i] = *in++;
  }
}

}  // namespace pbf
