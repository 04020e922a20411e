// The lookup side of every DSM storage strategy behind one small type that kernels receive by
// value: a tagged union of the strategies' readers (only the active one is set), dispatched with
// a switch (a uniform branch), so the renderer's kernels are instantiated once for the `dsm`
// shadow source, not once per strategy. A new storage adds its reader to the type list below
// (its include and one line). Host and device code.
#pragma once

#include <cstdint>

#include "core/hd.h"
#include "core/tagged_union.h"
#include "strategies/storage/avsm_device.h"
#include "strategies/storage/beer_device.h"
#include "strategies/storage/blocked_device.h"
#include "strategies/storage/chunked_device.h"
#include "strategies/storage/compact_device.h"
#include "strategies/storage/fourier_device.h"
#include "strategies/storage/moments_device.h"
#include "strategies/storage/occupancy_device.h"
#include "strategies/storage/texture3d_device.h"

namespace dv {

// The storages' readers: the tag, the union and the dispatch of DsmReader are generated from
// this list (core/tagged_union.h). A new storage adds its reader here, one line.
using DsmReaders = TaggedUnion<CompactReader,    //
                               Texture3dReader,  //
                               ChunkedReader,    //
                               BlockedReader,    //
                               BeerReader,       //
                               AvsmReader,       //
                               MomentsReader,    //
                               FourierReader,    //
                               OccupancyReader>;

// The texels one lookup reads: a bilinear filter's four, or the nearest one; -1 for a texel
// outside the map (lit).
struct DsmTaps {
  int64_t texel[4];
  int count = 0;
};

// A union, not one member per storage: the shading kernel keeps a copy of the reader on its stack
// as the reader call's `this`, so its size is the largest reader's (measured in
// results/perf/rounds/12-reader-union/README.md).
struct DsmReader : DsmReaders {
  using DsmReaders::DsmReaders;

  // V'(z) of texel `texel`; `hint` carries coherent-search state between lookups of one ray
  // (start it at -1).
  DV_HD DV_NOINLINE float visibility(int64_t texel, float z, int& hint) const {
    return dispatch([&](const auto& r) { return r.visibility(texel, z, hint); });
  }

  // V'(z) of every tap of a lookup into v (1 for a tap outside the map), hint[i] tap i's
  // coherent-search state: one call and one dispatch for the lookup's taps. Out of line on the
  // GPU: inlined into each of the fragment kernel's lookups, or called once a tap, the readers
  // took the shading kernel to 255 registers and spills; called once a lookup it needs neither
  // (ptxas -v: results/perf/rounds/11-lookup-taps/README.md).
  DV_HD DV_NOINLINE void visibilities(const DsmTaps& taps, float z, int* hint, float* v) const {
    dispatch([&](const auto& r) {
      for (int i = 0; i < taps.count; ++i)
        v[i] = taps.texel[i] < 0 ? 1.0f : r.visibility(taps.texel[i], z, hint[i]);
    });
  }
};

}  // namespace dv
