// The picture that shows where a deep shadow map's memory goes: layers (stored nodes) per texel
// as colour, every face of every light in a near-square grid in layout order (ceil(sqrt(n))
// columns, at most kHeatmapMaxWidth pixels wide), each face under its label ("L2 +X"), with a
// colour scale below (viridis from 0 to the maximum, texels without nodes black, the scale's
// ends labelled). Text is stb_easy_font's (libstb-dev), scaled with the map.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "core/image.h"

namespace dv {

inline constexpr int kHeatmapMaxWidth = 8192;  // columns are dropped beyond this (one at least)

// `layers` holds faces * res^2 counts, face after face, rows from the top (texel index
// face * res^2 + y * res + x); `labels` one per face, or none.
Image layer_heatmap(const std::vector<int32_t>& layers, int faces, int res,
                    const std::vector<std::string>& labels = {});

}  // namespace dv
