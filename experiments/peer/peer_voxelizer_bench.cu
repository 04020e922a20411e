// peer_voxelizer_bench: warm-kernel timing of the peer voxelizer, Forceflow's
// cuda_voxelizer (v0.6), on bench_voxelizer's meshes and grids. Our code, but it compiles only
// against the peer's source that scripts/build-peer.sh extracts into .peer/src/ (it builds this
// file into .peer/bin/peer_voxelizer_bench): this one translation unit includes the peer's
// src/voxelize.cu, so the kernel voxelize_triangle is the peer's, unchanged.
//
// What the peer's program does (src/main.cpp and src/voxelize.cu):
//  - reads the mesh with trimesh2 (TriMesh::read, need_faces, need_bbox);
//  - makes the float bounding box a cube (src/util.h createMeshBBCube: the shorter sides padded
//    equally on both ends, then 1/10001 of each side added at both ends) and a voxinfo for an
//    N^3 grid (unit = side / N);
//  - copies the triangles (9 floats each) into managed memory and allocates the bit table,
//    ceil(N^3 / 32) 32-bit words, as managed memory too (never cleared);
//  - voxelize(): copies the Morton tables to constant memory (only for output format morton),
//    takes the block size from cudaOccupancyMaxPotentialBlockSize, grid = ceil(triangles /
//    block), and prints as "Voxelization GPU time" the time between two events on stream 0:
//    cudaEventRecord(start), the kernel launch, cudaDeviceSynchronize(), cudaEventRecord(stop).
//    So it times the one kernel launch (not the table copies, the occupancy query, the
//    allocations or the triangle copy), but cold: the kernel's first touches of the managed
//    triangles and table migrate them to the GPU inside the timed span, and the host's wait
//    and the stop event's submission come before the stop event.
// What this program times, per mesh and grid, with the peer's voxinfo and launch shape:
//  - the triangles already on the GPU (cudaMalloc + cudaMemcpy; with --managed, in managed
//    memory as the peer has them, prefetched to the GPU), the table likewise;
//  - warm-up launches first, each on a table cleared with cudaMemset: at least --warmup
//    (default 2) and until --warmup-ms of wall time have passed (default 200, so that the
//    clocks have risen also before the 12-triangle cube's microsecond launches);
//  - then --repeats rounds (default 20): clear_ms = events around cudaMemset(table, 0, bytes);
//    kernel_ms = events recorded just before and just after the launch on stream 0, with no
//    host wait between them (as deepvox's PassTimer), i.e. the kernel's own GPU time;
//    --peer-timer puts the peer's cudaDeviceSynchronize() between the launch and the stop
//    event, to reproduce its number warm;
//  - filled_voxels: set bits of the table after the last round; it must equal the count after
//    the warm-up (else exit 1: the kernel would not be deterministic in what it fills).
// Bounds: --bounds peer (default) is the peer's padded cube; --bounds cubic is deepvox's
// cubic_bounds (the bounding box's centre, side = its longest extent, no padding; computed in
// double from trimesh2's float box), so that filled voxels can be compared on the same grid.
// Output: one JSON line per mesh and grid on stdout, messages on stderr.
//
// Usage: peer_voxelizer_bench [--grids 512,1024] [--repeats 20] [--warmup 2] [--warmup-ms 200]
//                             [--morton] [--managed] [--peer-timer] [--bounds peer|cubic] MESH...
#include "voxelize.cu"  // the peer's kernel voxelize_triangle (and its voxelize(), unused)

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>
#include <vector>

namespace {

#define CHECK(call) check_cuda((call), #call, __LINE__)

void check_cuda(cudaError_t status, const char* what, int line) {
  if (status == cudaSuccess) return;
  std::fprintf(stderr, "peer_voxelizer_bench: line %d: %s: %s\n", line, what,
               cudaGetErrorString(status));
  std::exit(1);
}

[[noreturn]] void usage(const char* problem) {
  std::fprintf(stderr,
               "peer_voxelizer_bench: %s\n"
               "usage: peer_voxelizer_bench [--grids 512,1024] [--repeats 20] [--warmup 2] "
               "[--warmup-ms 200] [--morton] [--managed] [--peer-timer] [--bounds peer|cubic] "
               "MESH...\n",
               problem);
  std::exit(2);
}

struct Options {
  std::vector<unsigned> grids{512, 1024};
  int repeats = 20;
  int warmup = 2;
  int warmup_ms = 200;
  bool morton = false;
  bool managed = false;
  bool peer_timer = false;
  bool cubic_bounds = false;
  std::vector<std::string> meshes;
};

int positive(const char* text, const char* option) {
  char* end = nullptr;
  const long value = std::strtol(text, &end, 10);
  if (*text == '\0' || *end != '\0' || value < 1 || value > 1000000)
    usage((std::string(option) + " wants a positive integer").c_str());
  return int(value);
}

Options parse(int argc, char** argv) {
  Options o;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    auto value = [&]() -> const char* {
      if (i + 1 >= argc) usage((a + " needs a value").c_str());
      return argv[++i];
    };
    if (a == "--grids") {
      o.grids.clear();
      std::string list = value();
      for (size_t start = 0; start <= list.size();) {
        size_t comma = list.find(',', start);
        if (comma == std::string::npos) comma = list.size();
        const int n = positive(list.substr(start, comma - start).c_str(), "--grids");
        if (n % 4 != 0 || n > 2048) usage("--grids: each size a multiple of 4, at most 2048");
        o.grids.push_back(unsigned(n));
        start = comma + 1;
      }
    } else if (a == "--repeats") {
      o.repeats = positive(value(), "--repeats");
    } else if (a == "--warmup") {
      o.warmup = positive(value(), "--warmup");
    } else if (a == "--warmup-ms") {
      o.warmup_ms = positive(value(), "--warmup-ms");
    } else if (a == "--morton") {
      o.morton = true;
    } else if (a == "--managed") {
      o.managed = true;
    } else if (a == "--peer-timer") {
      o.peer_timer = true;
    } else if (a == "--bounds") {
      const std::string b = value();
      if (b != "peer" && b != "cubic") usage("--bounds is peer or cubic");
      o.cubic_bounds = b == "cubic";
    } else if (a.rfind("--", 0) == 0) {
      usage(("unknown option " + a).c_str());
    } else {
      o.meshes.push_back(a);
    }
  }
  if (o.meshes.empty()) usage("no mesh given");
  for (unsigned n : o.grids)  // a Morton index of a grid that is no power of two leaves the table
    if (o.morton && (n & (n - 1)) != 0) usage("--morton needs power-of-two grid sizes");
  return o;
}

std::string json_string(const std::string& s) {
  std::string out = "\"";
  for (char c : s) {
    if (c == '"' || c == '\\') out += '\\';
    if (static_cast<unsigned char>(c) < 0x20) {
      char buf[8];
      std::snprintf(buf, sizeof buf, "\\u%04x", c);
      out += buf;
    } else {
      out += c;
    }
  }
  return out + "\"";
}

std::string stem(const std::string& path) {
  const size_t slash = path.find_last_of('/');
  std::string name = slash == std::string::npos ? path : path.substr(slash + 1);
  const size_t dot = name.find_last_of('.');
  return dot == std::string::npos || dot == 0 ? name : name.substr(0, dot);
}

struct Stats {
  double median, min, max;
};

Stats stats_of(std::vector<float> v) {
  std::sort(v.begin(), v.end());
  const size_t n = v.size();
  const double median = n % 2 ? v[n / 2] : 0.5 * (double(v[n / 2 - 1]) + double(v[n / 2]));
  return {median, v.front(), v.back()};
}

void prefetch_to_device(const void* p, size_t bytes, int device) {
#if CUDART_VERSION >= 13000
  cudaMemLocation location{};
  location.type = cudaMemLocationTypeDevice;
  location.id = device;
  CHECK(cudaMemPrefetchAsync(p, bytes, location, 0, 0));
#else
  CHECK(cudaMemPrefetchAsync(p, bytes, device, 0));
#endif
}

template <typename T>
T* allocate(size_t bytes, bool managed, int device) {
  void* p = nullptr;
  if (managed) {
    CHECK(cudaMallocManaged(&p, bytes));
    prefetch_to_device(p, bytes, device);
  } else {
    CHECK(cudaMalloc(&p, bytes));
  }
  return static_cast<T*>(p);
}

int64_t count_set_bits(const unsigned int* table, size_t bytes) {
  std::vector<unsigned int> host(bytes / sizeof(unsigned int));
  CHECK(cudaMemcpy(host.data(), table, bytes, cudaMemcpyDefault));
  int64_t set = 0;
  for (unsigned int w : host) set += __builtin_popcount(w);
  return set;
}

}  // namespace

int main(int argc, char** argv) {
  const Options o = parse(argc, argv);
  int device = 0;
  CHECK(cudaGetDevice(&device));
  cudaDeviceProp prop{};
  CHECK(cudaGetDeviceProperties(&prop, device));
  trimesh::TriMesh::set_verbose(false);
  if (o.morton) {  // as voxelize() does for the morton output format
    CHECK(cudaMemcpyToSymbol(morton256_x, host_morton256_x, 256 * sizeof(uint32_t)));
    CHECK(cudaMemcpyToSymbol(morton256_y, host_morton256_y, 256 * sizeof(uint32_t)));
    CHECK(cudaMemcpyToSymbol(morton256_z, host_morton256_z, 256 * sizeof(uint32_t)));
  }
  int min_grid = 0, block = 0;  // as voxelize() asks for them
  CHECK(cudaOccupancyMaxPotentialBlockSize(&min_grid, &block, voxelize_triangle, 0, 0));
  cudaEvent_t clear0, clear1, kernel0, kernel1;
  for (cudaEvent_t* e : {&clear0, &clear1, &kernel0, &kernel1}) CHECK(cudaEventCreate(e));

  for (const std::string& path : o.meshes) {
    // Read as the peer's main does.
    trimesh::TriMesh* mesh = trimesh::TriMesh::read(path.c_str());
    if (!mesh) {
      std::fprintf(stderr, "peer_voxelizer_bench: cannot read mesh %s\n", path.c_str());
      return 1;
    }
    mesh->need_faces();
    mesh->need_bbox();
    const size_t n_triangles = mesh->faces.size();
    if (n_triangles == 0) {
      std::fprintf(stderr, "peer_voxelizer_bench: %s has no triangles\n", path.c_str());
      return 1;
    }
    AABox<float3> box;
    if (o.cubic_bounds) {
      const trimesh::point lo = mesh->bbox.min, hi = mesh->bbox.max;
      const double side =
          std::max({double(hi[0]) - lo[0], double(hi[1]) - lo[1], double(hi[2]) - lo[2]});
      double c[3];
      for (int k = 0; k < 3; ++k) c[k] = 0.5 * (double(lo[k]) + double(hi[k]));
      box.min =
          make_float3(float(c[0] - 0.5 * side), float(c[1] - 0.5 * side), float(c[2] - 0.5 * side));
      box.max =
          make_float3(float(c[0] + 0.5 * side), float(c[1] + 0.5 * side), float(c[2] + 0.5 * side));
    } else {
      box = createMeshBBCube<float3>(
          AABox<float3>(trimesh_to_float3(mesh->bbox.min), trimesh_to_float3(mesh->bbox.max)));
    }
    // The triangle layout of meshToGPU_managed: 9 floats per triangle.
    std::vector<float> host_triangles(9 * n_triangles);
    for (size_t i = 0; i < n_triangles; ++i) {
      for (int k = 0; k < 3; ++k) {
        const trimesh::point& p = mesh->vertices[mesh->faces[i][k]];
        for (int d = 0; d < 3; ++d) host_triangles[9 * i + 3 * k + d] = p[d];
      }
    }
    const size_t triangle_bytes = host_triangles.size() * sizeof(float);
    float* triangles = allocate<float>(triangle_bytes, o.managed, device);
    CHECK(cudaMemcpy(triangles, host_triangles.data(), triangle_bytes, cudaMemcpyDefault));
    if (o.managed) prefetch_to_device(triangles, triangle_bytes, device);

    for (unsigned n : o.grids) {
      const voxinfo info(box, make_uint3(n, n, n), n_triangles);
      // The table size as the peer's main computes it.
      const size_t table_bytes = static_cast<size_t>(
          ceil(static_cast<size_t>(info.gridsize.x) * static_cast<size_t>(info.gridsize.y) *
               static_cast<size_t>(info.gridsize.z) / 32.0f) *
          4);
      unsigned int* table = allocate<unsigned int>(table_bytes, o.managed, device);
      const int blocks = static_cast<int>((info.n_triangles + block - 1) / block);
      auto launch = [&] {
        voxelize_triangle<<<blocks, block>>>(info, triangles, table, o.morton);
        CHECK(cudaGetLastError());
      };
      int warmups = 0;
      const auto warm_start = std::chrono::steady_clock::now();
      while (warmups < o.warmup || std::chrono::steady_clock::now() - warm_start <
                                       std::chrono::milliseconds(o.warmup_ms)) {
        CHECK(cudaMemset(table, 0, table_bytes));
        launch();
        CHECK(cudaDeviceSynchronize());
        ++warmups;
      }
      const int64_t warm_filled = count_set_bits(table, table_bytes);
      std::vector<float> clear_ms, kernel_ms;
      for (int r = 0; r < o.repeats; ++r) {
        CHECK(cudaEventRecord(clear0, 0));
        CHECK(cudaMemset(table, 0, table_bytes));
        CHECK(cudaEventRecord(clear1, 0));
        CHECK(cudaEventRecord(kernel0, 0));
        launch();
        if (o.peer_timer) CHECK(cudaDeviceSynchronize());
        CHECK(cudaEventRecord(kernel1, 0));
        CHECK(cudaEventSynchronize(kernel1));
        float c = 0.0f, k = 0.0f;
        CHECK(cudaEventElapsedTime(&c, clear0, clear1));
        CHECK(cudaEventElapsedTime(&k, kernel0, kernel1));
        clear_ms.push_back(c);
        kernel_ms.push_back(k);
      }
      const int64_t filled = count_set_bits(table, table_bytes);
      if (filled != warm_filled) {
        std::fprintf(stderr,
                     "peer_voxelizer_bench: %s at %u: %lld voxels after the warm-up, %lld "
                     "after the timed rounds\n",
                     path.c_str(), n, (long long)warm_filled, (long long)filled);
        return 1;
      }
      const Stats k = stats_of(kernel_ms), c = stats_of(clear_ms);
      std::printf(
          "{\"mesh\":%s,\"path\":%s,\"triangles\":%zu,\"grid\":%u,\"kernel_ms_median\":%.5f,"
          "\"kernel_ms_min\":%.5f,\"kernel_ms_max\":%.5f,\"clear_ms_median\":%.5f,"
          "\"clear_ms_min\":%.5f,\"clear_ms_max\":%.5f,\"repeats\":%d,\"warmup\":%d,"
          "\"filled_voxels\":%lld,\"table_bytes\":%zu,\"block\":%d,\"blocks\":%d,"
          "\"timer\":\"%s\",\"memory\":\"%s\",\"morton\":%s,\"bounds\":\"%s\","
          "\"bbox\":[%.9g,%.9g,%.9g,%.9g,%.9g,%.9g],\"device\":%s}\n",
          json_string(stem(path)).c_str(), json_string(path).c_str(), n_triangles, n, k.median,
          k.min, k.max, c.median, c.min, c.max, o.repeats, warmups, (long long)filled, table_bytes,
          block, blocks, o.peer_timer ? "peer" : "events", o.managed ? "managed" : "device",
          o.morton ? "true" : "false", o.cubic_bounds ? "cubic" : "peer", box.min.x, box.min.y,
          box.min.z, box.max.x, box.max.y, box.max.z, json_string(prop.name).c_str());
      std::fflush(stdout);
      CHECK(cudaFree(table));
    }
    CHECK(cudaFree(triangles));
    delete mesh;
  }
  for (cudaEvent_t e : {clear0, clear1, kernel0, kernel1}) CHECK(cudaEventDestroy(e));
  return 0;
}
