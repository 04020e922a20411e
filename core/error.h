// Errors the user can act on: every input problem becomes a dv::InputError whose message names
// the file (or scene key) and the problem; the CLI prints it and exits non-zero.
#pragma once

#include <stdexcept>
#include <string>

namespace dv {

class Error : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// Bad input: a file or parameter the user supplied is wrong.
class InputError : public Error {
 public:
  InputError(const std::string& where, const std::string& problem)
      : Error(where.empty() ? problem : where + ": " + problem) {}
};

}  // namespace dv
