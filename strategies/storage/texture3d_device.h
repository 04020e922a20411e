// Kernel side of the `texture3d` storage (Knecht 2011 §4.2.1): one 3D atlas for all maps of all
// lights with a fixed number of layers per texel, a (depth, visibility) float pair per layer
// (visibility = 1 - the thesis's opacity), layer k of texel t at k * texels + t (the maps side by
// side in x/y, layers along z), and each texel's layer count (instead of clearing every unused
// layer). Lookups: binary search at a ray's first lookup, then the coherent forward/backward
// search from the node the previous lookup of the same ray ended at. Host and device code.
#pragma once

#include <cstdint>

#include "core/hd.h"
#include "cuda/buffer.h"
#include "cuda/read_only.h"
#include "engine/dsm/node_search.h"

namespace dv {

struct Texture3dSink {
  DsmNode* texel_base;  // layer 0 of the texel
  int64_t layer_stride;
  int layers;
  int count = 0;
  DV_HD bool emit(float z, float v) {
    if (count >= layers) return false;
    texel_base[int64_t(count++) * layer_stride] = {z, v};
    return true;
  }
};

struct Texture3dReader {
  View<const DsmNode> atlas;  // layers * texels
  View<const int32_t> counts;
  int64_t texels;

  DV_HD float visibility(int64_t texel, float z, int& hint) const {
    const StridedNodes node{atlas.data + texel, texels};
    return evaluate_nodes(node, read_only(counts.data + texel), z, hint);
  }
};

}  // namespace dv
