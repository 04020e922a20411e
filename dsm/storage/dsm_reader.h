// The lookup side of every DSM storage strategy behind one small type that kernels receive by
// value: a kind and the strategies' readers, dispatched with a switch (a uniform branch), so the
// renderer's kernels are instantiated once for the `dsm` shadow source, not once per strategy.
// A new storage adds its reader here. Host and device code.
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

struct DsmReader {
  DsmReaderKind kind = DsmReaderKind::compact;
  CompactReader compact{};
  Texture3dReader texture3d{};
  ChunkedReader chunked{};
  BlockedReader blocked{};
  BeerReader beer{};
  AvsmReader avsm{};
  MomentsReader moments{};
  FourierReader fourier{};
  OccupancyReader occupancy{};

  // V'(z) of texel `texel`; `hint` carries coherent-search state between lookups of one ray
  // (start it at -1). Out of line on the GPU: inlined into each of the fragment kernel's
  // lookups (four bilinear taps, clustered and plain faces), the nine readers took the shading
  // kernel to 255 registers and 3216 bytes of stack (ptxas -v, sm_90); out of line, 2064 bytes.
  DV_HD DV_NOINLINE float visibility(int64_t texel, float z, int& hint) const {
    switch (kind) {
      case DsmReaderKind::texture3d:
        return texture3d.visibility(texel, z, hint);
      case DsmReaderKind::chunked:
        return chunked.visibility(texel, z, hint);
      case DsmReaderKind::blocked:
        return blocked.visibility(texel, z, hint);
      case DsmReaderKind::beer:
        return beer.visibility(texel, z, hint);
      case DsmReaderKind::avsm:
        return avsm.visibility(texel, z, hint);
      case DsmReaderKind::moments:
        return moments.visibility(texel, z, hint);
      case DsmReaderKind::fourier:
        return fourier.visibility(texel, z, hint);
      case DsmReaderKind::occupancy:
        return occupancy.visibility(texel, z, hint);
      default:
        return compact.visibility(texel, z, hint);
    }
  }
};

}  // namespace dv
