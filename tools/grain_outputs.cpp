#include "grain_outputs.hpp"

#include <cstdio>
#include <filesystem>
#include <fstream>

#include "filmgrain/error.hpp"
#include "io/output_file.hpp"
#include "metadata/aom_grain_table.hpp"
#include "metadata/av1_params_json.hpp"
#include "metadata/fgc_json.hpp"

namespace filmgrain::cli {

void write_file_atomically(const std::string& path, const std::string& bytes) {
    OutputFile out(path);
    if (std::fwrite(bytes.data(), 1, bytes.size(), out.stream()) != bytes.size())
        throw Error(ErrorCode::kIo, "cannot write '" + path + "'");
    out.commit();
}

std::string fgc_params_json_text(const FgcParams& p) { return fgc_params_to_json(p).dump(1) + "\n"; }

std::vector<Av1FilmGrainParams> av1_per_frame(const Av1FilmGrainParams& p, int frames) {
    std::vector<Av1FilmGrainParams> out;
    for (int k = 0; k < frames; k++) {
        Av1FilmGrainParams q = p;
        if (q.apply_grain) q.grain_seed = (p.grain_seed + 7919 * k) & 0xFFFF;
        out.push_back(q);
    }
    return out;
}

std::string av1_params_json_text(const std::vector<Av1FilmGrainParams>& frames, const Av1ColorInfo& color) {
    std::vector<Av1FrameParams> f;
    for (const auto& p : frames) f.push_back({p, color});
    return av1_frame_params_to_json(f).dump(1) + "\n";
}

std::string av1_grain_table_text(const std::vector<Av1FilmGrainParams>& frames, int fps_num, int fps_den) {
    AomGrainTable t;
    for (std::size_t k = 0; k < frames.size(); k++) {
        AomGrainTableEntry e;
        e.start_time = int64_t(k) * 10000000 * fps_den / fps_num;
        e.end_time = int64_t(k + 1) * 10000000 * fps_den / fps_num;
        e.params = frames[k];
        e.params.update_grain = (k == 0 || !frames[k].apply_grain) ? 1 : 0;
        t.entries.push_back(e);
    }
    return format_aom_grain_table(t);
}

}  // namespace filmgrain::cli
