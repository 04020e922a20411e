// Deep shadow maps as OpenEXR deep images (through OpenImageIO's deep-data API), the interchange
// format of deep compositing tools, so that the maps can be inspected and composited elsewhere
// and read back exactly. One subimage per map face; per texel one deep sample per node of its
// visibility function: Z = node depth, A = the alpha that makes front-to-back compositing of
// samples 0..k give accumulated opacity 1 - v_k, and V = v_k itself (exact on reading back).
// Each subimage's header holds the face's world-to-clip matrix, light and face index, eps,
// depth convention, resolution and the deepvox commit. Full build only: the lean build links
// render/io/deep_exr_unavailable.cpp, whose functions throw an InputError saying so.
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "engine/dsm/node_search.h"

namespace dv {

struct DeepMapFace {
  int resolution = 0;            // res x res texels; texel index y * res + x
  std::vector<int64_t> offsets;  // res^2 + 1: texel t's nodes are nodes[offsets[t], offsets[t + 1])
  std::vector<DsmNode> nodes;
  // clip = world_to_clip * (p, 1), column-major (glm's memory order, which is the row-major
  // memory of the Imath M44d that maps row vectors, p * M, as EXR stores matrices).
  std::array<double, 16> world_to_clip{};
  int light = 0;
  int face = 0;               // index in the light's faces (omni: 0..5 = +x, -x, +y, -y, +z, -z)
  bool orthographic = false;  // depth: from the near plane along the axis; else from the light
};

struct DeepMapFile {
  float eps = 0.0f;
  std::string commit;  // deepvox git commit that wrote the file ("" when unknown)
  std::vector<DeepMapFace> faces;
};

// The alpha of the deep sample of a node with visibility v after one with v_before (1 before
// the first): front-to-back compositing then accumulates opacity 1 - v.
inline float deep_sample_alpha(float v_before, float v) {
  return v_before > 0.0f ? 1.0f - v / v_before : 0.0f;
}

// False in the lean build (no OpenImageIO).
bool deep_exr_supported();
// Throws InputError naming `path` when it cannot be written.
void write_deep_exr(const std::string& path, const DeepMapFile& file);
// Throws InputError naming `path` and the problem: missing file, not a deep image, channels
// other than A, Z and V of float type, a face that is not square.
DeepMapFile read_deep_exr(const std::string& path);

}  // namespace dv
