// Checkasm-style equivalence of the optimized AV1 row blends (av1/simd/av1_kernels.hpp,
// including the 512-bit VBMI form of the AVX3 target at 8 bits) with the scalar references
// blend_luma_row / blend_chroma_row (grain_blending.hpp), for every vector target this CPU
// runs (each forced in turn), the way the synthesis hands them their noise: every block's
// rows in one grain-template-like buffer, the row chosen by row_offset. Covers rows of full
// HD width and beyond (many 64-sample steps and every tail length), each form of the
// horizontal overlap (none, given seams, faded in the kernel), 8-bit noise as int16 and as
// bytes (BlockNoiseRow::byte_blocks), every clip, chroma with and without subsampling and
// scaling from luma, odd luma widths, and in place.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <optional>
#include <random>
#include <vector>

#include "av1/block_synthesis.hpp"
#include "av1/grain_blending.hpp"
#include "av1/scaling_lookup.hpp"
#include "av1/simd/av1_kernels.hpp"
#include "forced_simd_target.hpp"

using namespace filmgrain;

namespace {

class SimdAv1BlendRowsEquivalence : public test_support::ForcedSimdTarget<20261125u> {};

// A template-like buffer of `rows` rows and the blocks of a picture row at random offsets in
// it, as stripe_block_origins places them: block b of row i is blocks[b] + i * pitch.
struct TemplateNoise {
    int pitch = 0;
    std::vector<int16_t> samples;
    std::vector<const int16_t*> blocks;
    // the int8 copy (BlockNoiseRow::byte_blocks) at 8 bits, padded as the synthesis pads it
    std::vector<int8_t> bytes;
    std::vector<const int8_t*> byte_blocks;
    std::vector<uint32_t> seams;
    av1::simd::BlockNoiseRow row;
    std::vector<int16_t> flat;  // row.at(x), as the references take it

    TemplateNoise(int width, int block_width, int bd, int rows, int mode, std::mt19937& rng) {
        auto u = [&](int lo, int hi) { return std::uniform_int_distribution<int>(lo, hi)(rng); };
        const int gmax = (128 << (bd - 8)) - 1;
        pitch = block_width + 2 + 16 + u(0, 7);  // room for the block, its overlap and an offset
        samples.resize(std::size_t(pitch) * std::size_t(rows));
        for (auto& v : samples) v = int16_t(u(-gmax - 1, gmax));
        const int count = (width + block_width - 1) / block_width;
        for (int b = 0; b < count; b++) blocks.push_back(samples.data() + u(0, 16));
        row.blocks = blocks.data();
        if (bd == 8 && u(0, 1)) {  // half the 8-bit cases with it, given seams included (which ignore it)
            av1::simd::copy_noise_as_bytes(samples, bytes);
            for (const int16_t* p : blocks) byte_blocks.push_back(bytes.data() + (p - samples.data()));
            row.byte_blocks = byte_blocks.data();
        }
        row.block_width = block_width;
        row.row_offset = std::ptrdiff_t(u(0, rows - 1)) * pitch;
        row.gmin = int16_t(-gmax - 1), row.gmax = int16_t(gmax);
        const bool subsampled = block_width == 16;
        if (mode == 1) {
            for (int b = 0; b < count; b++)
                seams.push_back(uint32_t(uint16_t(u(-gmax - 1, gmax))) | uint32_t(uint16_t(u(-gmax - 1, gmax))) << 16);
            row.seams = seams.data();
        } else if (mode == 2) {
            row.fade = true;
            row.fade_old[0] = int16_t(subsampled ? 23 : 27), row.fade_old[1] = int16_t(subsampled ? 0 : 17);
            row.fade_new[0] = int16_t(subsampled ? 22 : 17), row.fade_new[1] = int16_t(subsampled ? 32 : 27);
        }
        for (int x = 0; x < width; x++) flat.push_back(row.at(x));
    }

    // `flat` of the row r rows below `row` (the rows of a stripe, for the one-row references)
    std::vector<int16_t> flat_below(int r) const {
        av1::simd::BlockNoiseRow below = row;
        below.row_offset += std::ptrdiff_t(r) * pitch;
        std::vector<int16_t> out;
        for (int x = 0; x < int(flat.size()); x++) out.push_back(below.at(x));
        return out;
    }
};

av1::ScalingLookup random_scaling(std::mt19937& rng, int bd) {
    auto u = [&](int lo, int hi) { return std::uniform_int_distribution<int>(lo, hi)(rng); };
    int values[14], scalings[14];
    const int count = u(1, 14);
    int n = 0;
    for (int v = u(0, 30); n < count && v < 256; v += u(1, 40), n++) values[n] = v, scalings[n] = u(0, 255);
    return av1::ScalingLookup(values, scalings, n, bd);
}

template <typename Pixel>
std::vector<Pixel> random_samples(std::mt19937& rng, int count, int bd, bool smooth) {
    auto u = [&](int lo, int hi) { return std::uniform_int_distribution<int>(lo, hi)(rng); };
    std::vector<Pixel> out(static_cast<std::size_t>(count), Pixel(0));
    int level = u(0, (1 << bd) - 1);
    for (auto& s : out) {
        level = smooth ? std::clamp(level + u(-(4 << (bd - 8)), 4 << (bd - 8)), 0, (1 << bd) - 1) : u(0, (1 << bd) - 1);
        s = Pixel(level);
    }
    return out;
}

void blend_luma(const uint8_t* s, uint8_t* d, const av1::simd::BlockNoiseRow& n, int w, const av1::ScalingLookup& sc,
                int shift, int, const av1::ClipLimits& c) {
    av1::simd::blend_luma_row_u8(s, d, n, w, sc, shift, c.min_value, c.max_luma);
}
// The u16 forms with a row to prefetch (`ahead`, here the source itself) on even widths and
// none on odd ones: a hint the output must not depend on.
const uint16_t* prefetch_row(const uint16_t* s, int w) { return w & 1 ? nullptr : s; }
void blend_luma(const uint16_t* s, uint16_t* d, const av1::simd::BlockNoiseRow& n, int w,
                const av1::ScalingLookup& sc, int shift, int bd, const av1::ClipLimits& c) {
    av1::simd::blend_luma_row_u16(s, d, n, w, sc, shift, bd, c.min_value, c.max_luma, nullptr, prefetch_row(s, w));
}
void blend_chroma(const uint8_t* s, uint8_t* d, const uint8_t* l, int lw, const av1::simd::BlockNoiseRow& n, int w,
                  int subx, const av1::ChromaScalingIndex& i, const av1::ScalingLookup& sc, int shift, int bd,
                  const av1::ClipLimits& c) {
    av1::simd::blend_chroma_row_u8(s, d, l, lw, n, w, subx, i, sc, shift, bd, c.min_value, c.max_chroma);
}
void blend_chroma(const uint16_t* s, uint16_t* d, const uint16_t* l, int lw, const av1::simd::BlockNoiseRow& n,
                  int w, int subx, const av1::ChromaScalingIndex& i, const av1::ScalingLookup& sc, int shift, int bd,
                  const av1::ClipLimits& c) {
    av1::simd::blend_chroma_row_u16(s, d, l, lw, n, w, subx, i, sc, shift, bd, c.min_value, c.max_chroma,
                                    prefetch_row(s, w));
}

template <typename Pixel>
void check_rows(std::mt19937& rng, int bd, int iterations) {
    auto u = [&](int lo, int hi) { return std::uniform_int_distribution<int>(lo, hi)(rng); };
    for (int iter = 0; iter < iterations; iter++) {
        // full HD and 4K widths, and any other (every tail after the whole 64-sample steps)
        const int pick = u(0, 3);
        const int width = pick == 0 ? 1920 : pick == 1 ? 3840 : u(1, 2200);
        const int subx = u(0, 1), mode = u(0, bd <= 10 ? 2 : 1);
        const int luma_width = subx ? 2 * width - u(0, 1) : width;
        const int chroma_width = subx ? (luma_width + 1) / 2 : width;
        const av1::ScalingLookup scaling = random_scaling(rng, bd);
        const int shift = u(8, 11);
        const av1::ClipLimits clip = av1::clip_limits(u(0, 1), bd, u(0, 2));
        const av1::ChromaScalingIndex index{u(0, 3) == 0, u(-128, 127), u(-128, 127), u(-256, 255)};
        const TemplateNoise luma_noise(luma_width, 32, bd, u(1, 40), mode, rng);
        // unsubsampled luma with 16-wide noise blocks: subsampled chroma above 8 bits, which the
        // synthesis hands its shared co-sited luma rows
        const int chroma_block = subx || u(0, 2) == 0 ? 16 : 32;
        const TemplateNoise chroma_noise(chroma_width, chroma_block, bd, u(1, 40), mode, rng);
        const bool smooth = u(0, 1);
        const std::vector<Pixel> luma = random_samples<Pixel>(rng, luma_width, bd, smooth);
        const std::vector<Pixel> chroma = random_samples<Pixel>(rng, chroma_width, bd, smooth);
        std::vector<Pixel> want(static_cast<std::size_t>(luma_width), Pixel(0)), got = want;

        av1::blend_luma_row<Pixel>(luma.data(), want.data(), luma_noise.flat.data(), luma_width, scaling, shift,
                                   clip.min_value, clip.max_luma);
        blend_luma(luma.data(), got.data(), luma_noise.row, luma_width, scaling, shift, bd, clip);
        ASSERT_EQ(got, want) << "luma, iteration " << iter << " bd " << bd << " width " << luma_width << " mode "
                             << mode;
        std::vector<Pixel> in_place = luma;
        blend_luma(in_place.data(), in_place.data(), luma_noise.row, luma_width, scaling, shift, bd, clip);
        ASSERT_EQ(in_place, want) << "luma in place, iteration " << iter;
        if constexpr (sizeof(Pixel) == 2) {
            // in place with the co-sited luma of the clean row as a by-product (the synthesis
            // shares it between the chroma planes), nothing written past its end
            const int co_sited_width = (luma_width + 1) / 2;
            std::vector<uint16_t> co_sited_want(static_cast<std::size_t>(co_sited_width));
            std::vector<uint16_t> co_sited_got(std::size_t(co_sited_width) + 40, uint16_t(0x7777));
            av1::co_sited_luma_row<uint16_t>(luma.data(), luma_width, co_sited_width, co_sited_want.data());
            in_place = luma;
            av1::simd::blend_luma_row_u16(in_place.data(), in_place.data(), luma_noise.row, luma_width, scaling, shift,
                                          bd, clip.min_value, clip.max_luma, co_sited_got.data());
            ASSERT_EQ(in_place, want) << "luma in place with co-sited luma, iteration " << iter;
            for (std::size_t x = 0; x < co_sited_got.size(); x++)
                ASSERT_EQ(co_sited_got[x], x < co_sited_want.size() ? co_sited_want[x] : uint16_t(0x7777))
                    << "co-sited luma at " << x << ", iteration " << iter << " luma width " << luma_width;
        }

        want.assign(std::size_t(chroma_width), 0);
        got.assign(want.size(), 0);
        av1::blend_chroma_row<Pixel>(chroma.data(), want.data(), luma.data(), luma_width, chroma_noise.flat.data(),
                                     chroma_width, subx, index, scaling, shift, bd, clip.min_value, clip.max_chroma);
        blend_chroma(chroma.data(), got.data(), luma.data(), luma_width, chroma_noise.row, chroma_width, subx, index,
                     scaling, shift, bd, clip);
        ASSERT_EQ(got, want) << "chroma, iteration " << iter << " bd " << bd << " width " << chroma_width
                             << " luma width " << luma_width << " subx " << subx << " mode " << mode
                             << " from luma " << index.from_luma;
        in_place = chroma;
        blend_chroma(in_place.data(), in_place.data(), luma.data(), luma_width, chroma_noise.row, chroma_width, subx,
                     index, scaling, shift, bd, clip);
        ASSERT_EQ(in_place, want) << "chroma in place, iteration " << iter;
    }
}

TEST_P(SimdAv1BlendRowsEquivalence, EightBitRows) { check_rows<uint8_t>(rng, 8, 400); }

TEST_P(SimdAv1BlendRowsEquivalence, HighBitDepthRows) {
    check_rows<uint16_t>(rng, 10, 100);
    check_rows<uint16_t>(rng, 12, 60);
}

// Samples beyond the declared bit depth (bad input nobody scans for): the references read
// the scaling function's last entry for them (ScalingLookup), and every vector form must too,
// whether a few such samples sit among valid ones near the top of the range or all are
// large, up to 65535 (rows holding a sample above the bit depth take the scalar form:
// AnyAboveBitDepth).
TEST_P(SimdAv1BlendRowsEquivalence, SamplesBeyondTheBitDepth) {
    for (int iter = 0; iter < 60; iter++) {
        const int bd = 10, width = uniform(0, 1) ? 1920 : uniform(1, 700);
        // a few rows of the scale table around its end (where the vector forms look up a
        // step's rows at once), a wider band, anything, or valid samples with a few of any
        // value among them (steps left to the scalar form beside vector ones)
        const int range = uniform(0, 3);
        const int bottom = range == 0 ? 1005 : range == 1 ? 900 : 0;
        const int top = range == 0 ? 1035 : range == 1 ? 1200 : range == 2 ? 65535 : 1023;
        // a scaling function that still changes within the table's last rows, so that a
        // wrong entry there shows
        const int values[4] = {uniform(0, 120), uniform(121, 251), 252, 255};
        const int scalings[4] = {uniform(0, 255), uniform(0, 255), uniform(0, 127), uniform(128, 255)};
        const av1::ScalingLookup scaling(values, scalings, 4, bd);
        const int shift = uniform(8, 11);
        const av1::ClipLimits clip = av1::clip_limits(0, bd, 0);
        const av1::ChromaScalingIndex index{uniform(0, 1) == 0, uniform(-128, 127), uniform(-128, 127),
                                            uniform(-256, 255)};
        const TemplateNoise luma_noise(width, 32, bd, 4, uniform(0, 2), rng);
        const TemplateNoise chroma_noise(width, uniform(0, 1) ? 16 : 32, bd, 4, uniform(0, 2), rng);
        std::vector<uint16_t> luma(static_cast<std::size_t>(width)), chroma(luma.size());
        auto sample = [&] {
            return uint16_t(range == 3 && uniform(0, 150) == 0 ? uniform(1024, 65535) : uniform(bottom, top));
        };
        for (auto& v : luma) v = sample();
        for (auto& v : chroma) v = sample();
        std::vector<uint16_t> want(luma.size()), got(luma.size());
        av1::blend_luma_row<uint16_t>(luma.data(), want.data(), luma_noise.flat.data(), width, scaling, shift,
                                      clip.min_value, clip.max_luma);
        av1::simd::blend_luma_row_u16(luma.data(), got.data(), luma_noise.row, width, scaling, shift, bd,
                                      clip.min_value, clip.max_luma);
        ASSERT_EQ(got, want) << "luma, iteration " << iter << " width " << width << " top " << top;
        // chroma with luma of its width, or subsampled with luma twice as wide
        const int subx = uniform(0, 1), luma_width = width << subx;
        for (int i = width; i < luma_width; i++) luma.push_back(sample());
        av1::blend_chroma_row<uint16_t>(chroma.data(), want.data(), luma.data(), luma_width,
                                        chroma_noise.flat.data(), width, subx, index, scaling, shift, bd,
                                        clip.min_value, clip.max_chroma);
        av1::simd::blend_chroma_row_u16(chroma.data(), got.data(), luma.data(), luma_width, chroma_noise.row, width,
                                        subx, index, scaling, shift, bd, clip.min_value, clip.max_chroma);
        ASSERT_EQ(got, want) << "chroma, iteration " << iter << " width " << width << " top " << top
                             << " from luma " << index.from_luma << " subx " << subx;
    }
}

// The several-row kernels (blend_luma_rows_u8 / blend_chroma_rows_u8, as the synthesis calls
// them for a stripe's rows): each row r at its stride, its noise r template rows further
// down, its co-sited luma a luma stride further, against the references row by row.
TEST_P(SimdAv1BlendRowsEquivalence, EightBitRowsOfAStripe) {
    for (int iter = 0; iter < 60; iter++) {
        const int width = uniform(0, 1) ? 1920 : uniform(1, 700), subx = uniform(0, 1), mode = uniform(0, 2);
        const int luma_width = subx ? 2 * width - uniform(0, 1) : width;
        const int chroma_width = subx ? (luma_width + 1) / 2 : width;
        const int rows = uniform(1, 32);
        const av1::ScalingLookup scaling = random_scaling(rng, 8);
        const int shift = uniform(8, 11);
        const av1::ClipLimits clip = av1::clip_limits(uniform(0, 1), 8, uniform(0, 2));
        const av1::ChromaScalingIndex index{uniform(0, 3) == 0, uniform(-128, 127), uniform(-128, 127), uniform(-256, 255)};
        // the first row anywhere in the first 40 template rows, the others below it
        TemplateNoise luma_noise(luma_width, 32, 8, rows + 40, mode, rng);
        TemplateNoise chroma_noise(chroma_width, 32 >> subx, 8, rows + 40, mode, rng);
        luma_noise.row.row_offset = std::ptrdiff_t(uniform(0, 40)) * luma_noise.pitch;
        chroma_noise.row.row_offset = std::ptrdiff_t(uniform(0, 40)) * chroma_noise.pitch;
        const int luma_stride = luma_width + uniform(0, 40), chroma_stride = chroma_width + uniform(0, 40);
        const std::vector<uint8_t> luma = random_samples<uint8_t>(rng, luma_stride * rows, 8, uniform(0, 1));
        const std::vector<uint8_t> chroma = random_samples<uint8_t>(rng, chroma_stride * rows, 8, uniform(0, 1));
        const int got_stride = luma_stride + uniform(0, 40);
        std::vector<uint8_t> want(std::size_t(got_stride) * std::size_t(rows), uint8_t(7)), got = want;
        // the luma rows co-sited with the chroma rows: every one, or every other (4:2:0)
        const int luma_step = uniform(0, 1) + 1;
        const int chroma_rows = (rows + luma_step - 1) / luma_step;
        for (int r = 0; r < rows; r++)
            av1::blend_luma_row<uint8_t>(luma.data() + r * luma_stride, want.data() + r * got_stride,
                                         luma_noise.flat_below(r).data(), luma_width, scaling, shift, clip.min_value,
                                         clip.max_luma);
        const av1::simd::PlaneRows luma_rows{rows, luma_stride, got_stride, 0, luma_noise.pitch};
        av1::simd::blend_luma_rows_u8(luma.data(), got.data(), luma_rows, luma_noise.row, luma_width, scaling, shift,
                                      clip.min_value, clip.max_luma);
        ASSERT_EQ(got, want) << "luma rows, iteration " << iter << " width " << luma_width << " rows " << rows;
        for (int r = 0; r < chroma_rows; r++)
            av1::blend_chroma_row<uint8_t>(chroma.data() + r * chroma_stride, want.data() + r * got_stride,
                                           luma.data() + r * luma_step * luma_stride, luma_width,
                                           chroma_noise.flat_below(r).data(), chroma_width, subx, index, scaling, shift,
                                           8, clip.min_value, clip.max_chroma);
        const av1::simd::PlaneRows chroma_rows_of{chroma_rows, chroma_stride, got_stride, std::ptrdiff_t(luma_step) * luma_stride,
                                                  chroma_noise.pitch};
        av1::simd::blend_chroma_rows_u8(chroma.data(), got.data(), luma.data(), luma_width, chroma_rows_of,
                                        chroma_noise.row, chroma_width, subx, index, scaling, shift, 8,
                                        clip.min_value, clip.max_chroma);
        ASSERT_EQ(got, want) << "chroma rows, iteration " << iter << " width " << chroma_width << " rows "
                             << chroma_rows;
    }
}

// The several-row kernels above 8 bits (blend_luma_rows_u16 / blend_chroma_rows_u16, as the
// synthesis calls them): each row at its stride, its noise r template rows down, a row to
// prefetch for some rows and none for the others, the co-sited luma of every row or every
// other one from any row of the stripe on (CoSitedRows::first_row), nothing written beside
// them, in place or not, and some rows holding samples above 10 bits (steps the 10-bit forms
// leave to the scalar way, row by row).
TEST_P(SimdAv1BlendRowsEquivalence, HighBitDepthRowsOfAStripe) {
    for (int iter = 0; iter < 80; iter++) {
        const int bd = uniform(0, 3) ? 10 : 12;
        const int width = uniform(0, 1) ? 1920 : uniform(1, 700), subx = uniform(0, 1);
        const int mode = uniform(0, bd == 10 ? 2 : 1);
        const int luma_width = subx ? 2 * width - uniform(0, 1) : width;
        const int chroma_width = subx ? (luma_width + 1) / 2 : width;
        const int rows = uniform(1, 34);
        const av1::ScalingLookup scaling = random_scaling(rng, bd);
        const int shift = uniform(8, 11);
        const av1::ClipLimits clip = av1::clip_limits(uniform(0, 1), bd, uniform(0, 2));
        const av1::ChromaScalingIndex index{uniform(0, 3) == 0, uniform(-128, 127), uniform(-128, 127),
                                            uniform(-256, 255)};
        TemplateNoise luma_noise(luma_width, 32, bd, rows + 40, mode, rng);
        // unsubsampled luma (or the shared co-sited rows) with 16- or 32-wide chroma blocks
        TemplateNoise chroma_noise(chroma_width, uniform(0, 1) ? 16 : 32, bd, rows + 40, mode, rng);
        luma_noise.row.row_offset = std::ptrdiff_t(uniform(0, 40)) * luma_noise.pitch;
        chroma_noise.row.row_offset = std::ptrdiff_t(uniform(0, 40)) * chroma_noise.pitch;
        const int luma_stride = luma_width + uniform(0, 40), chroma_stride = chroma_width + uniform(0, 40);
        std::vector<uint16_t> luma = random_samples<uint16_t>(rng, luma_stride * rows, bd, uniform(0, 1));
        std::vector<uint16_t> chroma = random_samples<uint16_t>(rng, chroma_stride * rows, bd, uniform(0, 1));
        if (uniform(0, 2) == 0)  // a few samples above 10 bits in a few rows
            for (int k = uniform(1, 6); k > 0; k--) {
                luma[std::size_t(uniform(0, int(luma.size()) - 1))] = uint16_t(uniform(1024, 65535));
                chroma[std::size_t(uniform(0, int(chroma.size()) - 1))] = uint16_t(uniform(1024, 65535));
            }
        const int got_stride = luma_stride + uniform(0, 40);
        std::vector<uint16_t> want(std::size_t(got_stride) * std::size_t(rows), uint16_t(7)), got = want;
        // the rows' prefetch: none, or for the first ahead_count rows (the output must not depend on it)
        auto with_ahead = [&](av1::simd::PlaneRows r, const std::vector<uint16_t>& source) {
            if (uniform(0, 1)) r.ahead = source.data(), r.ahead_count = uniform(0, r.count);
            return r;
        };
        // co-sited luma of the stripe's rows from first_row on, every row or every other one
        const int rows_shift = uniform(0, 1), first_row = uniform(0, 3);
        const int co_sited_width = (luma_width + 1) / 2, co_sited_rows = (first_row + rows) / (1 << rows_shift) + 1;
        const std::size_t co_sited_size = std::size_t(co_sited_width) * std::size_t(co_sited_rows);
        std::vector<uint16_t> co_sited_want(co_sited_size, uint16_t(0x7777)), co_sited_got = co_sited_want;
        const bool in_place = uniform(0, 1);
        for (int r = 0; r < rows; r++) {
            av1::blend_luma_row<uint16_t>(luma.data() + r * luma_stride, want.data() + r * got_stride,
                                          luma_noise.flat_below(r).data(), luma_width, scaling, shift, clip.min_value,
                                          clip.max_luma);
            const int i = first_row + r;
            if (i % (1 << rows_shift) == 0)
                av1::co_sited_luma_row<uint16_t>(luma.data() + r * luma_stride, luma_width, co_sited_width,
                                                 co_sited_want.data() + (i >> rows_shift) * co_sited_width);
        }
        const av1::simd::CoSitedRows co_sited{co_sited_got.data(), co_sited_width, rows_shift, first_row};
        if (in_place) {
            // got holds the source at got's stride, blended where it is
            for (int r = 0; r < rows; r++)
                std::copy_n(luma.data() + r * luma_stride, luma_width, got.data() + r * got_stride);
            const std::vector<uint16_t> src = got;
            const av1::simd::PlaneRows luma_rows = with_ahead({rows, got_stride * 2, got_stride * 2, 0, luma_noise.pitch}, src);
            av1::simd::blend_luma_rows_u16(got.data(), got.data(), luma_rows, luma_noise.row, luma_width, scaling,
                                           shift, bd, clip.min_value, clip.max_luma, co_sited);
        } else {
            const av1::simd::PlaneRows luma_rows =
                with_ahead({rows, luma_stride * 2, got_stride * 2, 0, luma_noise.pitch}, luma);
            av1::simd::blend_luma_rows_u16(luma.data(), got.data(), luma_rows, luma_noise.row, luma_width, scaling,
                                           shift, bd, clip.min_value, clip.max_luma, co_sited);
        }
        ASSERT_EQ(got, want) << "luma rows, iteration " << iter << " bd " << bd << " width " << luma_width
                             << " rows " << rows << " mode " << mode << " in place " << in_place;
        ASSERT_EQ(co_sited_got, co_sited_want) << "co-sited rows, iteration " << iter << " shift " << rows_shift
                                               << " first row " << first_row;

        // chroma with luma of its width (the shared co-sited rows) or subsampled luma
        const bool co_sited_luma = uniform(0, 1) && rows_shift == 0 && first_row == 0;
        const uint16_t* chroma_luma = co_sited_luma ? co_sited_want.data() : luma.data();
        const std::ptrdiff_t chroma_luma_stride = co_sited_luma ? co_sited_width : luma_stride;
        const int chroma_luma_width = co_sited_luma ? co_sited_width : luma_width;
        const int chroma_subx = co_sited_luma ? 0 : subx;
        const int chroma_w = co_sited_luma ? co_sited_width : chroma_width;
        std::optional<TemplateNoise> own_noise;
        if (co_sited_luma) {
            own_noise.emplace(chroma_w, 16 << uniform(0, 1), bd, rows + 40, mode, rng);
            own_noise->row.row_offset = std::ptrdiff_t(uniform(0, 40)) * own_noise->pitch;
        }
        const TemplateNoise& noise = co_sited_luma ? *own_noise : chroma_noise;
        std::vector<uint16_t> chroma_src = chroma;
        if (co_sited_luma) chroma_src = random_samples<uint16_t>(rng, chroma_stride * rows + chroma_w, bd, false);
        const int chroma_src_stride = co_sited_luma ? std::max(chroma_stride, chroma_w) : chroma_stride;
        want.assign(want.size(), uint16_t(9));
        got = want;
        for (int r = 0; r < rows; r++)
            av1::blend_chroma_row<uint16_t>(chroma_src.data() + r * chroma_src_stride, want.data() + r * got_stride,
                                            chroma_luma + r * chroma_luma_stride, chroma_luma_width,
                                            noise.flat_below(r).data(), chroma_w, chroma_subx, index, scaling, shift,
                                            bd, clip.min_value, clip.max_chroma);
        const av1::simd::PlaneRows chroma_rows = with_ahead(
            {rows, chroma_src_stride * 2, got_stride * 2, chroma_luma_stride * 2, noise.pitch}, chroma_src);
        av1::simd::blend_chroma_rows_u16(chroma_src.data(), got.data(), chroma_luma, chroma_luma_width, chroma_rows,
                                         noise.row, chroma_w, chroma_subx, index, scaling, shift, bd, clip.min_value,
                                         clip.max_chroma);
        ASSERT_EQ(got, want) << "chroma rows, iteration " << iter << " bd " << bd << " width " << chroma_w
                             << " rows " << rows << " co-sited luma " << co_sited_luma << " subx " << chroma_subx;
    }
}

// The rows a stripe shares with the one above (assemble_cross_faded_row, up to 10 bits): both
// rows' noise, each with its horizontal overlap faded or none, then the vertical fade of
// build_stripe_noise, against the same from BlockNoiseRow::at.
TEST_P(SimdAv1BlendRowsEquivalence, CrossFadedRows) {
    for (int iter = 0; iter < 300; iter++) {
        const int bd = uniform(0, 1) ? 10 : 8, subx = uniform(0, 1), suby = uniform(0, 1);
        const int width = uniform(0, 2) ? uniform(1, 2200) : 1920 >> subx;
        const int mode = uniform(0, 1) ? 2 : 0;  // faded in the kernel or no overlap (both rows alike)
        const TemplateNoise above(width, 32 >> subx, bd, uniform(1, 40), mode, rng);
        const TemplateNoise own(width, 32 >> subx, bd, uniform(1, 40), mode, rng);
        const av1::OverlapWeights w = av1::overlap_weights(uniform(0, 1 - suby), suby);
        const int gmin = own.row.gmin, gmax = own.row.gmax;
        std::vector<int16_t> want(static_cast<std::size_t>(width), int16_t(0)), got(want.size() + 3, int16_t(0x7777));
        for (int x = 0; x < width; x++) {
            const int v = (above.flat[std::size_t(x)] * w.old_weight + own.flat[std::size_t(x)] * w.new_weight + 16) >> 5;
            want[std::size_t(x)] = int16_t(std::clamp(v, gmin, gmax));
        }
        av1::simd::assemble_cross_faded_row(above.row, own.row, width, w.old_weight, w.new_weight, got.data());
        for (int x = 0; x < width; x++)
            ASSERT_EQ(got[std::size_t(x)], want[std::size_t(x)])
                << "iteration " << iter << " x " << x << " width " << width << " bd " << bd << " mode " << mode;
        for (std::size_t x = std::size_t(width); x < got.size(); x++) ASSERT_EQ(got[x], int16_t(0x7777)) << "wrote past the row";
    }
}

// The copy the byte kernels read: every 8-bit noise value as it is, then the spare bytes
// they may read past the last row, zero (a reused buffer is resized, not appended to).
TEST(Av1ByteNoise, CopyKeepsEveryValueAndPadsForTheKernelsReads) {
    std::vector<int16_t> samples;
    for (int v = -128; v <= 127; v++) samples.push_back(int16_t(v));
    std::vector<int8_t> bytes(1000, int8_t(5));
    av1::simd::copy_noise_as_bytes(samples, bytes);
    ASSERT_EQ(bytes.size(), samples.size() + std::size_t(av1::simd::kByteNoiseReadBytes));
    for (std::size_t i = 0; i < samples.size(); i++) ASSERT_EQ(int(bytes[i]), int(samples[i])) << i;
    for (std::size_t i = samples.size(); i < bytes.size(); i++) ASSERT_EQ(int(bytes[i]), 0) << i;
}

INSTANTIATE_TEST_SUITE_P(Targets, SimdAv1BlendRowsEquivalence, ::testing::ValuesIn(simd::available_targets()),
                         [](const ::testing::TestParamInfo<simd::Target>& info) { return info.param.name; });

}  // namespace
