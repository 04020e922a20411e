// `deepvox voxelize` (options: its --help, docs/cli.md): a binary surface voxel grid of every
// triangle of the scene, written as binvox or as an OpenVDB float grid "density"
// (render/io/vdb_io.h; not in the lean build), with counts, pass timings and (optionally) the
// metrics against `exact` in the stats JSON. The work itself is run_voxelize_job
// (apps/deepvox/voxelize_job.h). In the full binary `--backend gl` runs the OpenGL implementations
// (gl/gl_voxelizers.h, registered by main.cpp), headless through EGL.
#include <cstdio>

#include "apps/deepvox/commands.h"
#include "apps/deepvox/voxelize_job.h"
#include "core/log.h"
#include "experiments/harness/run_metadata.h"
#include "strategies/voxelizer/voxelizer.h"

namespace dv::cli {

Runner add_voxelize(CLI::App& app) {
  auto job = std::make_shared<VoxelizeJob>();
  CLI::App* cmd = app.add_subcommand("voxelize", "binary surface voxel grid of a mesh or scene");
  cmd->add_option("scene", job->input, "mesh file or scene (.json, .gltf/.glb, .obj/.off/...)")
      ->required();
  cmd->add_option("--method", job->method, "voxelizer (see `deepvox list`)")->capture_default_str();
  cmd->add_option("--param", job->params, "voxelizer parameter key=value (repeatable)");
  cmd->add_option("--backend", job->backend,
                  "cpu, cuda or gl (OpenGL through EGL; default: cuda when a GPU is present)");
  cmd->add_option("--res", job->res, "grid size WxHxD, D a multiple of 32")->capture_default_str();
  cmd->add_option("--bounds", job->bounds,
                  "grid box x0,y0,z0,x1,y1,z1 (default: the scene's bounds made cubic)");
  cmd->add_option("--out", job->out,
                  "grid to write: .binvox, or .vdb (float grid \"density\", 1 in set voxels)")
      ->required();
  cmd->add_option("--stats", job->stats, "write counts, timings and run metadata as JSON");
  cmd->add_flag("--compare-exact", job->compare_exact,
                "also run `exact` on the CPU and report missing/extra voxels");
  return [job] {
    // Run metadata (a git call, the device query) only for a stats file that holds it.
    RunMetadataSource meta;
    if (!job->stats.empty())
      meta = [job](Backend backend) {
        nlohmann::json m = run_metadata(backend);
        if (voxelize_job_uses_gl(*job)) m["backend"] = "gl";
        return m;
      };
    const nlohmann::json stats = run_voxelize_job(*job, meta);
    log_info("voxelize: " + stats["method"].get<std::string>() + " on " +
             stats["backend"].get<std::string>() + ": " +
             std::to_string(stats["filled"].get<int64_t>()) + " voxels set in " +
             std::to_string(stats["total_ms"].get<double>()) + " ms -> " + job->out);
    if (stats.contains("exact")) {
      const nlohmann::json& m = stats["exact"]["metrics"];
      std::printf("vs exact: missing %lld (%lld outside the band), extra %lld (%lld outside)\n",
                  (long long)m["missing"].get<int64_t>(),
                  (long long)m["missing_outside_band"].get<int64_t>(),
                  (long long)m["extra"].get<int64_t>(),
                  (long long)m["extra_outside_band"].get<int64_t>());
    }
    return 0;
  };
}

}  // namespace dv::cli
