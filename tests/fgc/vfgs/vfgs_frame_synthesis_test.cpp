// The threaded, vectorized VFGS frame synthesis (vfgs_frame_synthesis.hpp) against the
// serial scalar reference add_grain_frame(): random parameter sets, formats, sizes, bit
// depths, seeds and gains, two frames in a row (the LFSR runs on across frames), every
// kernel choice and thread counts 1, 2, 3 and 7; and the VersatileFilmGrain goldens on
// 1, 2, 3 and 7 threads. Both for every vector target this CPU runs (each forced in turn).
#include <gtest/gtest.h>

#include <cstring>
#include <random>
#include <string>

#include "conformance_case.hpp"
#include "core/frame_buffer.hpp"
#include "fgc/vfgs/vfgs_frame_setup.hpp"
#include "fgc/vfgs/vfgs_frame_synthesis.hpp"
#include "fgc/vfgs/vfgs_random.hpp"
#include "filmgrain/error.hpp"
#include "forced_simd_target.hpp"
#include "metadata/fgc_json.hpp"

using namespace filmgrain;
using namespace filmgrain::vfgs;

namespace {

struct RandomCase {
    FgcParams params;
    Options options;
    PixelFormat format;
    int width = 0, height = 0, out_bit_depth = 8;
    std::string describe;
};

RandomCase random_case(std::mt19937& rng) {
    auto uniform = [&](int lo, int hi) { return std::uniform_int_distribution<int>(lo, hi)(rng); };
    RandomCase rc;
    const ChromaFormat formats[] = {ChromaFormat::k420, ChromaFormat::k420, ChromaFormat::k422, ChromaFormat::k444};
    rc.format.chroma = formats[uniform(0, 3)];
    rc.format.bit_depth = uniform(0, 1) ? 8 : 10;
    rc.out_bit_depth = rc.format.bit_depth == 10 && uniform(0, 2) == 0 ? 8 : rc.format.bit_depth;
    rc.options.output_bit_depth = rc.out_bit_depth == rc.format.bit_depth ? 0 : rc.out_bit_depth;
    rc.width = uniform(129, 420) & ~1;
    if (rc.width <= 128) rc.width = 130;
    rc.height = uniform(128, 220) & ~1;
    const int gains[] = {100, 100, 100, 60, 150, 300, 40};
    rc.options.gain_percent = gains[uniform(0, 6)];
    if (uniform(0, 3)) rc.options.seed = static_cast<uint32_t>(uniform(0, 1 << 30));
    rc.options.pattern_interpolation = uniform(0, 7) == 0;
    FgcParams& p = rc.params;
    p.film_grain_model_id = uniform(0, 4) == 0 ? 1 : 0;
    p.log2_scale_factor = uniform(2, 7) + p.film_grain_model_id;
    for (int c = 0; c < 3; ++c) {
        if (c > 0 && (p.film_grain_model_id == 1 || rc.format.chroma != ChromaFormat::k420 || uniform(0, 3) == 0)) continue;
        if (c == 0 && uniform(0, 9) == 0) continue;
        FgcComponentModel& cm = p.comp[static_cast<size_t>(c)];
        cm.comp_model_present_flag = true;
        cm.num_model_values_minus1 = uniform(0, p.film_grain_model_id ? 5 : 2);
        int lower = uniform(0, 40);
        const int intervals = uniform(1, 6);
        for (int i = 0; i < intervals && lower <= 255; ++i) {
            const int upper = std::min(255, lower + uniform(0, 90));
            FgcIntensityInterval iv;
            iv.intensity_interval_lower_bound = lower;
            iv.intensity_interval_upper_bound = upper;
            iv.comp_model_value[0] = uniform(0, 5) == 0 ? 255 : uniform(0, 255);
            if (p.film_grain_model_id == 0) {
                iv.comp_model_value[1] = uniform(2, 14);
                iv.comp_model_value[2] = uniform(2, 14);
            } else {
                for (int k = 1; k < 6; ++k) iv.comp_model_value[static_cast<size_t>(k)] = uniform(-20, 60);
            }
            cm.intervals.push_back(iv);
            lower = upper + 1 + uniform(0, 1) * uniform(0, 30);
        }
    }
    rc.describe = std::to_string(rc.width) + "x" + std::to_string(rc.height) + " format " +
                  std::to_string(static_cast<int>(rc.format.chroma)) + " bd " + std::to_string(rc.format.bit_depth) +
                  "->" + std::to_string(rc.out_bit_depth) + " model " + std::to_string(p.film_grain_model_id) +
                  " gain " + std::to_string(rc.options.gain_percent) + " interpolation " +
                  std::to_string(rc.options.pattern_interpolation);
    return rc;
}

FrameBuffer random_picture(std::mt19937& rng, int w, int h, PixelFormat fmt) {
    FrameBuffer f(w, h, fmt);
    FrameView v = f.view();
    // smooth ramps with noise: every intensity interval is visited
    std::uniform_int_distribution<int> noise(-6, 6);
    const int top = (1 << fmt.bit_depth) - 1;
    for (int p = 0; p < v.plane_count(); ++p)
        for (int y = 0; y < v.planes[p].height; ++y)
            for (int x = 0; x < v.planes[p].width; ++x) {
                const int base = ((x * 3 + y * 2) * (top + 1) / 1024) % (top + 1);
                const int s = std::clamp(base + noise(rng) * (top + 1) / 256, 0, top);
                if (fmt.bit_depth > 8) v.planes[p].row<uint16_t>(y)[x] = static_cast<uint16_t>(s);
                else v.planes[p].row<uint8_t>(y)[x] = static_cast<uint8_t>(s);
            }
    return f;
}

bool same_bytes(const FrameBuffer& a, const FrameBuffer& b) {
    return a.byte_size() == b.byte_size() && std::memcmp(a.bytes(), b.bytes(), a.byte_size()) == 0;
}

class VfgsFrameSynthesis : public test_support::ForcedSimdTarget<2025u> {};

}  // namespace

TEST_P(VfgsFrameSynthesis, EqualsTheSerialReferenceForEveryThreadCountAndKernel) {
    FrameSynthesis engines[] = {FrameSynthesis(1, Kernels::kOptimized), FrameSynthesis(2, Kernels::kOptimized),
                                FrameSynthesis(3, Kernels::kOptimized), FrameSynthesis(7, Kernels::kOptimized),
                                FrameSynthesis(1, Kernels::kReference), FrameSynthesis(3, Kernels::kReference)};
    int tried = 0;
    for (int iter = 0; tried < 60 && iter < 1000; ++iter) {
        const RandomCase rc = random_case(rng);
        TemplateBank bank;
        SynthesisSetup setup;
        try {
            validate_params(rc.params, rc.options.gain_percent);
            setup = prepare_setup(rc.params, rc.format.chroma, rc.format.bit_depth, rc.options, bank);
        } catch (const Error&) {
            continue;  // a set VFGS refuses
        }
        ++tried;
        const PixelFormat out_fmt{rc.format.chroma, rc.out_bit_depth};
        const FrameBuffer in[2] = {random_picture(rng, rc.width, rc.height, rc.format),
                                   random_picture(rng, rc.width, rc.height, rc.format)};
        const uint32_t start = rc.options.seed ? lfsr_state_from_seed(*rc.options.seed) : kDefaultLfsrState;
        LfsrCursor ref_cursor{start, start};
        FrameBuffer want[2] = {FrameBuffer(rc.width, rc.height, out_fmt), FrameBuffer(rc.width, rc.height, out_fmt)};
        for (int k = 0; k < 2; ++k) {
            FrameBuffer src = in[k];
            add_grain_frame(src.view(), want[k].view(), setup, ref_cursor);
        }
        for (size_t e = 0; e < std::size(engines); ++e) {
            LfsrCursor cursor{start, start};
            for (int k = 0; k < 2; ++k) {
                FrameBuffer src = in[k];
                FrameBuffer got(rc.width, rc.height, out_fmt);
                if (rc.out_bit_depth == rc.format.bit_depth && (k + static_cast<int>(e)) % 2) {
                    engines[e].apply(src.view(), src.view(), setup, cursor);  // in place
                    got = src;
                } else {
                    engines[e].apply(src.view(), got.view(), setup, cursor);
                }
                ASSERT_TRUE(same_bytes(got, want[k])) << rc.describe << " engine " << e << " (threads "
                                                      << engines[e].threads() << ") frame " << k;
            }
            EXPECT_EQ(cursor.stripe, ref_cursor.stripe);
            EXPECT_EQ(cursor.upper, ref_cursor.upper);
        }
    }
    EXPECT_GE(tried, 60);
}

// The goldens of VersatileFilmGrain through the frame synthesis on several threads (the
// conformance suite runs them through vfgs::Synthesizer, one thread, best target).
TEST_P(VfgsFrameSynthesis, GoldensOnSeveralThreads) {
    int cases = 0;
    for (const std::string& name : test_support::list_cases("vfgs-")) {
        if (name.rfind("vfgs-afgs1-", 0) == 0) continue;
        const test_support::ConformanceCase c = test_support::load_case(name);
        Options opt;
        if (!c.json.at("seed").is_null()) opt.seed = c.json.at("seed").get<uint32_t>();
        opt.gain_percent = c.json.value("vfgs_gain_percent", 100);
        if (c.output_format.bit_depth != c.format.bit_depth) opt.output_bit_depth = c.output_format.bit_depth;
        const uint32_t start = opt.seed ? lfsr_state_from_seed(*opt.seed) : kDefaultLfsrState;
        for (int threads : {1, 2, 3, 7}) {
            FrameSynthesis engine(threads);
            LfsrCursor cursor{start, start};
            TemplateBank bank;
            SynthesisSetup setup;
            nlohmann::json last;
            for (int k = 0; k < c.frames; ++k) {
                const nlohmann::json& pj = c.frame_info(k).at("params").at("fgc");
                if (k == 0 || pj != last) {
                    setup = prepare_setup(fgc_params_from_json(pj), c.format.chroma, c.format.bit_depth, opt, bank);
                    last = pj;
                }
                FrameBuffer src = c.input_frame(k);
                FrameBuffer dst(c.width, c.height, c.output_format);
                engine.apply(src.view(), dst.view(), setup, cursor);
                EXPECT_EQ(test_support::describe_mismatch(c, k, dst.bytes(), dst.byte_size()), "")
                    << name << " threads " << threads << " frame " << k;
            }
        }
        ++cases;
    }
    EXPECT_GE(cases, 10);
}

INSTANTIATE_TEST_SUITE_P(Targets, VfgsFrameSynthesis, ::testing::ValuesIn(filmgrain::simd::available_targets()),
                         [](const ::testing::TestParamInfo<filmgrain::simd::Target>& i) { return i.param.name; });
