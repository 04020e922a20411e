// Host side of the deep-shadow-map storage family (texture3d, chunked, blocked, compact; beer and
// avsm, the fixed-size approximations engines ship; moments, fourier and occupancy, which fold
// each texel's nodes into a fixed record: basis coefficients, slice bits and slab sums). A
// storage strategy is a sink the generation walk writes nodes into as it goes (per texel: begin,
// push node, end), with an optional counting pass before; its generation time includes these
// writes, which is where the strategies differ. It then answers lookups through a DsmReader
// (strategies/storage/dsm_reader.h). Figures common to all (nodes, layers, overflow) come from
// the per-texel records (strategies/storage/dsm_records.h); each strategy adds its own.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "core/registry.h"
#include "cuda/buffer.h"
#include "cuda/execute.h"
#include "cuda/pass_timer.h"
#include "engine/dsm/dsm_generator.h"
#include "strategies/storage/dsm_reader.h"
#include "strategies/storage/dsm_records.h"

namespace dv {

struct DsmPass {
  std::string name;
  double milliseconds = 0.0;
};

// What the replay scratch and records of one set of faces may take, for a storage that
// generates its faces in sets (compact): a small part of the maps' own bytes at 512^2 and up,
// and still enough texels at once to fill the device (12 faces of 512^2, 3 of 1024^2).
inline constexpr int64_t kFaceSetBytes = int64_t(256) << 20;

// What a storage's generate() works with. The storage's passes write each texel's record
// (DsmGenerator::generate's results) into texel_records(). A storage that generates in sets of
// faces runs its passes over contexts of its own whose generator has a set's faces, its first
// texel at first_texel.
struct DsmGenerationContext {
  Backend backend;
  const DsmGenerator& generator;
  float eps;
  DsmRecords& records;
  std::vector<DsmPass>* passes;
  int64_t face_set_bytes = kFaceSetBytes;
  int64_t first_texel = 0;  // the index of the generator's first texel

  // The records of the generator's texels (DsmRecords::range).
  DsmRecordRange texel_records() const {
    return records.range(first_texel, generator.texel_count());
  }
};

// Runs f() and adds its time (CUDA events on the GPU) to pass `name`: the generation's pass of
// that name (a storage that generates in sets of faces runs its passes once a set), or a new one.
template <class F>
void timed_pass(const DsmGenerationContext& c, const char* name, F&& f) {
  PassTimer timer(c.backend);
  f();
  const double milliseconds = timer.stop();
  for (DsmPass& p : *c.passes)
    if (p.name == name) {
      p.milliseconds += milliseconds;
      return;
    }
  c.passes->push_back({name, milliseconds});
}

// Every texel's nodes in host memory, packed: texel t's are nodes[offsets[t] .. offsets[t + 1]).
struct DsmHostNodes {
  std::vector<int64_t> offsets;
  std::vector<DsmNode> nodes;
};

class DsmStorage {
 public:
  virtual ~DsmStorage() = default;
  virtual std::string name() const = 0;
  virtual nlohmann::json params() const = 0;
  // Builds the maps of every texel of c.generator, replacing what was there.
  virtual void generate(const DsmGenerationContext& c) = 0;
  virtual DsmReader reader() const = 0;
  // Bytes of every buffer the strategy holds now (its structures, pools and lookup tables).
  virtual int64_t bytes_allocated() const = 0;
  // Whether every texel's stored function stays within eps of the exact one (|V' - V| <= eps;
  // overflows are flagged): true for the papers' storages, false for fixed-size
  // approximations whose error is measured, not bounded.
  virtual bool keeps_error_bound() const = 0;
  // Bytes one stored node takes in the strategy's format.
  virtual int64_t bytes_per_node() const = 0;
  // The stored functions copied to the host (export, tests). Strategies that do not offer it
  // throw; `compact` does.
  virtual DsmHostNodes host_nodes() const;
  // The strategy's own figures (waste, chunks, blocks, recompressions, ...).
  virtual nlohmann::json own_figures() const { return nlohmann::json::object(); }
};

Registry<DsmStorage>& storage_registry();

// Figures shared by all strategies, from the sums over the per-texel records (DsmRecords: no
// copy of the records): bytes allocated, bytes holding nodes, nodes, mean and max layers per
// texel, overflowed texels (with those a fixed-node storage approximated) and the largest error
// they reached, recompressed texels, walk overflows.
nlohmann::json dsm_figures(const DsmStorage& storage, const DsmRecordSums& sums);

}  // namespace dv
