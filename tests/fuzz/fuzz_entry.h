// The fuzzed entry points: each takes arbitrary bytes, hands them to one loader as a
// file, and returns normally when the loader accepts them or rejects them with dv::InputError
// (a clear bad-input error, exit code 2 in the CLI); any other exception, a crash or a
// sanitizer report is a finding. libFuzzer runs them through fuzz_target.cpp (preset `fuzz`,
// scripts/fuzz.sh); test_fuzz_replay runs every committed corpus input through them in the
// normal build, so each crasher kept under corpus/ stays a regression test.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>

namespace dv::fuzz {

int scene_json(const uint8_t* data, size_t size);  // load_scene on a .json file
int gltf(const uint8_t* data, size_t size);   // load_gltf_scene on .glb ("glTF" magic) or .gltf
int mesh(const uint8_t* data, size_t size);   // load_mesh_file; first byte picks obj/off/ply/stl
int suite(const uint8_t* data, size_t size);  // parse_suite on the text

// Writes the bytes to a file of this process in the temporary folder, named `stem` + `ext`,
// and returns its path (a fresh file per call; parallel fuzz jobs are separate processes).
std::string scratch_input(const uint8_t* data, size_t size, const std::string& ext);

}  // namespace dv::fuzz
