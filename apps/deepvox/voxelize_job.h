// What `deepvox voxelize` does, as library functions the tests can call: parse the resolution
// and bounds options, voxelize a mesh or scene with a registered voxelizer, optionally measure
// it against `exact`, write the grid (binvox, or .vdb in a build with OpenVDB) and the stats JSON.
#pragma once

#include <functional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "core/math.h"
#include "cuda/execute.h"
#include "strategies/voxelizer/voxel_bounds.h"

namespace dv {

struct VoxelizeJob {
  std::string input;                // mesh file or scene (anything load_scene takes)
  std::string method = "sat";       // registered voxelizer
  std::vector<std::string> params;  // key=value for the voxelizer
  std::string backend;              // "cpu" | "cuda" | "gl"; empty: CUDA when a GPU is present
  std::string res = "512x512x32";   // WxHxD, D a multiple of 32
  std::string bounds;               // "x0,y0,z0,x1,y1,z1"; empty: the scene's bounds made cubic
  std::string out;                  // .binvox or .vdb path; empty: none written
  std::string stats;                // stats JSON path; empty: none written
  bool compare_exact = false;       // add metrics against `exact` (CPU) to the stats
};

// Whether the job asks for the OpenGL implementation (backend "gl", gl_voxelizer_registry()).
bool voxelize_job_uses_gl(const VoxelizeJob& job);
// The Backend whose memory receives the grid: Backend::cpu for "gl", else the parsed name
// (InputError for unknown names) or the default backend.
Backend voxelize_job_backend(const VoxelizeJob& job);

// Run metadata for the stats, asked for once the input is loaded (the device query in it waits
// for the CUDA driver, which starts while the input loads); nullptr: none.
using RunMetadataSource = std::function<nlohmann::json(Backend)>;

// Runs the job and returns its stats (also written to job.stats, with `meta`'s answer under
// "meta").
nlohmann::json run_voxelize_job(const VoxelizeJob& job, const RunMetadataSource& meta = nullptr);

}  // namespace dv
