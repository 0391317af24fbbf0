// Writes the C header the AFGS1 tests of the C API include: payloads made by the project's
// AFGS1 writer (write_afgs1) and the same parameter sets as C code filling fg_av1_params.
// The C tests cannot call the writer themselves (libfilmgrain.so exports the C API only),
// so the build runs this program and the tests compare what the payload gives through
// fg_context_push_afgs1_t35 with what the sets give through fg_context_push_av1_params.
//
//   afgs1_fixture_gen OUTPUT.h
#include <cstdio>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "filmgrain/error.hpp"
#include "metadata/afgs1.hpp"

using namespace filmgrain;

namespace {

// Set 0: luma and both chroma components with their own points, lag 3, overlap.
Av1FilmGrainParams set0_params() {
    Av1FilmGrainParams p;
    p.apply_grain = 1;
    p.grain_seed = 4242;
    p.num_y_points = 4;
    const int yv[4] = {0, 64, 160, 255}, ys[4] = {50, 90, 70, 30};
    for (int i = 0; i < 4; i++) {
        p.point_y_value[i] = yv[i];
        p.point_y_scaling[i] = ys[i];
    }
    p.num_cb_points = 2;
    p.point_cb_value[0] = 16;
    p.point_cb_scaling[0] = 40;
    p.point_cb_value[1] = 240;
    p.point_cb_scaling[1] = 64;
    p.num_cr_points = 3;
    const int cv[3] = {0, 128, 255}, cs[3] = {30, 55, 20};
    for (int i = 0; i < 3; i++) {
        p.point_cr_value[i] = cv[i];
        p.point_cr_scaling[i] = cs[i];
    }
    p.grain_scaling_minus_8 = 2;
    p.ar_coeff_lag = 3;
    for (int i = 0; i < 24; i++) p.ar_coeffs_y_plus_128[i] = 128 + ((i * 7) % 13) - 6;
    for (int i = 0; i < 25; i++) {
        p.ar_coeffs_cb_plus_128[i] = 128 + ((i * 5) % 9) - 4;
        p.ar_coeffs_cr_plus_128[i] = 128 - ((i * 3) % 7) + 3;
    }
    p.ar_coeff_shift_minus_6 = 1;
    p.grain_scale_shift = 0;
    p.cb_mult = 140;
    p.cb_luma_mult = 180;
    p.cb_offset = 260;
    p.cr_mult = 120;
    p.cr_luma_mult = 200;
    p.cr_offset = 250;
    p.overlap_flag = 1;
    return p;
}

// Set 1: chroma scaled from luma, lag 1, restricted range, no overlap.
Av1FilmGrainParams set1_params() {
    Av1FilmGrainParams p;
    p.apply_grain = 1;
    p.grain_seed = 977;
    p.num_y_points = 2;
    p.point_y_value[0] = 0;
    p.point_y_scaling[0] = 100;
    p.point_y_value[1] = 255;
    p.point_y_scaling[1] = 60;
    p.chroma_scaling_from_luma = 1;
    p.grain_scaling_minus_8 = 1;
    p.ar_coeff_lag = 1;
    const int y[4] = {140, 110, 135, 150};
    for (int i = 0; i < 4; i++) p.ar_coeffs_y_plus_128[i] = y[i];
    const int c[5] = {120, 130, 125, 128, 140};
    for (int i = 0; i < 5; i++) {
        p.ar_coeffs_cb_plus_128[i] = c[i];
        p.ar_coeffs_cr_plus_128[i] = 256 - c[i];
    }
    p.ar_coeff_shift_minus_6 = 0;
    p.grain_scale_shift = 1;
    p.clip_to_restricted_range = 1;
    return p;
}

// A 4:2:0 10-bit picture of the given size, as AFGS1 targets it.
Afgs1SetTarget target(int width, int height) {
    Afgs1SetTarget t;
    t.apply_units_resolution_log2 = 0;
    t.apply_horz_resolution = width;
    t.apply_vert_resolution = height;
    t.subsampling_x = 1;
    t.subsampling_y = 1;
    t.video_signal_characteristics_flag = 1;
    t.bit_depth_minus8 = 2;
    return t;
}

std::string c_array(const char* name, const std::vector<uint8_t>& bytes) {
    std::ostringstream s;
    s << "static const uint8_t " << name << "[" << bytes.size() << "] = {";
    for (std::size_t i = 0; i < bytes.size(); i++) s << (i % 16 ? " " : "\n    ") << int(bytes[i]) << ",";
    s << "\n};\n";
    return s.str();
}

template <std::size_t N>
void c_points(std::ostringstream& s, const char* field, const std::array<int, N>& v, int count) {
    for (int i = 0; i < count; i++) s << "    p->" << field << "[" << i << "] = " << v[std::size_t(i)] << ";\n";
}

// C statements setting every field of an fg_av1_params (after fg_av1_params_init) to `p`.
std::string c_params(const char* name, const Av1FilmGrainParams& p) {
    std::ostringstream s;
    s << "static void " << name << "(fg_av1_params* p) {\n    fg_av1_params_init(p);\n";
#define FIELD(f) s << "    p->" #f " = " << p.f << ";\n"
    FIELD(apply_grain);
    FIELD(grain_seed);
    FIELD(update_grain);
    FIELD(num_y_points);
    FIELD(chroma_scaling_from_luma);
    FIELD(num_cb_points);
    FIELD(num_cr_points);
    FIELD(grain_scaling_minus_8);
    FIELD(ar_coeff_lag);
    FIELD(ar_coeff_shift_minus_6);
    FIELD(grain_scale_shift);
    FIELD(cb_mult);
    FIELD(cb_luma_mult);
    FIELD(cb_offset);
    FIELD(cr_mult);
    FIELD(cr_luma_mult);
    FIELD(cr_offset);
    FIELD(overlap_flag);
    FIELD(clip_to_restricted_range);
#undef FIELD
    c_points(s, "point_y_value", p.point_y_value, p.num_y_points);
    c_points(s, "point_y_scaling", p.point_y_scaling, p.num_y_points);
    c_points(s, "point_cb_value", p.point_cb_value, p.num_cb_points);
    c_points(s, "point_cb_scaling", p.point_cb_scaling, p.num_cb_points);
    c_points(s, "point_cr_value", p.point_cr_value, p.num_cr_points);
    c_points(s, "point_cr_scaling", p.point_cr_scaling, p.num_cr_points);
    c_points(s, "ar_coeffs_y_plus_128", p.ar_coeffs_y_plus_128, 24);
    c_points(s, "ar_coeffs_cb_plus_128", p.ar_coeffs_cb_plus_128, 25);
    c_points(s, "ar_coeffs_cr_plus_128", p.ar_coeffs_cr_plus_128, 25);
    s << "}\n";
    return s.str();
}

}  // namespace

int main(int argc, char** argv) {
    if (argc != 2) {
        std::fprintf(stderr, "usage: afgs1_fixture_gen OUTPUT.h\n");
        return 2;
    }
    try {
        const Av1FilmGrainParams p0 = set0_params(), p1 = set1_params();

        // Two sets with the T.35 header: set 0 for 352x288, set 1 for 176x144 (4:2:0, 10 bit).
        Afgs1Payload two;
        Afgs1ParamSet s0, s1;
        s0.film_grain_param_set_idx = 0;
        s0.target = target(352, 288);
        s0.params = p0;
        s1.film_grain_param_set_idx = 1;
        s1.target = target(176, 144);
        s1.params = p1;
        two.sets = {s0, s1};
        const std::vector<uint8_t> two_sets = write_afgs1(two);

        // Without the T.35 header: set 0 again with update_grain_flag = 0 and a new seed,
        // which the receiver resolves from its stored set 0.
        constexpr int kNewSeed = 31337;
        Afgs1Payload reseed;
        Afgs1ParamSet r = s0;
        r.params.update_grain = 0;
        r.params.grain_seed = kNewSeed;
        reseed.sets = {r};
        Afgs1WriteOptions bare;
        bare.t35_header = false;
        const std::vector<uint8_t> reseed_bare = write_afgs1(reseed, bare);

        // The writer's payloads must read back as written: the fixture is only as good as that.
        Afgs1Reader check;
        if (!(check.receive(two_sets).sets.at(1).params == p1) ||
            check.receive(reseed_bare, false).sets.at(0).params.grain_seed != kNewSeed)
            throw Error(ErrorCode::kInternal, "the AFGS1 writer's payloads do not read back");

        std::ostringstream h;
        h << "/* Generated by tests/capi/afgs1_fixture_gen.cpp with the project's AFGS1 writer: do not edit. */\n"
          << "#ifndef FILMGRAIN_AFGS1_FIXTURE_H\n#define FILMGRAIN_AFGS1_FIXTURE_H\n\n"
          << "#include <filmgrain/filmgrain.h>\n#include <stdint.h>\n\n"
          << "/* T.35 header + av1_film_grain_param_sets(): set 0 for 352x288, set 1 for 176x144,\n"
          << " * both 4:2:0 10-bit. */\n"
          << c_array("kAfgs1TwoSets", two_sets)
          << "/* No T.35 header: set 0 with update_grain_flag = 0 and grain_seed kAfgs1NewSeed. */\n"
          << c_array("kAfgs1ReseedBare", reseed_bare) << "#define kAfgs1NewSeed " << kNewSeed << "\n\n"
          << "/* The sets as fg_av1_params (raw values with their biases). */\n"
          << c_params("afgs1_fixture_set0", p0) << c_params("afgs1_fixture_set1", p1) << "\n#endif\n";
        const std::string tmp = std::string(argv[1]) + ".tmp";
        {
            std::ofstream out(tmp);
            out << h.str();
            if (!out.flush()) throw Error(ErrorCode::kIo, "cannot write '" + tmp + "'");
        }
        if (std::rename(tmp.c_str(), argv[1]) != 0) throw Error(ErrorCode::kIo, std::string("cannot write ") + argv[1]);
    } catch (const std::exception& e) {
        std::fprintf(stderr, "afgs1_fixture_gen: %s\n", e.what());
        return 1;
    }
    return 0;
}
