// The order in which one run of the replicate protocol (`deepvox suite NAME --protocol
// replicate`, docs/suite-format.md) measures its items. A fixed order ties every item to a place
// in the run (warm-up, clocks, what ran just before), and identical configurations then differ by
// more than their repetitions say; so each run permutes its items with its own recorded seed,
// and the two sides of every comparison claim (findings.h) are measured in adjacent pairs whose
// order alternates A B, B A, A B, ... (ABBA), the first pair's orientation set by the seed's
// lowest bit, so that consecutive seeds start with opposite orientations.
#pragma once

#include <cstdint>
#include <vector>

#include "experiments/harness/run_item.h"
#include "experiments/harness/suite_file.h"

namespace dv {

// `items` permuted with `seed` (Fisher-Yates on mt19937_64, indices as rng() % n, so every
// platform gives the same order), then the items of each comparison claim of their experiment
// paired, the first side's with the second's in permuted order (an item joins one pair at
// most), each pair placed together where its first item fell, in alternating orientation.
std::vector<RunItem> protocol_order(const std::vector<RunItem>& items, const Suite& suite,
                                    uint64_t seed);

}  // namespace dv
