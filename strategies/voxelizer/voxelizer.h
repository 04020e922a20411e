// Host side of the voxelizer family (slicemap, atlas, sat, atlas-compute, exact): a named
// strategy with its parameters that fills a binary grid (voxel_grid.h) from a triangle soup.
// Registered: `exact` (CPU reference, exact_voxelizer.h), `sat` (conservative, CPU and CUDA,
// sat_device.h), `slicemap` (slicemap_voxelizer.h), `atlas` and `atlas-compute`
// (atlas_voxelizer.h). OpenGL implementations (gl/gl_voxelizers.h) sit in a registry of their
// own, filled only by programs that link the GL library.
#pragma once

#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "core/registry.h"
#include "cuda/execute.h"
#include "strategies/voxelizer/triangle_soup.h"
#include "strategies/voxelizer/voxel_grid.h"

namespace dv {

struct VoxelizePass {
  std::string name;
  double milliseconds = 0.0;
};

struct VoxelizeResult {
  VoxelGrid grid;  // host memory on the CPU backend, device memory on CUDA
  std::vector<VoxelizePass> passes;
  nlohmann::json counters = nlohmann::json::object();  // strategy-specific figures

  double total_milliseconds() const;
  nlohmann::json passes_json() const;  // [{"pass": name, "ms": t}, ...]
};

class Voxelizer {
 public:
  virtual ~Voxelizer() = default;
  virtual std::string name() const = 0;
  virtual nlohmann::json params() const = 0;
  virtual bool supports(Backend backend) const = 0;
  // Voxelizes every triangle of `soup` into a fresh grid of `spec` (validated here). Throws
  // InputError when the backend is not supported.
  virtual VoxelizeResult voxelize(Backend backend, const TriangleSoup& soup,
                                  const GridSpec& spec) = 0;
};

// A voxelizer without parameters that is one function (exact, sat, slicemap): CPU always, CUDA
// when `gpu` and the build has it.
using VoxelizeFunction = VoxelizeResult (*)(Backend, const TriangleSoup&, const GridSpec&);
class FunctionVoxelizer : public Voxelizer {
 public:
  FunctionVoxelizer(std::string name, VoxelizeFunction voxelize, bool gpu)
      : name_(std::move(name)), voxelize_(voxelize), gpu_(gpu) {}
  std::string name() const override { return name_; }
  nlohmann::json params() const override { return nlohmann::json::object(); }
  bool supports(Backend backend) const override {
    return backend == Backend::cpu || (gpu_ && kBuiltWithCuda);
  }
  VoxelizeResult voxelize(Backend backend, const TriangleSoup& soup,
                          const GridSpec& spec) override {
    return voxelize_(backend, soup, spec);
  }

 private:
  std::string name_;
  VoxelizeFunction voxelize_;
  bool gpu_;
};

Registry<Voxelizer>& voxelizer_registry();

// The OpenGL implementations of registered methods, under the same names (`deepvox voxelize
// --backend gl`). GL is not a Backend (execute.h: kernels run on CPU threads or CUDA): these
// voxelizers support Backend::cpu only, meaning that their grids come back in host memory.
// Empty unless the program called gl::install_gl_voxelizers (gl/gl_voxelizers.h).
Registry<Voxelizer>& gl_voxelizer_registry();

}  // namespace dv
