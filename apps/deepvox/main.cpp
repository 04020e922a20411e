// deepvox: the research testbed's one executable. Parses the subcommand (command-line mistakes:
// apps/deepvox/usage_errors.h), runs it, and turns every error into a clear message on stderr
// and a non-zero exit (never a crash).
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <map>
#include <set>
#include <string>

#include "apps/deepvox/commands.h"
#include "apps/deepvox/usage_errors.h"
#include "core/error.h"
#include "core/wall_phases.h"
#include "cuda/device_warmup.h"
#include "experiments/harness/run_metadata.h"
#if DEEPVOX_WITH_GL
#include "gl/gl_voxelizers.h"
#include "strategies/voxelizer/voxelizer.h"
#endif

namespace {

// Whether the parsed subcommand may run on the GPU: it has a --backend option that is unset
// (cuda when a GPU is present) or says cuda.
bool may_use_cuda(CLI::App& sub) {
  static const std::set<std::string> kDeviceCommands{"render", "voxelize", "dsm", "probe",
                                                     "advise"};
  if (!kDeviceCommands.count(sub.get_name())) return false;
  const CLI::Option* backend = sub.get_option_no_throw("--backend");
  if (!backend || backend->count() == 0) return true;
  return backend->as<std::string>() == "cuda";
}

}  // namespace

int main(int argc, char** argv) {
  dv::start_wall_phases();
  // Load each CUDA kernel on its first launch, not all of them at context creation (the default
  // since CUDA 12.2; older runtimes loaded eagerly). A value set by the user wins.
  setenv("CUDA_MODULE_LOADING", "LAZY", 0);
  CLI::App app{"deepvox " DEEPVOX_VERSION
               ": deep shadow maps and voxelization for translucent scenes (research testbed)",
               "deepvox"};
  app.set_version_flag("--version", dv::version_text(), "print the version, commit and build");
  app.require_subcommand(1);
  dv::remember_command_line(argc, argv);
#if DEEPVOX_WITH_GL
  dv::gl::install_gl_voxelizers();  // voxelize --backend gl
#endif
  std::map<std::string, dv::cli::Runner> runners;
  runners["probe"] = dv::cli::add_probe(app);
  runners["render"] = dv::cli::add_render(app);
  runners["info"] = dv::cli::add_info(app);
  runners["list"] = dv::cli::add_list(app);
  runners["voxelize"] = dv::cli::add_voxelize(app);
  runners["dsm"] = dv::cli::add_dsm(app);
  runners["suite"] = dv::cli::add_suite(app);
  runners["merge"] = dv::cli::add_merge(app);
  runners["report"] = dv::cli::add_report(app);
  runners["advise"] = dv::cli::add_advise(app);
#if DEEPVOX_WITH_VIEWER
  runners["view"] = dv::cli::add_view(app);
#endif
  runners["help"] = dv::cli::add_help(app);
  if (const int parse_exit = dv::cli::parse_command_line(app, argc, argv); parse_exit >= 0)
    return parse_exit;
  dv::mark_wall_phase("arguments parsed");
  CLI::App* sub = app.get_subcommands().at(0);
  const dv::CudaWarmup warmup(may_use_cuda(*sub));  // overlaps the command's input loading
  int exit_code = 0;
  try {
    exit_code = runners.at(sub->get_name())();
  } catch (const dv::InputError& e) {
    std::fprintf(stderr, "deepvox: error: %s\n", e.what());
    exit_code = 2;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "deepvox: error: %s\n", e.what());
    exit_code = 1;
  }
  return exit_code;
}
