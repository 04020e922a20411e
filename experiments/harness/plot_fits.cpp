// The report's table of a line plot's fits (plot_fits.h).
#include "experiments/harness/plot_fits.h"

#include <sstream>

#include "core/number_text.h"

namespace dv {

namespace {

bool has_numbers(const nlohmann::json& o, std::initializer_list<const char*> keys) {
  if (!o.is_object()) return false;
  for (const char* k : keys)
    if (!o.contains(k) || !o[k].is_number()) return false;
  return true;
}

std::string percent(double fraction) {
  return significant_text(100.0 * fraction, 3) + " %";
}

}  // namespace

std::string fits_table(const nlohmann::json& fits) {
  if (!fits.is_array() || fits.empty()) return "";
  std::ostringstream md;
  const std::string x = fits[0].is_object() ? fits[0].value("x", std::string("x")) : "x";
  md << "\nFits against " << x
     << " (x): the power fit y = c x^k and the fixed-plus-marginal fit y = a + b x, a the "
        "fixed cost and b the cost per unit of x.\n\n"
        "| column | line | points | k | residual | a (fixed) | b (per unit of x) | residual |\n"
        "| --- | --- | --- | --- | --- | --- | --- | --- |\n";
  int rows = 0;
  for (const nlohmann::json& f : fits) {
    if (!f.is_object() ||
        !has_numbers(f.value("power", nlohmann::json()), {"c", "k", "residual"}) ||
        !has_numbers(f.value("affine", nlohmann::json()), {"a", "b", "residual"}))
      continue;
    const nlohmann::json& p = f["power"];
    const nlohmann::json& a = f["affine"];
    const std::string unit = f.value("unit", "");
    const std::string y_unit = unit.empty() || unit == "1" ? "" : " " + unit;
    md << "| " << f.value("y", "") << " | " << f.value("line", "") << " | " << f.value("points", 0)
       << " | " << significant_text(p["k"].get<double>(), 3) << " | "
       << percent(p["residual"].get<double>()) << " | " << significant_text(a["a"].get<double>(), 4)
       << y_unit << " | " << significant_text(a["b"].get<double>(), 4) << y_unit << " | "
       << percent(a["residual"].get<double>()) << " |\n";
    ++rows;
  }
  if (rows == 0) return "";
  md << "\nResidual: root mean square of (y - fit) / y over the line's points; the smaller one "
        "says which model describes the line.\n";
  return md.str();
}

}  // namespace dv
