#pragma once
// Screen tiles and the binning of what is drawn (particle discs, solid triangles) into them.
// Each tile is rendered by one task and owns its pixels; within a tile the items come in
// ascending index at any thread count, so ties in the z-buffer go the same way whatever the
// threads. Internal to engine/render.
#include <omp.h>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <utility>
#include <vector>

namespace pbf::render {

constexpr int kTile = 32;  // screen tiles of kTile x kTile pixels, one task each

// The tiles (inclusive ranges) a screen box [x0, x1] x [y0, y1] overlaps; clamped in float
// before the conversion to int, as a box may reach far beyond the image.
struct TileRange {
  int tx0, tx1, ty0, ty1;
  TileRange(float x0, float x1, float y0, float y1, int tiles_x, int tiles_y) {
    auto tile = [](float p, int count) { return int(std::clamp(std::floor(p / kTile), 0.0f, float(count - 1))); };
    tx0 = tile(x0, tiles_x), tx1 = tile(x1, tiles_x), ty0 = tile(y0, tiles_y), ty1 = tile(y1, tiles_y);
  }
};

// The items overlapping each tile of the scene area (at the image's top left), tile by tile.
struct TileBins {
  int area_width, area_height;
  int tiles_x, tiles_y;
  std::vector<std::size_t> start;  // tile t's items are items[start[t] .. start[t+1])
  std::vector<std::uint32_t> items;

  TileBins(int width, int height)
      : area_width(width),
        area_height(height),
        tiles_x((width + kTile - 1) / kTile),
        tiles_y((height + kTile - 1) / kTile) {}
  int count() const { return tiles_x * tiles_y; }

  // Bins items 0..n-1; range_of(i) gives an item's std::optional<TileRange> (none: not
  // drawn). A counting sort over (tile, thread), with per-thread histograms of contiguous
  // index blocks as in NeighborGrid, keeps each tile's items in ascending index.
  template <class RangeOf>
  void bin(std::size_t n, RangeOf range_of) {
    const int tile_count = count();
    start.assign(tile_count + 1, 0);
    std::vector<std::vector<std::size_t>> histogram(omp_get_max_threads());
#pragma omp parallel num_threads(static_cast <int>(histogram.size()))
    {
      const int t = omp_get_thread_num(), team = omp_get_num_threads();
      const std::size_t begin = n * t / team, end = n * (t + 1) / team;
      auto& hist = histogram[t];
      hist.assign(tile_count, 0);
      for (std::size_t i = begin; i < end; ++i)
        if (const auto r = range_of(i))
          for (int ty = r->ty0; ty <= r->ty1; ++ty)
            for (int tx = r->tx0; tx <= r->tx1; ++tx) ++hist[ty * tiles_x + tx];
#pragma omp barrier
#pragma omp single
      {
        std::size_t running = 0;  // exclusive prefix sum, tile-major, thread-minor
        for (int tile = 0; tile < tile_count; ++tile) {
          start[tile] = running;
          for (int u = 0; u < team; ++u) running += std::exchange(histogram[u][tile], running);
        }
        start[tile_count] = running;
        items.resize(running);
      }
      for (std::size_t i = begin; i < end; ++i)
        if (const auto r = range_of(i))
          for (int ty = r->ty0; ty <= r->ty1; ++ty)
            for (int tx = r->tx0; tx <= r->tx1; ++tx) items[hist[ty * tiles_x + tx]++] = static_cast<std::uint32_t>(i);
    }
  }
};

}  // namespace pbf::render
