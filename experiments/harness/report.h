// The Markdown report of a result folder, rebuilt from its files alone (meta.json, suite.json,
// rows.csv, samples/, runs.json, images/): per experiment a table of the chosen columns (the suite
// file's or the driver's), the paper's values beside it where the suite gives them, the image
// strip, and the plots that experiments/harness/plot_suite.py draws with matplotlib when python3
// and python3-matplotlib are there (the report says when plots were skipped and why). Needs no
// OpenImageIO: `deepvox report` runs in the lean binary too.
#pragma once

#include <string>

namespace dv {

// Writes DIR/report.md (and DIR/plots/*.png when possible); InputError when DIR is no result
// folder. The findings' intervals pool DIR with the independent runs DIR/runs.json names.
void build_report(const std::string& dir);

}  // namespace dv
