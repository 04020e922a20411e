// OpenVDB volumes with OpenVDB (see vdb_io.h): the only file that includes OpenVDB's headers,
// so the library's templates and their warnings stay in one translation unit. Files are read
// without delayed loading (no memory-mapped file a truncated file could fault in), and only
// after their header and grid descriptors have been checked against the file's length
// (GridExtentProbe below).
#include <openvdb/io/File.h>
#include <openvdb/openvdb.h>
#include <openvdb/tools/Dense.h>

#include <algorithm>
#include <climits>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <istream>
#include <mutex>
#include <streambuf>
#include <system_error>

#include "core/error.h"
#include "render/io/vdb_io.h"
#include "render/io/volume_io.h"

namespace dv {

namespace {

void initialize_openvdb() {
  static std::once_flag once;
  std::call_once(once, [] { openvdb::initialize(); });
}

std::string coord_text(const openvdb::Coord& c) {
  return "(" + std::to_string(c.x()) + ", " + std::to_string(c.y()) + ", " + std::to_string(c.z()) +
         ")";
}

void require_readable_file(const std::string& path) {
  namespace fs = std::filesystem;
  std::error_code ec;
  const fs::file_status status = fs::status(path, ec);
  if (ec || !fs::exists(status)) throw InputError(path, "volume file not found");
  if (!fs::is_regular_file(status)) throw InputError(path, "volume path is not a regular file");
}

// "density (float), temperature (float)": the grids a file holds, for the error that names none.
std::string grid_listing(openvdb::io::File& file) {
  std::string listing;
  const openvdb::GridPtrVecPtr grids = file.readAllGridMetadata();  // alive through the loop
  for (const openvdb::GridBase::Ptr& grid : *grids) {
    if (!listing.empty()) listing += ", ";
    listing += "'" + grid->getName() + "' (" + grid->valueType() + ")";
  }
  return listing.empty() ? "none" : listing;
}

// A read-only view of a file that does not end: past its last byte it yields zeros and notes
// that a reader went there. OpenVDB 10 reads sizes and counts with istream::read without
// checking the stream, so on a truncated file it goes on with whatever its variables held
// (uninitialised memory: an allocation of terabytes, which AddressSanitizer aborts). Zeros make
// such a read harmless and the note turns it into a clear error.
class ZeroPaddedFile final : public std::streambuf {
 public:
  explicit ZeroPaddedFile(const std::string& path) : in_(path, std::ios::binary) {
    in_.seekg(0, std::ios::end);
    size_ = in_.good() ? std::streamoff(in_.tellg()) : 0;
  }
  std::streamoff size() const { return size_; }
  bool read_past_end() const { return read_past_end_; }

 protected:
  int_type underflow() override {
    if (gptr() < egptr()) return traits_type::to_int_type(*gptr());
    const std::streamoff at = position();
    std::streamsize loaded = 0;
    if (at < size_) {
      in_.clear();
      in_.seekg(at);
      in_.read(buffer_, std::streamsize(std::min<std::streamoff>(kBuffer, size_ - at)));
      loaded = in_.gcount();
    }
    if (loaded == 0) {
      read_past_end_ = true;
      std::memset(buffer_, 0, kBuffer);
      loaded = kBuffer;
    }
    base_ = at;
    setg(buffer_, buffer_, buffer_ + loaded);
    return traits_type::to_int_type(*gptr());
  }
  pos_type seekoff(off_type offset, std::ios_base::seekdir from,
                   std::ios_base::openmode which) override {
    const std::streamoff origin = from == std::ios_base::beg   ? 0
                                  : from == std::ios_base::cur ? position()
                                                               : size_;
    return seekpos(pos_type(origin + offset), which);
  }
  pos_type seekpos(pos_type target, std::ios_base::openmode which) override {
    if (!(which & std::ios_base::in) || std::streamoff(target) < 0) return pos_type(off_type(-1));
    base_ = std::streamoff(target);
    setg(buffer_, buffer_, buffer_);  // empty: the next read loads from the new position
    return target;
  }

 private:
  static constexpr std::streamsize kBuffer = 4096;
  std::streamoff position() const { return base_ + (gptr() - eback()); }

  std::ifstream in_;
  std::streamoff size_ = 0;
  std::streamoff base_ = 0;  // file offset of buffer_[0]
  bool read_past_end_ = false;
  char buffer_[kBuffer];
};

// Reads what io::File::open reads (header, file metadata, one descriptor per grid) through a
// ZeroPaddedFile and requires every grid to end inside the file, so that OpenVDB's own reader
// never reads past the end. Archive's readers are protected: hence a subclass.
class GridExtentProbe final : public openvdb::io::Archive {
 public:
  void require_complete(const std::string& path) {
    ZeroPaddedFile file(path);
    std::istream in(&file);
    const std::string size_text = std::to_string(file.size()) + " bytes";
    try {
      readHeader(in);
      setFormatVersion(in);
      setLibraryVersion(in);
      setDataCompression(in);
      openvdb::MetaMap metadata;
      metadata.readMeta(in);
      if (inputHasGridOffsets() && !file.read_past_end()) {
        const int32_t count = readGridCount(in);
        for (int32_t i = 0; i < count && !file.read_past_end(); ++i) {
          openvdb::io::GridDescriptor grid;
          grid.read(in);
          if (file.read_past_end()) break;
          const bool ordered = grid.getGridPos() >= 0 && grid.getGridPos() <= grid.getBlockPos() &&
                               grid.getBlockPos() <= grid.getEndPos();
          if (!ordered || grid.getEndPos() > file.size()) {
            throw InputError(
                path, "not a readable OpenVDB file: truncated or damaged: grid '" +
                          grid.gridName() + "' spans bytes " + std::to_string(grid.getGridPos()) +
                          " to " + std::to_string(grid.getEndPos()) + " of a file of " + size_text);
          }
          grid.seekToEnd(in);
        }
      }
    } catch (const InputError&) {
      throw;
    } catch (const std::exception& e) {
      if (!file.read_past_end())
        throw InputError(path, std::string("not a readable OpenVDB file: ") + e.what());
    }
    if (file.read_past_end()) {
      throw InputError(path, "not a readable OpenVDB file: truncated: it ends (" + size_text +
                                 ") inside its header, metadata or grid descriptors");
    }
  }
};

openvdb::FloatGrid::Ptr read_float_grid(const std::string& path, const std::string& grid_name) {
  GridExtentProbe().require_complete(path);
  openvdb::io::File file(path);
  file.open(false);
  if (!file.hasGrid(grid_name)) {
    const std::string listing = grid_listing(file);
    throw InputError(path, "no grid named '" + grid_name + "' (grids in the file: " + listing +
                               "); name one with \"grid\"");
  }
  const openvdb::GridBase::Ptr base = file.readGrid(grid_name);
  file.close();
  openvdb::FloatGrid::Ptr grid = openvdb::gridPtrCast<openvdb::FloatGrid>(base);
  if (!grid) {
    throw InputError(path, "grid '" + grid_name + "' holds " + base->valueType() + " values (" +
                               base->type() + "); deepvox reads float grids");
  }
  return grid;
}

// Origin and spacing of index space, or an InputError for transforms that are not linear and
// axis aligned with positive voxel sizes.
void axis_aligned_placement(const std::string& path, const std::string& grid_name,
                            const openvdb::math::Transform& transform, dvec3& origin,
                            dvec3& spacing) {
  const std::string which = "grid '" + grid_name + "': ";
  if (!transform.isLinear()) {
    throw InputError(path, which + "its transform (" + transform.mapType() +
                               ") is not linear (a frustum); deepvox reads linear, axis-aligned "
                               "transforms: resample the grid to one first");
  }
  const openvdb::Vec3d o = transform.indexToWorld(openvdb::Vec3d(0.0));
  for (int a = 0; a < 3; ++a) {
    openvdb::Vec3d step(0.0);
    step[a] = 1.0;
    const openvdb::Vec3d axis = transform.indexToWorld(step) - o;
    const double length = axis.length();
    const bool aligned = std::isfinite(length) && length > 0.0 &&
                         std::abs(axis[(a + 1) % 3]) <= 1e-9 * length &&
                         std::abs(axis[(a + 2) % 3]) <= 1e-9 * length && axis[a] > 0.0;
    if (!aligned) {
      throw InputError(path, which + "its transform (" + transform.mapType() +
                                 ") is rotated, sheared or mirrored (index axis " +
                                 std::to_string(a) + " maps to (" + std::to_string(axis[0]) + ", " +
                                 std::to_string(axis[1]) + ", " + std::to_string(axis[2]) +
                                 ")); deepvox reads axis-aligned transforms: rotate the object "
                                 "in the scene instead, or resample the grid");
    }
    spacing[a] = axis[a];
  }
  for (int a = 0; a < 3; ++a) origin[a] = o[a];
}

}  // namespace

bool vdb_supported() {
  return true;
}

void require_vdb_support(const std::string&) {}

VolumeGrid load_vdb_volume(const std::string& path, const std::string& grid_name) {
  require_readable_file(path);
  initialize_openvdb();
  openvdb::FloatGrid::Ptr grid;
  try {
    grid = read_float_grid(path, grid_name);
  } catch (const InputError&) {
    throw;
  } catch (const std::exception& e) {
    // OpenVDB's own errors, and what a damaged file makes of its sizes (std::bad_alloc).
    throw InputError(path, std::string("not a readable OpenVDB file: ") + e.what());
  }

  dvec3 origin{0.0}, spacing{1.0};
  axis_aligned_placement(path, grid_name, grid->transform(), origin, spacing);

  const openvdb::CoordBBox active = grid->evalActiveVoxelBoundingBox();
  if (active.empty()) throw InputError(path, "grid '" + grid_name + "' has no active voxels");
  for (int a = 0; a < 3; ++a)
    if (active.min()[a] == INT_MIN || active.max()[a] == INT_MAX)
      throw InputError(path,
                       "grid '" + grid_name + "': active voxels reach the edge of index space");
  // One voxel more on every side (vdb_io.h), in 64 bits: an index box may span all of int32.
  int64_t extent[3];
  for (int a = 0; a < 3; ++a) extent[a] = int64_t(active.max()[a]) - active.min()[a] + 3;
  const bool too_large = extent[0] * extent[1] > kMaxVolumeVoxels ||
                         extent[0] * extent[1] * extent[2] > kMaxVolumeVoxels;
  if (too_large) {
    const double bytes = double(extent[0]) * double(extent[1]) * double(extent[2]) * 4.0;
    char bytes_text[64];
    std::snprintf(bytes_text, sizeof bytes_text, "%.0f", bytes);
    throw InputError(
        path, "grid '" + grid_name + "': active voxels span " + coord_text(active.min()) + " to " +
                  coord_text(active.max()) + ", a dense grid of " + std::to_string(extent[0]) +
                  "x" + std::to_string(extent[1]) + "x" + std::to_string(extent[2]) +
                  " samples with its border (" + bytes_text + " bytes of float32); at most " +
                  std::to_string(kMaxVolumeVoxels) + " samples (" +
                  std::to_string(kMaxVolumeVoxels * 4) + " bytes) are allowed");
  }
  const openvdb::CoordBBox box(active.min().offsetBy(-1), active.max().offsetBy(1));

  VolumeGrid volume;
  volume.name = path;
  volume.dims = ivec3(int(extent[0]), int(extent[1]), int(extent[2]));
  volume.spacing = spacing;
  const openvdb::Vec3d lo = grid->transform().indexToWorld(box.min());
  volume.origin = dvec3(lo[0], lo[1], lo[2]);
  volume.density.resize(size_t(volume.voxel_count()));
  // LayoutXYZ: x fastest, as VolumeGrid; the dense view writes straight into the densities.
  openvdb::tools::Dense<float, openvdb::tools::LayoutXYZ> dense(box, volume.density.data());
  openvdb::tools::copyToDense(*grid, dense);
  for (size_t i = 0; i < volume.density.size(); ++i) {
    if (!std::isfinite(volume.density[i])) {
      const int64_t x = int64_t(i) % extent[0];
      const int64_t y = (int64_t(i) / extent[0]) % extent[1];
      const int64_t z = int64_t(i) / (extent[0] * extent[1]);
      throw InputError(path, "grid '" + grid_name + "': the value at index " +
                                 coord_text(box.min().offsetBy(int(x), int(y), int(z))) +
                                 " is not a finite number");
    }
  }
  return volume;
}

void write_vdb_occupancy(const std::string& path, const VoxelGrid& grid) {
  const GridSpec& spec = grid.spec();
  if (spec.kind != GridKind::box) {
    throw InputError(path,
                     "only box grids can be written as .vdb (a light-frustum grid has no "
                     "linear placement)");
  }
  initialize_openvdb();
  const VoxelGrid host = grid.memory() == Memory::device ? grid.copy_to(Memory::host) : VoxelGrid();
  const VoxelGridView view = (grid.memory() == Memory::device ? host : grid).view();

  openvdb::FloatGrid::Ptr out = openvdb::FloatGrid::create(0.0f);
  out->setName("density");
  out->setGridClass(openvdb::GRID_FOG_VOLUME);
  const dvec3 size = spec.voxel_size();
  const dvec3 first_centre = spec.bounds.lo + 0.5 * size;
  openvdb::math::Mat4d matrix = openvdb::math::Mat4d::identity();
  for (int a = 0; a < 3; ++a) {
    matrix[a][a] = size[a];
    matrix[3][a] = first_centre[a];  // OpenVDB matrices act on row vectors: translation in row 3
  }
  out->setTransform(openvdb::math::Transform::createLinearTransform(matrix));
  openvdb::FloatGrid::Accessor voxels = out->getAccessor();
  for (int z = 0; z < spec.res.z; ++z)
    for (int y = 0; y < spec.res.y; ++y)
      for (int x = 0; x < spec.res.x; ++x)
        if (view.get(x, y, z)) voxels.setValueOn(openvdb::Coord(x, y, z), 1.0f);
  try {
    openvdb::io::File file(path);
    file.write({out});
    file.close();
  } catch (const openvdb::Exception& e) {
    throw InputError(path, std::string("writing the .vdb file failed: ") + e.what());
  }
}

}  // namespace dv
