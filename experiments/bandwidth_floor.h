// The bandwidth floor a kernel's time is judged by: the device copy bandwidth measured in the same
// run (cudaMemcpy device-to-device of a large buffer, CUDA events, median of several copies) and,
// per voxelizer pass, the fewest bytes the pass must move, so that a pass can be reported as a
// multiple of floor_ms = bytes / bandwidth (goal for kernels over 100 us: within 3x).
#pragma once

#include <cstdint>
#include <optional>
#include <string>

namespace dv {

// Bytes read plus bytes written per millisecond by device-to-device copies of `bytes` bytes
// (median of `copies` after a warm-up). Throws Error without a CUDA device.
double measure_copy_bandwidth(int64_t bytes = int64_t(1) << 30, int copies = 9);

// What the byte counts depend on.
struct FloorInputs {
  int64_t triangles = 0;
  int64_t grid_words = 0;    // 32-bit words of the whole grid
  int64_t set_words = 0;     // words of the result with at least one voxel set
  int64_t atlas_texels = 0;  // side^2 of the atlas methods' position texture
};

// The fewest bytes pass `pass` of voxelizer `method` must move: its inputs read once and its
// outputs written once (the grid: the words it sets; the clear: every word). Empty for passes
// without a model (host work, uploads, the tile rasterizer).
std::optional<double> pass_floor_bytes(const std::string& method, const std::string& pass,
                                       const FloorInputs& in);

// The fewest bytes of binning a scene into tile lists (engine/raster/tile_raster.h) `views`
// times (a light's faces, or the camera once): every view reads the triangles' indices and
// their vertices once; the lists' entries and the tiles' offsets are written once.
double tile_binning_floor_bytes(int64_t triangles, int64_t vertices, int views, int64_t entries,
                                int64_t tiles);

// What the byte counts of a deep-shadow-map generation depend on (DeepShadowMaps::figures()).
struct DsmFloorInputs {
  int64_t texels = 0;         // texels of every map (faces and clusters included)
  double bytes_in_nodes = 0;  // bytes the storage holds in nodes (its payload)
  double raster_bytes = 0;    // tile_binning_floor_bytes of the light views (0: not modelled)
};

// The fewest bytes DSM generation pass `pass` must move: count (one int64 per texel written),
// scan (read and written), range (a depth range per texel), write (the nodes and the texel
// records), relayout / rewrite / shrink (the nodes read and written), raster (the light views'
// tile binning, when raster_bytes is given). Empty for the clustering passes.
std::optional<double> dsm_pass_floor_bytes(const std::string& pass, const DsmFloorInputs& in);

// The fewest bytes of a rasterized frame's fragment pass: its image written once (3 floats a
// pixel). Its reads (fragment lists, the shadow method's maps) depend on the scene.
double frame_floor_bytes(int width, int height);

}  // namespace dv
