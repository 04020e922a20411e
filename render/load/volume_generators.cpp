// Procedural density volumes (see volume_generators.h): the 3D Shepp-Logan phantom, a seeded
// smoke plume built from our own integer-hash gradient noise (only integer hashing and
// +,-,*,/,sqrt, so outputs are bit-identical wherever IEEE doubles are), a constant block, and
// the JSON entry point that also loads raw and OpenVDB files.
#include "render/load/volume_generators.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <filesystem>

#include "core/error.h"
#include "core/parallel.h"
#include "render/io/vdb_io.h"
#include "render/io/volume_io.h"

namespace dv {

namespace {

// ---- placement -----------------------------------------------------------------------------

// Sample i of n on [-1, 1]; a single sample sits at 0. Matches origin + i * spacing below.
double unit_axis_origin(int n) {
  return n == 1 ? 0.0 : -1.0;
}
double unit_axis_spacing(int n) {
  return n == 1 ? 2.0 : 2.0 / double(n - 1);
}
double unit_axis_coordinate(int i, int n) {
  return unit_axis_origin(n) + double(i) * unit_axis_spacing(n);
}

VolumeGrid unit_cube_grid(const std::string& name, ivec3 dims) {
  check_volume_dims(dims, name);
  VolumeGrid volume;
  volume.name = name;
  volume.dims = dims;
  for (int a = 0; a < 3; ++a) {
    volume.origin[a] = unit_axis_origin(dims[a]);
    volume.spacing[a] = unit_axis_spacing(dims[a]);
  }
  volume.density.assign(size_t(volume.voxel_count()), 0.0f);
  return volume;
}

// ---- Shepp-Logan ---------------------------------------------------------------------------

struct Ellipsoid {
  double intensity;
  dvec3 half_axes;
  dvec3 center;
  double phi_deg;  // rotation about z
};

constexpr std::array<Ellipsoid, 10> kSheppLogan = {{
    {1.0, {0.6900, 0.920, 0.810}, {0.00, 0.0000, 0.00}, 0.0},
    {-0.8, {0.6624, 0.874, 0.780}, {0.00, -0.0184, 0.00}, 0.0},
    {-0.2, {0.1100, 0.310, 0.220}, {0.22, 0.0000, 0.00}, -18.0},
    {-0.2, {0.1600, 0.410, 0.280}, {-0.22, 0.0000, 0.00}, 18.0},
    {0.1, {0.2100, 0.250, 0.410}, {0.00, 0.3500, -0.15}, 0.0},
    {0.1, {0.0460, 0.046, 0.050}, {0.00, 0.1000, 0.25}, 0.0},
    {0.1, {0.0460, 0.046, 0.050}, {0.00, -0.1000, 0.25}, 0.0},
    {0.1, {0.0460, 0.023, 0.050}, {-0.08, -0.6050, 0.00}, 0.0},
    {0.1, {0.0230, 0.023, 0.020}, {0.00, -0.6060, 0.00}, 0.0},
    {0.1, {0.0230, 0.046, 0.020}, {0.06, -0.6050, 0.00}, 0.0},
}};

// Cosine and sine of each ellipsoid's rotation, computed once.
struct EllipsoidRotations {
  std::array<double, kSheppLogan.size()> cos_phi{};
  std::array<double, kSheppLogan.size()> sin_phi{};
  EllipsoidRotations() {
    for (size_t e = 0; e < kSheppLogan.size(); ++e) {
      const double radians = kSheppLogan[e].phi_deg * (3.14159265358979323846 / 180.0);
      cos_phi[e] = std::cos(radians);
      sin_phi[e] = std::sin(radians);
    }
  }
};

const EllipsoidRotations& rotations() {
  static const EllipsoidRotations table;
  return table;
}

bool ellipsoid_contains(size_t e, const dvec3& p) {
  const Ellipsoid& el = kSheppLogan[e];
  const dvec3 d = p - el.center;
  const double c = rotations().cos_phi[e];
  const double s = rotations().sin_phi[e];
  const double lx = (d.x * c + d.y * s) / el.half_axes.x;
  const double ly = (d.y * c - d.x * s) / el.half_axes.y;
  const double lz = d.z / el.half_axes.z;
  return lx * lx + ly * ly + lz * lz <= 1.0;
}

// Sum over the listed ellipsoids in table order, clamped; skipping an ellipsoid that cannot
// contain p leaves the sum bit-identical to the full loop.
template <class Indices>
double sum_intensities(const Indices& indices, size_t count, const dvec3& p) {
  double sum = 0.0;
  for (size_t k = 0; k < count; ++k) {
    if (ellipsoid_contains(indices[k], p)) sum += kSheppLogan[indices[k]].intensity;
  }
  return clamp_value(sum, 0.0, 1.0);
}

// Conservative reach of an ellipsoid along one axis (a little slack so rounding never drops an
// ellipsoid that the exact test would accept).
constexpr double kReachSlack = 1.0 + 1e-6;

// ---- deterministic gradient noise ----------------------------------------------------------

uint64_t mix64(uint64_t z) {
  z += 0x9e3779b97f4a7c15ull;
  z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
  z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
  return z ^ (z >> 31);
}

double fade(double t) {
  return t * t * t * (t * (t * 6.0 - 15.0) + 10.0);
}
double lerp(double a, double b, double t) {
  return a + (b - a) * t;
}

// Dot product of the lattice corner's pseudo-random gradient (one of the 12 cube-edge
// directions) with the offset from that corner.
double corner_gradient_dot(uint64_t hash, double x, double y, double z) {
  switch ((hash >> 40) % 12) {
    case 0:
      return x + y;
    case 1:
      return -x + y;
    case 2:
      return x - y;
    case 3:
      return -x - y;
    case 4:
      return x + z;
    case 5:
      return -x + z;
    case 6:
      return x - z;
    case 7:
      return -x - z;
    case 8:
      return y + z;
    case 9:
      return -y + z;
    case 10:
      return y - z;
    default:
      return -y - z;
  }
}

// Gradient noise in about [-1, 1]; zero at every lattice point.
double gradient_noise(uint64_t seed_hash, const dvec3& p) {
  const double fx = std::floor(p.x), fy = std::floor(p.y), fz = std::floor(p.z);
  const int64_t ix = int64_t(fx), iy = int64_t(fy), iz = int64_t(fz);
  const double x = p.x - fx, y = p.y - fy, z = p.z - fz;
  double corner[2][2][2];
  for (int dx = 0; dx < 2; ++dx) {
    const uint64_t hx = mix64(seed_hash ^ uint64_t(ix + dx));
    for (int dy = 0; dy < 2; ++dy) {
      const uint64_t hxy = mix64(hx ^ uint64_t(iy + dy));
      for (int dz = 0; dz < 2; ++dz) {
        const uint64_t h = mix64(hxy ^ uint64_t(iz + dz));
        corner[dx][dy][dz] = corner_gradient_dot(h, x - dx, y - dy, z - dz);
      }
    }
  }
  const double u = fade(x), v = fade(y), w = fade(z);
  const double x00 = lerp(corner[0][0][0], corner[1][0][0], u);
  const double x10 = lerp(corner[0][1][0], corner[1][1][0], u);
  const double x01 = lerp(corner[0][0][1], corner[1][0][1], u);
  const double x11 = lerp(corner[0][1][1], corner[1][1][1], u);
  return lerp(lerp(x00, x10, v), lerp(x01, x11, v), w);
}

// Fractal sum of `octaves` noise layers (doubling frequency, halving amplitude), normalised
// by the total amplitude and clamped to [-1, 1].
double fbm(uint64_t seed_hash, const dvec3& p, int octaves) {
  double sum = 0.0, amplitude = 1.0, total = 0.0, frequency = 1.0;
  for (int o = 0; o < octaves; ++o) {
    sum += amplitude * gradient_noise(mix64(seed_hash + uint64_t(o)), p * frequency);
    total += amplitude;
    amplitude *= 0.5;
    frequency *= 2.0;
  }
  return clamp_value(sum / total, -1.0, 1.0);
}

double smoothstep(double edge0, double edge1, double x) {
  const double t = clamp_value((x - edge0) / (edge1 - edge0), 0.0, 1.0);
  return t * t * (3.0 - 2.0 * t);
}

// ---- smoke plume shape ---------------------------------------------------------------------

constexpr double kBaseRadius = 0.10;    // column radius at the bottom (unit-cube coordinates)
constexpr double kRadiusGrowth = 0.42;  // extra radius at the top
constexpr double kSwayAmount = 0.25;    // centre drift at the top, per unit turbulence
constexpr double kWarpAmount = 0.12;    // horizontal domain warp, per unit turbulence
constexpr double kWarpFrequency = 2.5;
constexpr double kDetailFrequency = 3.0;

struct SmokeSeeds {
  uint64_t sway_x, sway_z, warp_x, warp_z, detail;
  explicit SmokeSeeds(uint64_t seed)
      : sway_x(mix64(seed ^ 0x51a7e5ull)),
        sway_z(mix64(seed ^ 0x51a7e6ull)),
        warp_x(mix64(seed ^ 0x3a4b1ull)),
        warp_z(mix64(seed ^ 0x3a4b2ull)),
        detail(mix64(seed ^ 0xde7a11ull)) {}
};

}  // namespace

double shepp_logan_density(const dvec3& p) {
  std::array<size_t, kSheppLogan.size()> all{};
  for (size_t e = 0; e < all.size(); ++e) all[e] = e;
  return sum_intensities(all, all.size(), p);
}

VolumeGrid make_shepp_logan_3d(ivec3 dims) {
  VolumeGrid volume = unit_cube_grid("shepp_logan", dims);
  cpu_parallel_for(
      dims.z,
      [&](int64_t k) {
        const double z = unit_axis_coordinate(int(k), dims.z);
        std::array<size_t, kSheppLogan.size()> in_slice{}, in_row{};
        size_t slice_count = 0;
        for (size_t e = 0; e < kSheppLogan.size(); ++e) {
          const Ellipsoid& el = kSheppLogan[e];
          if (std::abs(z - el.center.z) <= el.half_axes.z * kReachSlack)
            in_slice[slice_count++] = e;
        }
        for (int j = 0; j < dims.y; ++j) {
          const double y = unit_axis_coordinate(j, dims.y);
          size_t row_count = 0;
          for (size_t s = 0; s < slice_count; ++s) {
            const Ellipsoid& el = kSheppLogan[in_slice[s]];
            const double reach = std::max(el.half_axes.x, el.half_axes.y) * kReachSlack;
            if (std::abs(y - el.center.y) <= reach) in_row[row_count++] = in_slice[s];
          }
          float* row = volume.density.data() + (k * dims.y + j) * int64_t(dims.x);
          for (int i = 0; i < dims.x; ++i) {
            const dvec3 p(unit_axis_coordinate(i, dims.x), y, z);
            row[i] = float(sum_intensities(in_row, row_count, p));
          }
        }
      },
      1);
  return volume;
}

VolumeGrid make_smoke_plume(ivec3 dims, uint64_t seed, double turbulence) {
  if (!std::isfinite(turbulence) || turbulence < 0.0) {
    throw InputError("smoke", "turbulence must be a finite number >= 0");
  }
  VolumeGrid volume = unit_cube_grid("smoke", dims);
  const SmokeSeeds seeds(seed);

  // Per-row column centre (drifting more with height) and radius.
  std::vector<dvec2> row_center(size_t(dims.y));
  std::vector<double> row_radius(size_t(dims.y));
  for (int j = 0; j < dims.y; ++j) {
    const double t = 0.5 * (unit_axis_coordinate(j, dims.y) + 1.0);
    const dvec3 q(0.0, 1.5 * t, 0.0);
    const double drift = turbulence * kSwayAmount * t;
    row_center[size_t(j)] = drift * dvec2(fbm(seeds.sway_x, q, 3), fbm(seeds.sway_z, q, 3));
    row_radius[size_t(j)] = kBaseRadius + kRadiusGrowth * t;
  }
  const double max_warp = turbulence * kWarpAmount;

  cpu_parallel_for(
      dims.z,
      [&](int64_t k) {
        if (k == 0 || k == dims.z - 1) return;  // border slices stay zero
        const double z = unit_axis_coordinate(int(k), dims.z);
        for (int j = 1; j < dims.y - 1; ++j) {
          const double y = unit_axis_coordinate(j, dims.y);
          const double t = 0.5 * (y + 1.0);
          const double vertical =
              smoothstep(0.0, 0.08, t) * (1.0 - smoothstep(0.8, 0.97, t)) * (1.0 - 0.45 * t);
          if (vertical <= 0.0) continue;
          const dvec2 center = row_center[size_t(j)];
          const double radius = row_radius[size_t(j)];
          float* row = volume.density.data() + (k * dims.y + j) * int64_t(dims.x);
          for (int i = 1; i < dims.x - 1; ++i) {
            const double x = unit_axis_coordinate(i, dims.x);
            const dvec2 offset(x - center.x, z - center.y);
            // fbm is clamped to [-1, 1], so the warp moves a point by at most max_warp per axis.
            const double reach = radius + max_warp * 1.5;
            if (offset.x * offset.x + offset.y * offset.y >= reach * reach) continue;
            const dvec3 p(x, y, z);
            const dvec3 warp_at = p * kWarpFrequency;
            const dvec2 warped = offset + max_warp * dvec2(fbm(seeds.warp_x, warp_at, 3),
                                                           fbm(seeds.warp_z, warp_at, 3));
            const double d = std::sqrt(warped.x * warped.x + warped.y * warped.y) / radius;
            const double profile = 1.0 - smoothstep(0.35, 1.0, d);
            if (profile <= 0.0) continue;
            const dvec3 detail_at(x * kDetailFrequency, y * kDetailFrequency - 0.7 * t,
                                  z * kDetailFrequency);
            const double detail = fbm(seeds.detail, detail_at, 5);
            const double body = clamp_value(0.85 + turbulence * detail, 0.0, 1.0);
            const double border = (1.0 - smoothstep(0.9, 1.0, std::abs(x))) *
                                  (1.0 - smoothstep(0.9, 1.0, std::abs(z)));
            row[i] = float(clamp_value(profile * body * vertical * border, 0.0, 1.0));
          }
        }
      },
      1);
  return volume;
}

VolumeGrid make_constant_block(ivec3 dims, float density) {
  if (!std::isfinite(density) || density < 0.0f || density > 1.0f) {
    throw InputError("block", "density must be in [0, 1], got " + std::to_string(density));
  }
  VolumeGrid volume = unit_cube_grid("block", dims);
  volume.density.assign(volume.density.size(), density);
  return volume;
}

std::vector<std::string> volume_generator_names() {
  return {"shepp_logan", "smoke", "block", "raw", "vdb"};
}

namespace {

std::string resolve_volume_file(const std::string& file, const std::string& scene_dir) {
  std::filesystem::path path(file);
  if (path.is_relative() && !scene_dir.empty()) path = std::filesystem::path(scene_dir) / path;
  return path.string();
}

}  // namespace

VolumeGrid generate_volume(JsonReader& spec, const std::string& scene_dir) {
  const std::string generator = spec.string("generator");
  const auto names = volume_generator_names();
  if (std::find(names.begin(), names.end(), generator) == names.end()) {
    std::string known;
    for (const auto& n : names) known += (known.empty() ? "" : ", ") + n;
    spec.fail("generator", "unknown volume generator '" + generator + "' (known: " + known + ")");
  }
  if (generator == "vdb") {  // size and placement come from the file
    for (const char* key : {"dims", "spacing", "origin"})
      if (spec.has(key)) spec.fail(key, "a vdb volume takes its size and placement from the file");
    const std::string file = spec.string("file");
    const std::string grid = spec.string("grid", kDefaultVdbGrid);
    spec.finish();
    return load_vdb_volume(resolve_volume_file(file, scene_dir), grid);
  }
  const ivec3 dims = spec.ivec3_value("dims");
  check_volume_dims(dims, spec.where("dims"));

  const int largest = std::max(dims.x, std::max(dims.y, dims.z));
  const dvec3 spacing = spec.vec3("spacing", dvec3(largest > 1 ? 1.0 / double(largest - 1) : 1.0));
  for (int a = 0; a < 3; ++a) {
    if (spacing[a] <= 0.0) spec.fail("spacing", "every spacing must be > 0");
  }
  const dvec3 origin = spec.vec3("origin", -0.5 * dvec3(dims - 1) * spacing);

  VolumeGrid volume;
  if (generator == "shepp_logan") {
    spec.finish();
    volume = make_shepp_logan_3d(dims);
  } else if (generator == "smoke") {
    uint64_t seed = 1;
    if (spec.has("seed")) {
      const Json& v = spec.raw("seed");
      if (v.is_number_unsigned()) {
        seed = v.get<uint64_t>();
      } else if (v.is_number_integer() && v.get<int64_t>() >= 0) {
        seed = uint64_t(v.get<int64_t>());
      } else {
        spec.fail("seed", "expected a non-negative integer");
      }
    }
    const double turbulence = spec.number("turbulence", 1.0);
    if (turbulence < 0.0) spec.fail("turbulence", "must be >= 0");
    spec.finish();
    volume = make_smoke_plume(dims, seed, turbulence);
  } else if (generator == "block") {
    const double density = spec.number("density", 1.0);
    if (density < 0.0 || density > 1.0) spec.fail("density", "must be in [0, 1]");
    spec.finish();
    volume = make_constant_block(dims, float(density));
  } else {
    const std::string file = spec.string("file");
    const RawType type = parse_raw_type(spec.string("type"), spec.where("type"));
    const bool big_endian = spec.boolean("big_endian", false);
    spec.finish();
    volume = load_raw_volume(resolve_volume_file(file, scene_dir), dims, type, spacing, big_endian);
  }
  volume.origin = origin;
  volume.spacing = spacing;
  return volume;
}

}  // namespace dv
