// The fits of a line plot with "fit": "power" as the report prints them under the plot: per
// line a row with the power fit y = c x^k and the fixed-plus-marginal fit y = a + b x over the
// same points, each with its relative residual, from the "fits" that plot_suite.py (through
// suite_fits.py) records in plots/plots.json. A power exponent alone misreads a cost with a
// fixed part (86 ms + 61 ms per Mpx fits k = 0.45), so both are printed side by side.
#pragma once

#include <string>

#include <nlohmann/json.hpp>

namespace dv {

// A Markdown table (with a blank line before it), or "" when `fits` is not a non-empty array;
// entries without the expected numbers are left out.
std::string fits_table(const nlohmann::json& fits);

}  // namespace dv
