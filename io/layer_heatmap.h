// The picture that shows where a deep shadow map's memory goes: layers (stored nodes) per texel
// as colour, every face of every light side by side in layout order, with a colour scale below
// (viridis from 0 to the maximum, texels without nodes black, the scale's ends labelled).
#pragma once

#include <cstdint>
#include <vector>

#include "io/image.h"

namespace dv {

// `layers` holds faces * res^2 counts, face after face, rows from the top (texel index
// face * res^2 + y * res + x).
Image layer_heatmap(const std::vector<int32_t>& layers, int faces, int res);

}  // namespace dv
