// The passes of the tile rasterizer (see tile_raster.h), each a parallel_for that runs on CPU
// threads or as a CUDA kernel (nvcc compiles this file when CUDA is on). A set of projections
// runs every pass once over all of them: pair i is source triangle i % n under projection
// i / n, records carry the pair as their source, and projection p's tiles follow p - 1's.
//   setup   one thread per pair: clip, snap, orient; the first piece goes to the pair's own
//           record, further pieces of clipped triangles are counted, and so are the tiles of
//           every piece's box (per projection);
//   extras  only if clipping made extra pieces: they are set up again and appended;
//   items   every tile of every record's box is one work item: the records' box sizes, scanned
//           on the device, give each record its first item;
//   count   one thread per item: the tile's coverage mask; non-zero ones are counted per tile
//           (atomic);
//   offsets the per-tile counts scanned on the device, then cut at the entry limit; the host
//           reads back only the totals and where each projection's entries start;
//   write   the same masks again, each stored at its tile's next free slot (atomic cursor) of
//           a scratch copy;
//   sort    entries ordered by (triangle, mask) into the lists, so the arbitrary order of the
//           atomic writes never shows: one thread per entry of a short list (at most
//           rank_sorted_entries) puts it at its rank among its tile's entries, one thread per
//           longer list sorts that list. The order is total up to equal entries, so both give
//           the same lists.
#include <algorithm>
#include <span>
#include <string>
#include <utility>
#include <vector>

#include "core/atomic.h"
#include "core/error.h"
#include "cuda/device_memory.h"
#include "cuda/scan.h"
#include "engine/raster/tile_raster.h"

namespace dv {

namespace {

constexpr const char* kWhere = "rasterize_tiles";

// Per projection.
struct SetupCounters {
  unsigned long long clipped, clipped_near, clipped_guard;
  unsigned long long culled_behind, culled_offscreen, culled_degenerate, culled_invalid;
  unsigned long long extra_pieces;
  unsigned long long box_tiles;  // over every piece, the extra ones included
};

// The triangles under one or more projections of one size. A single projection travels by
// value (no device copy for the camera's lists); more live in the backend's memory.
struct SetView {
  RasterProjection first;
  View<const RasterProjection> all;  // empty for a single projection
  int64_t projections = 1;
  View<const dvec3> vertices;
  View<const u32vec3> triangles;

  DV_HD const RasterProjection& projection(int64_t p) const { return p == 0 ? first : all[p]; }
  DV_HD int64_t pairs() const { return projections * triangles.size; }
  // Which projection and triangle a record's source pair is (32-bit: pairs < 2^32 by
  // check_projections); a single projection's sources are its triangles.
  DV_HD int64_t projection_of(uint32_t source) const {
    return projections == 1 ? 0 : int64_t(source / uint32_t(triangles.size));
  }
  DV_HD uint32_t triangle_of(uint32_t source) const {
    return projections == 1 ? source : source % uint32_t(triangles.size);
  }
};

// Sets up pair i of the view (indices checked: a bad one culls it as invalid).
template <class Emit>
DV_HD uint32_t setup_pair(const SetView& view, int64_t i, Emit&& emit) {
  const u32vec3 tri = view.triangles[i % view.triangles.size];
  dvec3 world[3];
  for (int k = 0; k < 3; ++k) {
    if (int64_t(tri[k]) >= view.vertices.size) return kSetupCulledInvalid;
    world[k] = view.vertices[tri[k]];
  }
  return setup_triangle(view.projection(i / view.triangles.size), world, uint32_t(i), emit);
}

DV_HD inline unsigned long long one_if(bool b) {
  return b ? 1ull : 0ull;
}

// Every thread adds to the same counters (zero where its flag is not set): combined per warp.
DV_HD inline void tally(SetupCounters* c, uint32_t flags, int pieces, int64_t box_tiles) {
  const bool culled = (flags & kSetupCulledAny) != 0;
  atomic_add_combined(&c->culled_behind, one_if(flags & kSetupCulledBehind));
  atomic_add_combined(&c->culled_offscreen, one_if(flags & kSetupCulledOffscreen));
  atomic_add_combined(&c->culled_degenerate, one_if(flags & kSetupCulledDegenerate));
  atomic_add_combined(&c->culled_invalid, one_if(flags & kSetupCulledInvalid));
  atomic_add_combined(&c->clipped,
                      one_if(!culled && (flags & (kSetupClippedNear | kSetupClippedGuard))));
  atomic_add_combined(&c->clipped_near, one_if(!culled && (flags & kSetupClippedNear)));
  atomic_add_combined(&c->clipped_guard, one_if(!culled && (flags & kSetupClippedGuard)));
  atomic_add_combined(&c->extra_pieces,
                      (unsigned long long)(!culled && pieces > 1 ? pieces - 1 : 0));
  atomic_add_combined(&c->box_tiles, (unsigned long long)(box_tiles));
}

// What the host reads back of the tile lists' sizes. tiles_from_first_dropped is tiles - t for
// the first tile t (of all projections) whose list does not fit, 0 if every list fits (so
// zeroed memory starts it).
struct ListTotals {
  unsigned long long stored, needed, tiles_from_first_dropped;
};

// Per projection: the entries needed before its first tile, its longest list and the tiles of
// it whose lists do not fit.
struct ProjectionTotals {
  unsigned long long first_entry, most_per_tile, dropped_tiles;
};

// Tiles of a record's box (0 for an empty record); at most 2^26 (kMaxRasterSide / kTileSide
// squared).
DV_HD inline int64_t box_tile_count(const RasterTriangle& t) {
  if (t.tile_x0 > t.tile_x1 || t.tile_y0 > t.tile_y1) return 0;
  return int64_t(t.tile_x1 - t.tile_x0 + 1) * (t.tile_y1 - t.tile_y0 + 1);
}

// The records: one per source triangle (possibly empty), then the extra pieces.
struct Records {
  View<const RasterTriangle> first, extra;
  DV_HD int64_t size() const { return first.size + extra.size; }
  DV_HD const RasterTriangle& operator[](int64_t r) const {
    return r < first.size ? first[r] : extra[r - first.size];
  }
};

// Work item `item` of the records: tile item - starts[r] of record r's box, row by row, where
// starts holds each record's first item (records without tiles share the next one's, and the
// search takes the last of equal starts). One thread per item spreads a large triangle over
// the whole GPU: the floor of knecht-fig56 covers all 16,384 tiles of a 1024^2 light view, and
// one warp per record walked them in 512 steps while the pass waited.
template <class Visit>
DV_HD void visit_box_tile(const Records& records, View<const int64_t> starts, int64_t item,
                          Visit&& visit) {
  const int64_t r = owner_of_item(starts, records.size(), item);
  const RasterTriangle& t = records[r];
  const int64_t k = item - starts[r];
  if (k >= box_tile_count(t)) return;  // only if the items and the starts disagreed
  const int columns = t.tile_x1 - t.tile_x0 + 1;
  visit(t, t.tile_x0 + int(k % columns), t.tile_y0 + int(k / columns));
}

DV_HD inline bool entry_less(const TileEntry& a, const TileEntry& b) {
  return a.triangle != b.triangle ? a.triangle < b.triangle : a.mask < b.mask;
}

DV_HD inline void sift_down(TileEntry* e, int64_t root, int64_t end) {
  while (2 * root + 1 < end) {
    int64_t child = 2 * root + 1;
    if (child + 1 < end && entry_less(e[child], e[child + 1])) ++child;
    if (!entry_less(e[root], e[child])) return;
    const TileEntry swap = e[root];
    e[root] = e[child];
    e[child] = swap;
    root = child;
  }
}

// Lists up to this long are sorted by rank, one thread per entry (as many comparisons as the
// list has entries, all in parallel); longer ones by one thread per list. On the GPU a thread
// that heap-sorts a list of hundreds of entries alone holds up the whole pass (the tile binning
// of knecht-fig56 waited mostly on such threads: results/perf), so ranks go much further there;
// CPU threads are few and sort faster alone.
int64_t rank_sorted_entries(Backend backend) {
  return backend == Backend::cuda ? 4096 : 64;
}

// Insertion sort for short lists, heap sort (n log n, no extra memory) for long ones.
DV_HD inline void sort_entries(TileEntry* e, int64_t n) {
  if (n <= 16) {
    for (int64_t i = 1; i < n; ++i) {
      const TileEntry key = e[i];
      int64_t j = i;
      for (; j > 0 && entry_less(key, e[j - 1]); --j) e[j] = e[j - 1];
      e[j] = key;
    }
    return;
  }
  for (int64_t start = n / 2 - 1; start >= 0; --start) sift_down(e, start, n);
  for (int64_t end = n - 1; end > 0; --end) {
    const TileEntry swap = e[0];
    e[0] = e[end];
    e[end] = swap;
    sift_down(e, 0, end);
  }
}

void check_projections(const std::vector<RasterProjection>& projections, int64_t triangles) {
  if (projections.empty()) throw InputError(kWhere, "no projection to rasterize");
  for (const RasterProjection& p : projections) {
    if (p.width < 1 || p.height < 1 || p.width > kMaxRasterSide || p.height > kMaxRasterSide)
      throw InputError(kWhere, "image size " + std::to_string(p.width) + "x" +
                                   std::to_string(p.height) + " is outside 1.." +
                                   std::to_string(kMaxRasterSide));
    if (p.width != projections[0].width || p.height != projections[0].height)
      throw InputError(kWhere, "a set of projections must share one image size, got " +
                                   std::to_string(projections[0].width) + "x" +
                                   std::to_string(projections[0].height) + " and " +
                                   std::to_string(p.width) + "x" + std::to_string(p.height));
  }
  const int64_t pairs = int64_t(projections.size()) * triangles;
  if (pairs * int64_t(kMaxPiecesPerTriangle) >= int64_t(UINT32_MAX))
    throw InputError(kWhere, std::to_string(triangles) + " triangles under " +
                                 std::to_string(projections.size()) +
                                 " projections are more than the 32-bit triangle ids can hold");
}

struct SetupResult {
  Buffer<RasterTriangle> first;         // per pair: its first piece (or an empty record)
  Buffer<uint8_t> pieces;               // per pair: its pieces
  std::vector<SetupCounters> counters;  // per projection
  int64_t extra_pieces = 0, box_tiles = 0;
};

// The setup pass: each pair's first piece, its piece count, and the counters.
SetupResult setup_records(Backend backend, const SetView& view) {
  const Memory memory = memory_of(backend);
  const int64_t n = view.pairs();
  SetupResult out;
  out.first = Buffer<RasterTriangle>(memory, n, "raster records");
  out.pieces = Buffer<uint8_t>(memory, n, "raster piece counts");
  Buffer<SetupCounters> counters(memory, view.projections, "raster counters");
  counters.fill_zero();
  const View<RasterTriangle> first = out.first.view();
  const View<uint8_t> pieces_of = out.pieces.view();
  SetupCounters* c = counters.data();
  parallel_for(
      backend, "raster_setup", n, DV_KERNEL_LAMBDA(int64_t i) {
        RasterTriangle head = empty_raster_triangle(uint32_t(i));
        int pieces = 0;
        int64_t box_tiles = 0;
        const uint32_t flags = setup_pair(view, i, [&](const RasterTriangle& t) {
          if (pieces == 0) head = t;
          ++pieces;
          box_tiles += box_tile_count(t);
        });
        first[i] = head;
        pieces_of[i] = uint8_t(pieces);
        tally(c + i / view.triangles.size, flags, pieces, box_tiles);
      });
  out.counters = counters.to_vector();
  for (const SetupCounters& k : out.counters) {
    out.extra_pieces += int64_t(k.extra_pieces);
    out.box_tiles += int64_t(k.box_tiles);
  }
  return out;
}

// The extras pass: the pieces after the first of every clipped pair, set up again and appended
// (in arbitrary order; the sort pass hides it).
Buffer<RasterTriangle> setup_extra_pieces(Backend backend, const SetView& view,
                                          View<const uint8_t> pieces_of, int64_t extra_count) {
  const Memory memory = memory_of(backend);
  Buffer<RasterTriangle> extra_pieces(memory, extra_count, "raster extra pieces");
  if (extra_count == 0) return extra_pieces;
  Buffer<unsigned long long> cursor(memory, 1, "raster extra cursor");
  cursor.fill_zero();
  const View<RasterTriangle> extra = extra_pieces.view();
  unsigned long long* next = cursor.data();
  parallel_for(
      backend, "raster_setup_extra", pieces_of.size, DV_KERNEL_LAMBDA(int64_t i) {
        const int pieces = pieces_of[i];
        if (pieces <= 1) return;
        const unsigned long long base = atomic_add(next, (unsigned long long)(pieces - 1));
        int k = 0;
        setup_pair(view, i, [&](const RasterTriangle& t) {
          const int64_t slot = int64_t(base) + k - 1;
          if (k > 0 && slot < extra.size) extra[slot] = t;
          ++k;
        });
      });
  return extra_pieces;
}

// What the passes after setup share: the set, its records, where each record's work items start
// (records.size() + 1 values, the last one the item count) and the tiles of every projection.
struct Binning {
  SetView view;
  Records records;
  View<const int64_t> starts;
  int64_t items;
  int width, height, tiles_x;
  int64_t face_tiles;  // per projection
  int64_t tiles;       // of every projection

  // Tile (tx, ty) of the projection record t belongs to, counted over every projection.
  DV_HD int64_t tile_of(const RasterTriangle& t, int tx, int ty) const {
    return view.projection_of(t.source) * face_tiles + int64_t(ty) * tiles_x + tx;
  }
  DV_HD uint64_t coverage(const RasterTriangle& t, int tx, int ty) const {
    return tile_coverage(t, tx, ty, tile_valid_mask(tx, ty, width, height));
  }
};

// The items pass: each record's first work item, from the records' box sizes scanned on the
// device.
Buffer<int64_t> record_item_starts(Backend backend, const Records& records) {
  Buffer<int64_t> record_starts(memory_of(backend), records.size() + 1, "raster record starts");
  const View<int64_t> starts_out = record_starts.view();
  parallel_for(
      backend, "raster_box_sizes", records.size() + 1, DV_KERNEL_LAMBDA(int64_t r) {
        starts_out[r] = r < records.size() ? box_tile_count(records[r]) : 0;
      });
  exclusive_scan_queued(backend, starts_out);
  return record_starts;
}

// The count pass: the entries each tile needs (non-zero coverage masks), per tile.
Buffer<uint32_t> count_tile_entries(Backend backend, const Binning& bin) {
  Buffer<uint32_t> tile_counts(memory_of(backend), bin.tiles, "raster tile counts");
  tile_counts.fill_zero();
  uint32_t* counts = tile_counts.data();
  parallel_for(
      backend, "raster_count", bin.items, DV_KERNEL_LAMBDA(int64_t i) {
        visit_box_tile(bin.records, bin.starts, i, [&](const RasterTriangle& t, int tx, int ty) {
          if (bin.coverage(t, tx, ty) != 0) atomic_add(counts + bin.tile_of(t, tx, ty), 1u);
        });
      });
  return tile_counts;
}

// The offsets pass: the counts scanned on the device, then tiles whose list does not fit under
// `limit` (and all tiles after the first such one) keep empty ranges. One small read-back brings
// the totals the host needs to size the entries. Fills the lists' offsets, allocates their
// entries and fills each projection's entry stats; returns the longest list.
int64_t size_tile_lists(Backend backend, const Binning& bin, View<const uint32_t> counted,
                        uint64_t limit, TileListSet& lists) {
  const Memory memory = memory_of(backend);
  const int64_t tiles = bin.tiles, face_tiles = bin.face_tiles;
  const int64_t count = bin.view.projections;
  Buffer<int64_t> tile_starts(memory, tiles + 1, "raster tile starts");
  const View<int64_t> tile_start = tile_starts.view();
  parallel_for(
      backend, "raster_tile_sizes", tiles + 1,
      DV_KERNEL_LAMBDA(int64_t t) { tile_start[t] = t < tiles ? int64_t(counted[t]) : 0; });
  exclusive_scan_queued(backend, tile_start);
  Buffer<ListTotals> totals_buffer(memory, 1, "raster list totals");
  totals_buffer.fill_zero();
  ListTotals* totals = totals_buffer.data();
  Buffer<ProjectionTotals> projection_totals(memory, count, "raster projection totals");
  projection_totals.fill_zero();
  ProjectionTotals* per_projection = projection_totals.data();
  parallel_for(
      backend, "raster_list_limit", tiles, DV_KERNEL_LAMBDA(int64_t t) {
        const unsigned long long entries = counted[t];
        const bool dropped = entries > 0 && uint64_t(tile_start[t + 1]) > limit;
        ProjectionTotals* mine = per_projection + t / face_tiles;
        atomic_max_combined(&mine->most_per_tile, entries);
        atomic_add_combined(&mine->dropped_tiles, (unsigned long long)(dropped));
        atomic_max_combined(&totals->tiles_from_first_dropped,
                            (unsigned long long)(dropped ? tiles - t : 0));
      });
  lists.offsets = Buffer<uint32_t>(memory, tiles + 1, "raster tile offsets");
  const View<uint32_t> offsets = lists.offsets.view();
  parallel_for(
      backend, "raster_offsets", tiles + 1, DV_KERNEL_LAMBDA(int64_t t) {
        const int64_t first_dropped = tiles - int64_t(totals->tiles_from_first_dropped);
        const int64_t stored = tile_start[first_dropped];
        offsets[t] = uint32_t(min_value(tile_start[t], stored));
        if (t % face_tiles == 0 && t < tiles)
          per_projection[t / face_tiles].first_entry = (unsigned long long)(tile_start[t]);
        if (t == tiles) {
          totals->stored = (unsigned long long)(stored);
          totals->needed = (unsigned long long)(tile_start[tiles]);
        }
      });
  const ListTotals sums = totals_buffer.to_vector()[0];
  const std::vector<ProjectionTotals> each = projection_totals.to_vector();
  const uint64_t stored = sums.stored;
  const int64_t first_dropped = tiles - int64_t(sums.tiles_from_first_dropped);
  lists.stats.resize(size_t(count));
  int64_t most_per_tile = 0;
  for (int64_t p = 0; p < count; ++p) {
    RasterStats& s = lists.stats[size_t(p)];
    const uint64_t first = each[size_t(p)].first_entry;
    const uint64_t end = p + 1 < count ? each[size_t(p) + 1].first_entry : sums.needed;
    s.entries_needed = int64_t(end - first);
    s.entries = int64_t(std::clamp(stored, first, end) - first);
    s.max_entries_per_tile = int64_t(each[size_t(p)].most_per_tile);
    s.dropped_tiles = int64_t(each[size_t(p)].dropped_tiles);
    s.first_incomplete_tile = std::clamp(first_dropped - p * face_tiles, int64_t(0), face_tiles);
    s.overflow = s.dropped_tiles > 0;
    most_per_tile = std::max(most_per_tile, s.max_entries_per_tile);
  }
  lists.entries = Buffer<TileEntry>(memory, int64_t(stored), "raster tile entries");
  return most_per_tile;
}

// The write pass: the masks again, each stored at its tile's next free slot (atomic cursor) of
// a scratch copy of the entries, in arbitrary order within a tile.
Buffer<TileEntry> write_tile_entries(Backend backend, const Binning& bin,
                                     View<const uint32_t> range, int64_t stored) {
  const Memory memory = memory_of(backend);
  Buffer<uint32_t> tile_fill(memory, bin.tiles, "raster tile cursors");
  tile_fill.fill_zero();
  uint32_t* fill = tile_fill.data();
  Buffer<TileEntry> unsorted_entries(memory, stored, "raster unsorted tile entries");
  const View<TileEntry> unsorted = unsorted_entries.view();
  parallel_for(
      backend, "raster_write", bin.items, DV_KERNEL_LAMBDA(int64_t i) {
        visit_box_tile(bin.records, bin.starts, i, [&](const RasterTriangle& t, int tx, int ty) {
          const uint64_t mask = bin.coverage(t, tx, ty);
          if (mask == 0) return;
          const int64_t tile = bin.tile_of(t, tx, ty);
          const uint32_t slot = atomic_add(fill + tile, 1u);
          if (slot < range[tile + 1] - range[tile])
            unsorted[range[tile] + slot] = {mask, bin.view.triangle_of(t.source), 0u};
        });
      });
  return unsorted_entries;
}

// The sort pass: each tile's entries ordered by (triangle, mask), short lists by rank, longer
// ones (there are some when most_per_tile is above the rank limit) by one thread a list.
void sort_tile_entries(Backend backend, View<const uint32_t> range, int64_t tiles,
                       View<const TileEntry> unsorted, View<TileEntry> entries,
                       int64_t most_per_tile) {
  const int64_t rank_sorted = rank_sorted_entries(backend);
  parallel_for(
      backend, "raster_rank_sort", entries.size, DV_KERNEL_LAMBDA(int64_t e) {
        const int64_t tile = owner_of_item(range, tiles, e);
        const int64_t first = range[tile], end = range[tile + 1];
        if (end - first > rank_sorted) return;
        const TileEntry mine = unsorted[e];
        int64_t rank = 0;
        for (int64_t j = first; j < end; ++j) {
          const TileEntry other = unsorted[j];
          rank += entry_less(other, mine) || (j < e && !entry_less(mine, other));
        }
        entries[first + rank] = mine;
      });
  if (most_per_tile > rank_sorted)
    parallel_for(
        backend, "raster_sort", tiles, DV_KERNEL_LAMBDA(int64_t t) {
          const int64_t first = range[t], count = int64_t(range[t + 1] - range[t]);
          if (count <= rank_sorted) return;
          for (int64_t j = first; j < first + count; ++j) entries[j] = unsorted[j];
          sort_entries(entries.data + first, count);
        });
}

// The setup pass's counters of each projection in its stats.
void add_setup_stats(const std::vector<SetupCounters>& counters, int64_t triangles,
                     std::vector<RasterStats>& stats) {
  for (size_t p = 0; p < stats.size(); ++p) {
    const SetupCounters& c = counters[p];
    RasterStats& s = stats[p];
    s.triangles_in = triangles;
    s.culled_behind = int64_t(c.culled_behind);
    s.culled_offscreen = int64_t(c.culled_offscreen);
    s.culled_degenerate = int64_t(c.culled_degenerate);
    s.culled_invalid = int64_t(c.culled_invalid);
    s.triangles_culled =
        s.culled_behind + s.culled_offscreen + s.culled_degenerate + s.culled_invalid;
    s.triangles_rasterized = s.triangles_in - s.triangles_culled;
    s.triangles_clipped = int64_t(c.clipped);
    s.clipped_near = int64_t(c.clipped_near);
    s.clipped_guard = int64_t(c.clipped_guard);
    s.pieces = s.triangles_rasterized + int64_t(c.extra_pieces);
  }
}

// The passes over a set of projections, in order (see the top of the file).
TileListSet rasterize_set(Backend backend, const std::vector<RasterProjection>& projections,
                          View<const dvec3> vertices, View<const u32vec3> triangles,
                          const RasterOptions& options) {
  require_backend(backend);
  check_projections(projections, triangles.size);
  if (options.max_entries < 0)
    throw InputError(
        kWhere, "max_entries must not be negative, got " + std::to_string(options.max_entries));
  const int64_t count = int64_t(projections.size());
  Buffer<RasterProjection> projection_buffer;
  if (count > 1)
    projection_buffer = Buffer<RasterProjection>(
        memory_of(backend), std::span<const RasterProjection>(projections), "raster projections");
  const SetView view{projections[0], projection_buffer.const_view(), count, vertices, triangles};
  TileListSet lists;
  lists.width = projections[0].width;
  lists.height = projections[0].height;
  lists.tiles_x = tiles_along(lists.width);
  lists.tiles_y = tiles_along(lists.height);

  const SetupResult setup = setup_records(backend, view);
  const Buffer<RasterTriangle> extra =
      setup_extra_pieces(backend, view, setup.pieces.const_view(), setup.extra_pieces);
  const Records records{setup.first.const_view(), extra.const_view()};
  const Buffer<int64_t> starts = record_item_starts(backend, records);
  const Binning bin{.view = view,
                    .records = records,
                    .starts = starts.const_view(),
                    .items = setup.box_tiles,
                    .width = lists.width,
                    .height = lists.height,
                    .tiles_x = lists.tiles_x,
                    .face_tiles = lists.tile_count(),
                    .tiles = lists.tile_count() * count};
  const Buffer<uint32_t> counts = count_tile_entries(backend, bin);
  const uint64_t limit = uint64_t(std::min<int64_t>(options.max_entries, int64_t(UINT32_MAX)));
  const int64_t most_per_tile = size_tile_lists(backend, bin, counts.const_view(), limit, lists);
  const Buffer<TileEntry> unsorted =
      write_tile_entries(backend, bin, lists.offsets.const_view(), lists.entries.size());
  sort_tile_entries(backend, lists.offsets.const_view(), bin.tiles, unsorted.const_view(),
                    lists.entries.view(), most_per_tile);
  if (backend == Backend::cuda) device_synchronize(kWhere);
  add_setup_stats(setup.counters, triangles.size, lists.stats);
  return lists;
}

}  // namespace

TileLists rasterize_tiles(Backend backend, const RasterView& view, const RasterOptions& options) {
  TileListSet set =
      rasterize_set(backend, {view.projection}, view.vertices, view.triangles, options);
  return {std::move(static_cast<TileListBuffers&>(set)), set.stats[0]};
}

TileLists rasterize_tiles(Backend backend, const SceneView& scene,
                          const RasterProjection& projection, const RasterOptions& options) {
  return rasterize_tiles(backend, make_raster_view(scene, projection), options);
}

TileListSet rasterize_tile_set(Backend backend, View<const dvec3> vertices,
                               View<const u32vec3> triangles,
                               const std::vector<RasterProjection>& projections,
                               const RasterOptions& options) {
  return rasterize_set(backend, projections, vertices, triangles, options);
}

int tile_set_projections(int64_t triangles) {
  constexpr int64_t kMostPairs = int64_t(1) << 22;
  return int(std::clamp<int64_t>(kMostPairs / std::max<int64_t>(triangles, 1), 1, 1 << 20));
}

Buffer<uint32_t> count_pixel_fragments(Backend backend, const TileLists& lists) {
  require_backend(backend);
  const Memory memory = memory_of(backend);
  if (lists.offsets.memory() != memory)
    throw Error("count_pixel_fragments: tile lists are not in the backend's memory");
  const int width = lists.width;
  Buffer<uint32_t> counts(memory, int64_t(lists.width) * lists.height, "fragment counts");
  const View<uint32_t> out = counts.view();
  const TileListsView v = lists.view();
  parallel_for(
      backend, "raster_fragment_count", out.size, DV_KERNEL_LAMBDA(int64_t i) {
        out[i] = uint32_t(fragment_count(v, int(i % width), int(i / width)));
      });
  if (backend == Backend::cuda) device_synchronize("count_pixel_fragments");
  return counts;
}

}  // namespace dv
