// `deepvox list`: the registered strategies of every family, the generators and the backends.
#include <cstdio>

#include "apps/deepvox/commands.h"
#include "cuda/device_memory.h"
#include "dsm/storage/dsm_storage.h"
#include "experiments/harness/driver.h"
#include "generators/mesh_generators.h"
#include "generators/volume_generators.h"
#include "strategies/shadow/shadow_method.h"
#include "strategies/voxelizer/voxelizer.h"

namespace dv::cli {

namespace {

template <class Base>
void print_family(const Registry<Base>& registry) {
  std::printf("%s:\n", registry.family().c_str());
  if (registry.names().empty()) std::printf("  (none registered yet)\n");
  for (const std::string& name : registry.names())
    std::printf("  %-20s %s\n", name.c_str(), registry.description(name).c_str());
}

void print_names(const char* title, const std::vector<std::string>& names) {
  std::printf("%s:\n ", title);
  for (const std::string& n : names) std::printf(" %s", n.c_str());
  std::printf("\n");
}

}  // namespace

Runner add_list(CLI::App& app) {
  app.add_subcommand("list", "registered strategies, generators and backends");
  return [] {
    print_family(shadow_registry());
    print_family(storage_registry());
    print_family(voxelizer_registry());
    print_family(driver_registry());
    print_names("mesh generators", mesh_generator_names());
    print_names("volume generators", volume_generator_names());
    std::string why;
    const bool gpu = cuda_device_available(&why);
    std::printf("backends:\n  cpu                  available\n  cuda                 %s\n",
                gpu ? ("available: " + cuda_device_name()).c_str() : why.c_str());
    return 0;
  };
}

}  // namespace dv::cli
