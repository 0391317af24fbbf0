// The parameter outputs of `analyze` and `preset`: JSON usable as `apply --params`, libaom
// grain tables, raw FGC SEI payloads. Each file appears only complete (temporary + rename).
#pragma once
#include <string>
#include <vector>

#include "filmgrain/av1_params.hpp"
#include "filmgrain/fgc_params.hpp"

namespace filmgrain::cli {

// `bytes` into `path` (through OutputFile: the file appears only complete; "-" is stdout, and
// a device or pipe is written directly).
void write_file_atomically(const std::string& path, const std::string& bytes);

// FGC: the single-object form (one SEI received with every picture).
std::string fgc_params_json_text(const FgcParams& p);

// AV1: {"frames": [...]}, one entry per picture with the seed advanced per picture (as
// encoders do, so the grain moves), plus the picture's colour facts.
std::vector<Av1FilmGrainParams> av1_per_frame(const Av1FilmGrainParams& p, int frames);
std::string av1_params_json_text(const std::vector<Av1FilmGrainParams>& frames, const Av1ColorInfo& color);
// libaom table: one entry per picture (10 MHz ticks at fps_num/fps_den), parameters in the
// first, update_parameters = 0 with a new seed in the others.
std::string av1_grain_table_text(const std::vector<Av1FilmGrainParams>& frames, int fps_num, int fps_den);

}  // namespace filmgrain::cli
