// Test streams made by the suite itself: a synthetic Y4M clip, encoded with the encoders
// tools/install-deps installs (x264, x265, aomenc), with metadata inserted by the
// project's own writers.
#pragma once
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "filmgrain/fgc_params.hpp"

namespace filmgrain::test_support {

std::filesystem::path fresh_test_dir(const std::string& name);  // removed and recreated
std::vector<uint8_t> read_bytes(const std::filesystem::path& p);
void write_bytes(const std::filesystem::path& p, const std::vector<uint8_t>& bytes);

// Frames differ in content and motion so encoders use P/B pictures.
void write_synthetic_y4m(const std::filesystem::path& p, int width, int height, int frames, int bit_depth);

// The filmgrain tool under test and a path, each single-quoted for a shell command line.
std::string tool();
std::string q(const std::filesystem::path& p);

// Runs a shell command; fails the calling test (ADD_FAILURE) with its output when it fails.
bool run_or_fail(const std::string& cmd);

// A valid FGC SEI (frequency filtering, additive) whose values depend on k, so that
// each access unit's payload is recognisable.
FgcParams fgc_params_for(int k);

}  // namespace filmgrain::test_support
