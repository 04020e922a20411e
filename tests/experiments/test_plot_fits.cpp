// The report's table of a line plot's fits (experiments/harness/plot_fits.h): the power fit and
// the fixed-plus-marginal fit that plot_suite.py records per line in plots/plots.json are
// printed side by side with their residuals, and malformed or missing fits print nothing.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "experiments/harness/plot_fits.h"

namespace dv {
namespace {

using Json = nlohmann::json;

// The exact oracle's frame, 86 ms + 61 ms per Mpx, as suite_fits.py fits it over the scale
// suite's six pixel counts (tests/scripts/test_suite_fits.py checks those numbers).
Json oracle_fit() {
  return {{"y", "frame_ms"},
          {"line", "reference"},
          {"unit", "ms"},
          {"x", "Mpx"},
          {"points", 6},
          {"power", {{"c", 180.9}, {"k", 0.454}, {"residual", 0.168}}},
          {"affine", {{"a", 86.0}, {"b", 61.0}, {"residual", 0.0}}}};
}

TEST(PlotFits, TablePrintsBothFitsOfEveryLine) {
  Json bytes = oracle_fit();
  bytes["y"] = "bytes";
  bytes["unit"] = "1";
  bytes["line"] = "dsm eps=0.02 res=1024";
  bytes["affine"] = {{"a", 1048576.0}, {"b", 0.5}, {"residual", 0.0123}};
  const std::string md = fits_table(Json::array({oracle_fit(), bytes}));
  EXPECT_NE(md.find("Fits against Mpx (x): the power fit y = c x^k and the fixed-plus-marginal "
                    "fit y = a + b x"),
            std::string::npos)
      << md;
  EXPECT_NE(md.find("| frame_ms | reference | 6 | 0.454 | 16.8 % | 86 ms | 61 ms | 0 % |"),
            std::string::npos)
      << md;
  // A unit of 1 (a count) prints no unit.
  EXPECT_NE(md.find("| bytes | dsm eps=0.02 res=1024 | 6 | 0.454 | 16.8 % | 1.049e+06 | 0.5 | "
                    "1.23 % |"),
            std::string::npos)
      << md;
  EXPECT_NE(md.find("Residual: root mean square of (y - fit) / y"), std::string::npos);
}

TEST(PlotFits, NoTableWithoutWellFormedFits) {
  EXPECT_EQ(fits_table(Json()), "");
  EXPECT_EQ(fits_table(Json::array()), "");
  Json broken = oracle_fit();
  broken["affine"].erase("b");
  EXPECT_EQ(fits_table(Json::array({broken})), "");
  Json text = oracle_fit();
  text["power"]["k"] = "0.45";
  const std::string md = fits_table(Json::array({text, oracle_fit()}));
  EXPECT_EQ(md.find("0.45 |"), std::string::npos) << md;  // the malformed entry is left out
  EXPECT_NE(md.find("| frame_ms | reference | 6 | 0.454 |"), std::string::npos) << md;
}

}  // namespace
}  // namespace dv
