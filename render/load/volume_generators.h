// Procedural density volumes for object interiors: the 3D Shepp-Logan phantom (a standard test
// object with known structure), a seeded smoke plume (soft, turbulent density) and a constant
// block, plus the JSON entry point that scene files use (it also loads raw and OpenVDB volume
// files).
//
// Scene-file parameters of a volume spec (an object read with JsonReader; unknown keys are
// errors):
//   "generator"   required: "shepp_logan" | "smoke" | "block" | "raw" | "vdb"
//   "dims"        required (not for vdb): [x, y, z] sample counts, each >= 1
//   "spacing"     optional: [x, y, z] world units between samples, each > 0;
//                 default 1 / (max(dims) - 1) on every axis, so the largest extent is 1 unit
//                 (1 when max(dims) == 1)
//   "origin"      optional: [x, y, z] position of sample (0,0,0) in object space;
//                 default -0.5 * (dims - 1) * spacing, so the grid is centred on the object
//                 origin
//   smoke only:   "seed" non-negative integer (default 1), "turbulence" >= 0 (default 1.0;
//                 0 gives a smooth column)
//   block only:   "density" in [0, 1] (default 1.0)
//   raw only:     "file" (required; a relative path resolves against the scene's folder),
//                 "type" (required: "uint8" | "uint16" | "float32"), "big_endian" (default
//                 false). Integer samples are divided by 255 / 65535.
//   vdb only:     "file" (required; relative to the scene's folder like raw), "grid" (the float
//                 grid to read, default "density"). "dims", "spacing" and "origin" are errors:
//                 the file's active voxels and transform give them (render/io/vdb_io.h).
// "origin" and "spacing" replace the placement the C++ generators below choose for
// themselves; the samples themselves do not change.
//
// 3D Shepp-Logan phantom used here: the ten-ellipsoid 3D extension with Toft's "modified"
// high-contrast intensities (as in common phantom3d implementations). Ellipsoid i contains
// p when ((R(-phi) (p - c)) / (a, b, c))^2 summed over axes <= 1, where R(phi) rotates about
// the z axis (angles in degrees, counter-clockwise from +x towards +y); the density is the sum
// of the intensities of all ellipsoids containing p, clamped to [0, 1].
//
//    #  intensity   a       b      c       x0      y0      z0     phi
//    1    1.0     0.6900  0.920  0.810    0.00    0.0000  0.00     0   skull (outer)
//    2   -0.8     0.6624  0.874  0.780    0.00   -0.0184  0.00     0   brain (inner)
//    3   -0.2     0.1100  0.310  0.220    0.22    0.0000  0.00   -18   ventricle
//    4   -0.2     0.1600  0.410  0.280   -0.22    0.0000  0.00    18   ventricle
//    5    0.1     0.2100  0.250  0.410    0.00    0.3500 -0.15     0
//    6    0.1     0.0460  0.046  0.050    0.00    0.1000  0.25     0
//    7    0.1     0.0460  0.046  0.050    0.00   -0.1000  0.25     0
//    8    0.1     0.0460  0.023  0.050   -0.08   -0.6050  0.00     0
//    9    0.1     0.0230  0.023  0.020    0.00   -0.6060  0.00     0
//   10    0.1     0.0230  0.046  0.020    0.06   -0.6050  0.00     0
//
// So the skull shell has density 1.0 (the top value), brain tissue 0.2, the ventricles 0.0 and
// the small features 0.3. Some published 3D tables add a second Euler angle (psi = 10) to
// ellipsoids 3 and 4; with theta = 0 it only adds to phi and spoils the 2D phantom's
// orientation, so it is left out here.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "core/json_reader.h"
#include "core/math.h"
#include "engine/scene/scene.h"

namespace dv {

// Density of the 3D Shepp-Logan phantom (table above) at p in phantom coordinates, where the
// phantom fits inside [-1, 1]^3. Already clamped to [0, 1].
double shepp_logan_density(const dvec3& p);

// The phantom sampled on a grid covering [-1, 1] on every axis: origin -1, spacing
// 2 / (dims - 1). Axes are mapped independently, so non-cubic grids such as 512x512x96 squash
// the phantom to fill them. An axis with a single sample sits at 0 (spacing 2).
VolumeGrid make_shepp_logan_3d(ivec3 dims);

// A rising smoke column along +y on a grid covering [-1, 1]^3 (same placement as the
// phantom): narrow at the bottom, widening with height, swaying and broken up by seeded
// gradient-noise fBm whose strength scales with `turbulence` (>= 0). Densities lie in [0, 1]
// and are zero on every border sample. The noise is our own integer-hash lattice noise, so
// the same seed gives bit-identical output on every platform.
VolumeGrid make_smoke_plume(ivec3 dims, uint64_t seed, double turbulence = 1.0);

// Every sample `density` (in [0, 1]); grid covers [-1, 1]^3 like the others.
VolumeGrid make_constant_block(ivec3 dims, float density);

// Builds a volume from a JSON spec (parameters in the comment at the top of this file).
// scene_dir resolves relative raw file paths; errors name the spec's file and JSON path.
VolumeGrid generate_volume(JsonReader& spec, const std::string& scene_dir);

// "shepp_logan", "smoke", "block", "raw", "vdb".
std::vector<std::string> volume_generator_names();

}  // namespace dv
