// Backend names (see backend.h).
#include "core/backend.h"

#include "core/error.h"

namespace dv {

const char* to_string(Backend backend) {
  return backend == Backend::cuda ? "cuda" : "cpu";
}

Backend parse_backend(const std::string& name) {
  if (name == "cpu") return Backend::cpu;
  if (name == "cuda") return Backend::cuda;
  throw InputError("--backend", "unknown backend '" + name + "' (known: cpu, cuda)");
}

}  // namespace dv
