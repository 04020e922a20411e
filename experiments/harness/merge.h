// Joins the folders of one sharded suite run (`deepvox suite --shard I/N` each) into one result
// folder with one report: rows in item order, as an unsharded run writes them. Refuses shards of
// different commits, suite files or shard counts, duplicate shards, and lists missing shards.
#pragma once

#include <string>
#include <vector>

namespace dv {

// Returns the new folder, made under OUT/<suite>/ (OUT empty: beside the first shard's folder).
// InputError naming the folder and the problem otherwise.
std::string merge_shards(const std::vector<std::string>& folders, const std::string& out);

}  // namespace dv
