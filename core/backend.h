// The two backends every pass can run on: CPU threads or CUDA, and their names. Which of them
// can run here is the executor's business (cuda/execute.h: default_backend, require_backend).
#pragma once

#include <cstdint>
#include <string>

namespace dv {

enum class Backend : uint8_t { cpu, cuda };

const char* to_string(Backend backend);
Backend parse_backend(const std::string& name);  // "cpu" | "cuda"; throws InputError

}  // namespace dv
