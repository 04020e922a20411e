// Copy bandwidth and per-pass byte counts (see bandwidth_floor.h).
#include "experiments/bandwidth_floor.h"

#include <algorithm>
#include <vector>

#include "core/error.h"
#include "core/math.h"
#include "cuda/buffer.h"
#include "engine/dsm/dsm_generator.h"
#include "engine/raster/tile_raster.h"
#include "strategies/voxelizer/atlas_packing.h"

#if defined(DEEPVOX_WITH_CUDA)
#include <cuda_runtime_api.h>

#include "cuda/cuda_check.h"
#endif

namespace dv {

double measure_copy_bandwidth(int64_t bytes, int copies) {
#if defined(DEEPVOX_WITH_CUDA)
  // Through device_allocate like every device buffer: too large is an OutOfMemory naming it.
  const Buffer<char> source(Memory::device, bytes, "copy bandwidth source");
  const Buffer<char> destination(Memory::device, bytes, "copy bandwidth destination");
  char *src = source.data(), *dst = destination.data();
  device_memset(src, 1, size_t(bytes));
  cudaEvent_t start, stop;
  DV_CUDA_CHECK(cudaEventCreate(&start));
  DV_CUDA_CHECK(cudaEventCreate(&stop));
  std::vector<float> ms;
  for (int i = 0; i <= copies; ++i) {  // the first is the warm-up
    DV_CUDA_CHECK(cudaEventRecord(start));
    DV_CUDA_CHECK(cudaMemcpy(dst, src, size_t(bytes), cudaMemcpyDeviceToDevice));
    DV_CUDA_CHECK(cudaEventRecord(stop));
    DV_CUDA_CHECK(cudaEventSynchronize(stop));
    float t = 0.0f;
    DV_CUDA_CHECK(cudaEventElapsedTime(&t, start, stop));
    if (i > 0) ms.push_back(t);
  }
  cudaEventDestroy(start);
  cudaEventDestroy(stop);
  std::sort(ms.begin(), ms.end());
  return 2.0 * double(bytes) / double(ms[ms.size() / 2]);
#else
  (void)bytes;
  (void)copies;
  throw Error("measure_copy_bandwidth: this build has no CUDA");
#endif
}

std::optional<double> pass_floor_bytes(const std::string& method, const std::string& pass,
                                       const FloorInputs& in) {
  const double t = double(in.triangles);
  const double corners = 3.0 * sizeof(dvec3) * t, offsets = sizeof(int64_t) * t;
  const double set = 4.0 * double(in.set_words);
  const double texture = sizeof(dvec4) * double(in.atlas_texels);
  if (pass == "clear") return 4.0 * double(in.grid_words);
  // sat: the small pass reads every corner and sets (nearly) every word; the large pass's
  // bytes depend on how many triangles are large, which the floor inputs do not hold.
  if (method == "sat" && pass == "small") return corners + set;
  if (method == "slicemap" && pass == "setup") return 2.0 * corners + 12.0 * t;  // + indices
  if (method == "slicemap" && pass == "slices") return corners + set;
  if (method == "atlas" && pass == "atlas_update") return corners + texture;
  if (method == "atlas" && pass == "points") return texture + set;
  if (method == "atlas-compute" && pass == "points")
    return corners + sizeof(AtlasCell) * t + offsets + set;
  return std::nullopt;
}

double tile_binning_floor_bytes(int64_t triangles, int64_t vertices, int views, int64_t entries,
                                int64_t tiles) {
  const double scene = sizeof(u32vec3) * double(triangles) + sizeof(dvec3) * double(vertices);
  return double(views) * scene + sizeof(TileEntry) * double(entries) +
         sizeof(uint32_t) * double(tiles + views);
}

std::optional<double> dsm_pass_floor_bytes(const std::string& pass, const DsmFloorInputs& in) {
  const double texels = double(in.texels);
  if (pass == "raster" && in.raster_bytes > 0) return in.raster_bytes;
  if (pass == "count") return sizeof(int64_t) * texels;
  if (pass == "scan") return 2.0 * sizeof(int64_t) * texels;
  if (pass == "range") return 2.0 * sizeof(float) * texels;
  if (pass == "write") return in.bytes_in_nodes + sizeof(DsmTexelRecord) * texels;
  if (pass == "relayout" || pass == "rewrite" || pass == "shrink") return 2.0 * in.bytes_in_nodes;
  return std::nullopt;
}

double frame_floor_bytes(int width, int height) {
  return 3.0 * sizeof(float) * double(width) * double(height);
}

}  // namespace dv
