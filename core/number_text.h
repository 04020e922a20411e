// Numbers as text: the one formatter of reports, tables, progress lines and command lines, so a
// number reads alike wherever deepvox prints it, and text that is read back (CSV cells, command
// lines) holds the very value that was written.
#pragma once

#include <string>

namespace dv {

// printf's %.Ng: `digits` significant digits, trailing zeros dropped ("0.0123", "1.2e+06").
std::string significant_text(double value, int digits);
// printf's %.Nf: `decimals` digits after the point ("0.0123", "12.300").
std::string fixed_text(double value, int decimals);
// As significant_text with a '+' before zero and positive values: a change or a difference.
std::string signed_text(double value, int digits);
// Whole numbers below 1e15 in full ("1048576", counts and bytes), others as significant_text.
std::string table_text(double value, int digits);
// The shortest decimal that reads back as the same double: %.Ng with the least N from 6 up
// ("0.1", "1234567", "0.30000000000000004").
std::string exact_text(double value);
// The shortest decimal that reads back as the same float ("0.01" for 0.01f, not 0.0099999998).
std::string exact_text(float value);

}  // namespace dv
