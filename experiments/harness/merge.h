// Joins the folders of one sharded suite run (`deepvox suite --shard I/N` each) into one result
// folder with one report: rows in item order, as an unsharded run writes them. Refuses shards of
// different commits, suite files, shard counts or shard assignments (shard_plan.h), duplicate
// shards, and lists missing shards. The merged meta.json names every shard's host and GPU and
// sums them up ("2 GPUs on 1 host") for the report.
#pragma once

#include <string>
#include <vector>

namespace dv {

// Returns the new folder, made under OUT/<suite>/ (OUT empty: beside the first shard's folder).
// InputError naming the folder and the problem otherwise. A shard that was killed and resumed
// merges like any other; one still being written is refused (its flock or writer.lock held by
// a live process; writer.lock of a process on another host, which cannot be checked, unless
// `allow_missing`: then its complete rows merge). `allow_missing`: missing shards,
// folders without meta.json and unfinished shards (killed, not resumed: their complete rows are
// merged, their missing items listed as "missing_items") go into meta.json and the report
// instead of being refused, so a failed SLURM task still leaves a report that names it.
std::string merge_shards(const std::vector<std::string>& folders, const std::string& out,
                         bool allow_missing = false);

}  // namespace dv
