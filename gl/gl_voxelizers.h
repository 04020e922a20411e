// Registration of the OpenGL voxelizers, `slicemap` (gl_slicemap.h) and `atlas` (gl_atlas.h,
// parameter atlas: texels per atlas side, as the CPU/CUDA one), into gl_voxelizer_registry()
// (strategies/voxelizer/voxelizer.h), which `deepvox voxelize --backend gl` uses. Each voxelizer
// creates its headless EGL context on first use (on the calling thread) and throws dv::Error
// with the reason when none can be had.
#pragma once

#include "strategies/voxelizer/voxelizer.h"

namespace dv::gl {

void register_gl_voxelizers(Registry<Voxelizer>& registry);
// Registers them into gl_voxelizer_registry() once per program; later calls do nothing.
void install_gl_voxelizers();

}  // namespace dv::gl
