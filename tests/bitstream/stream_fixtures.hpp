// Test streams made by the suite itself: a synthetic Y4M clip, encoded with the encoders
// tools/install-deps installs (x264, x265, aomenc), with metadata inserted by the
// project's own writers.
#pragma once
#include <cstdint>
#include <filesystem>
#include <functional>
#include <string>
#include <vector>

#include "bitstream/stream_scan.hpp"
#include "filmgrain/av1_params.hpp"
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

// A valid AV1 film grain set (auto-regressive, chroma points) whose values depend on k.
Av1FilmGrainParams av1_params_for(int k);

// A synthetic clip (write_synthetic_y4m, `dir`/src.y4m) encoded with B-frames, so that decode
// order differs from output order: x265 (--bframes 3, an IDR every 8 pictures, closed GOPs;
// 10-bit as main10) or x264 (--bframes 2, an IDR every 6: idr_pic_id 0, 1, ...; 8-bit only).
// Returns the Annex B stream; fails the calling test when the encoder does.
std::vector<uint8_t> encode_synthetic_clip(const std::filesystem::path& dir, bitstream::StreamCodec codec, int width,
                                           int height, int frames, int bit_depth);
// The stream with one FGC SEI before access unit k's first VCL NAL unit: fgc_params_for(k)
// in the codec's syntax, or payload_for(k) when given.
std::vector<uint8_t> with_fgc_sei_per_access_unit(const std::vector<uint8_t>& stream, bitstream::StreamCodec codec,
                                                  const std::function<std::vector<uint8_t>(int)>& payload_for = {});

}  // namespace filmgrain::test_support
