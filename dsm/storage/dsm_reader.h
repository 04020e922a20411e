// The lookup side of every DSM storage strategy behind one small type that kernels receive by
// value: a kind and a union of the strategies' readers (only the kind's is set), dispatched with a
// switch (a uniform branch), so the renderer's kernels are instantiated once for the `dsm` shadow
// source, not once per strategy. A new storage adds its reader here. Host and device code.
#pragma once

#include <cstdint>

#include "core/hd.h"
#include "dsm/storage/avsm_device.h"
#include "dsm/storage/beer_device.h"
#include "dsm/storage/blocked_device.h"
#include "dsm/storage/chunked_device.h"
#include "dsm/storage/compact_device.h"
#include "dsm/storage/fourier_device.h"
#include "dsm/storage/moments_device.h"
#include "dsm/storage/occupancy_device.h"
#include "dsm/storage/texture3d_device.h"

namespace dv {

enum class DsmReaderKind : uint8_t {
  compact,
  texture3d,
  chunked,
  blocked,
  beer,
  avsm,
  moments,
  fourier,
  occupancy
};

// The texels one lookup reads: a bilinear filter's four, or the nearest one; -1 for a texel
// outside the map (lit).
struct DsmTaps {
  int64_t texel[4];
  int count = 0;
};

struct DsmReader {
  DsmReaderKind kind = DsmReaderKind::compact;
  // A union, not nine members: the shading kernel keeps a copy of the reader on its stack as the
  // reader call's `this` (80 bytes instead of 312; ptxas -v, sm_90: the DSM shading kernel's
  // stack 1696 -> 1464 bytes).
  union {
    CompactReader compact;
    Texture3dReader texture3d;
    ChunkedReader chunked;
    BlockedReader blocked;
    BeerReader beer;
    AvsmReader avsm;
    MomentsReader moments;
    FourierReader fourier;
    OccupancyReader occupancy;
  };
  DV_HD DsmReader() : compact{} {}

  // f(reader) for the reader of this kind.
  template <class F>
  DV_HD auto with_reader(F f) const {
    switch (kind) {
      case DsmReaderKind::texture3d:
        return f(texture3d);
      case DsmReaderKind::chunked:
        return f(chunked);
      case DsmReaderKind::blocked:
        return f(blocked);
      case DsmReaderKind::beer:
        return f(beer);
      case DsmReaderKind::avsm:
        return f(avsm);
      case DsmReaderKind::moments:
        return f(moments);
      case DsmReaderKind::fourier:
        return f(fourier);
      case DsmReaderKind::occupancy:
        return f(occupancy);
      default:
        return f(compact);
    }
  }

  // V'(z) of texel `texel`; `hint` carries coherent-search state between lookups of one ray
  // (start it at -1).
  DV_HD DV_NOINLINE float visibility(int64_t texel, float z, int& hint) const {
    return with_reader([&](const auto& r) { return r.visibility(texel, z, hint); });
  }

  // V'(z) of every tap of a lookup into v (1 for a tap outside the map), hint[i] tap i's
  // coherent-search state: one call and one dispatch for the lookup's taps. Out of line on the
  // GPU: inlined into each of the fragment kernel's lookups (four bilinear taps, clustered and
  // plain faces), the nine readers took the shading kernel to 255 registers and 3216 bytes of
  // stack (ptxas -v, sm_90); called once a tap, 255 registers, 2000 bytes and spills; once a
  // lookup (with the moments resolve in registers), 240 registers, 1696 bytes, no spills.
  DV_HD DV_NOINLINE void visibilities(const DsmTaps& taps, float z, int* hint, float* v) const {
    with_reader([&](const auto& r) {
      for (int i = 0; i < taps.count; ++i)
        v[i] = taps.texel[i] < 0 ? 1.0f : r.visibility(taps.texel[i], z, hint[i]);
    });
  }
};

}  // namespace dv
