// Checkasm-style equivalence of the FGC kernels that take int8 grain (the narrow scaled
// tables) with the scalar reference stages, for every vector target this CPU runs (each
// forced in turn): random widths (vector tails included), block sizes, bit depths, grain
// over the whole int8 range and 16-bit samples above the bit depth, so that the clipping at
// both ends is exercised.
#include <gtest/gtest.h>

#include <algorithm>
#include <random>
#include <vector>

#include "core/simd_targets.hpp"
#include "forced_simd_target.hpp"
#include "prefetched_rows.hpp"
#include "fgc/blending.hpp"
#include "fgc/deblocking.hpp"
#include "fgc/simd/fgc_kernels.hpp"

using namespace filmgrain;

namespace {

class FgcSimdEquivalence : public test_support::ForcedSimdTarget<20261124u> {
protected:
    template <typename Pixel>
    void check_rows_from_blocks(int iterations);
    template <typename Pixel>
    void check_tables_from_sums(int iterations);
};

// One grain row as the optimized stripe holds it: element 0 is the readable element before
// column 0 (random: the kernels must not use it), then width + 1 grain values.
struct NarrowRow {
    std::vector<int8_t> storage;
    std::vector<int32_t> deblocked;  // the reference stages' result, stripe stride width + 2
    NarrowRow(int width, int block_size, std::mt19937& rng) : storage(std::size_t(width) + 2) {
        // extremes often: they are where a wrong rounding or clip shows
        std::uniform_int_distribution<int> pick(0, 9), value(-128, 127);
        for (auto& v : storage) {
            const int p = pick(rng);
            v = int8_t(p == 0 ? -128 : p == 1 ? 127 : value(rng));
        }
        deblocked.assign(storage.begin() + 1, storage.end());
        deblocked.push_back(0);
        fgc::deblock_stripe_vertical_edges(deblocked.data(), width + 2, 1, width, block_size);
    }
    const int8_t* grain() const { return storage.data() + 1; }
};

TEST_P(FgcSimdEquivalence, DeblockAndBlendInt8Grain8Bit) {
    for (int iter = 0; iter < 1000; iter++) {
        const int bs = 8 << uniform(0, 2), width = uniform(0, 3) ? uniform(1, 300) : 32 * uniform(1, 12);
        const NarrowRow g(width, bs, rng);
        std::vector<uint8_t> src(std::size_t(width) + 1), want(src.size(), 0xA5), got(src.size(), 0xA5);
        for (auto& v : src) v = uint8_t(uniform(0, 3) == 0 ? 255 * uniform(0, 1) : uniform(0, 255));
        fgc::blend_row_additive<uint8_t>(src.data(), want.data(), g.deblocked.data(), width, 8);
        // rows to prefetch (the next stripe's in the synthesis), each half the time: no effect
        test_support::PrefetchedRows<uint8_t> ahead(src.size());
        const auto next = ahead.pick([&] { return uniform(0, 1) == 1; });
        fgc::simd::deblock_blend_row_u8_i8(src.data(), got.data(), g.grain(), width, bs, next);
        ASSERT_TRUE(ahead.untouched()) << "a prefetched row was written";
        ASSERT_EQ(got, want) << "iteration " << iter << " width " << width << " bs " << bs
                             << " (the last byte is past the row and must stay untouched)";
    }
}

TEST_P(FgcSimdEquivalence, DeblockAndBlendInt8Grain16Bit) {
    for (int iter = 0; iter < 1000; iter++) {
        const int bs = 8 << uniform(0, 2), width = uniform(0, 3) ? uniform(1, 300) : 32 * uniform(1, 12);
        const int bd = uniform(9, 16);
        const NarrowRow g(width, bs, rng);
        std::vector<uint16_t> src(std::size_t(width) + 1), want(src.size(), 0xA5A5), got(src.size(), 0xA5A5);
        const int max_value = (1 << bd) - 1;
        // in a quarter of the rows samples of any 16-bit value: above the bit depth (bad input)
        // the kernels must clip as the reference's 32-bit sum does
        const int top = uniform(0, 3) == 0 ? 65535 : max_value;
        for (auto& v : src) v = uint16_t(uniform(0, 3) == 0 ? top * uniform(0, 1) : uniform(0, top));
        fgc::blend_row_additive<uint16_t>(src.data(), want.data(), g.deblocked.data(), width, bd);
        // rows to prefetch (the next stripe's in the synthesis), each half the time: no effect
        test_support::PrefetchedRows<uint16_t> ahead(src.size());
        const auto next = ahead.pick([&] { return uniform(0, 1) == 1; });
        fgc::simd::deblock_blend_row_u16_i8(src.data(), got.data(), g.grain(), width, bs, bd, next);
        ASSERT_TRUE(ahead.untouched()) << "a prefetched row was written";
        ASSERT_EQ(got, want) << "iteration " << iter << " width " << width << " bs " << bs << " bd " << bd;
    }
}

TEST_P(FgcSimdEquivalence, GatherBlockBands) {
    std::vector<int8_t> table(64 * 64 * 4);
    for (auto& v : table) v = int8_t(uniform(-128, 127));
    for (int iter = 0; iter < 500; iter++) {
        const int bs = 8 << uniform(0, 2), count = uniform(1, 40), rows = uniform(1, bs);
        const std::ptrdiff_t pitch = uniform(0, 1) ? 64 : bs, stride = count * bs + uniform(0, 5);
        const std::ptrdiff_t offset = pitch * uniform(0, 8);
        std::vector<const int8_t*> blocks;
        for (int j = 0; j < count; j++)
            blocks.push_back(table.data() + uniform(0, int(table.size() - offset) - int(pitch) * (rows - 1) - bs));
        std::vector<int8_t> want(std::size_t(stride) * rows + 1, 0x5A), got(want);
        for (int j = 0; j < count; j++)
            for (int r = 0; r < rows; r++)
                for (int k = 0; k < bs; k++)
                    want[std::size_t(r * stride + j * bs + k)] = blocks[j][offset + r * pitch + k];
        fgc::simd::gather_block_bands_i8(blocks.data(), offset, count, bs, rows, pitch, got.data(), stride);
        ASSERT_EQ(got, want) << "iteration " << iter << " bs " << bs << " count " << count << " rows " << rows;
    }
}

// Rows straight from block pointers: the reference is the element-wise gather, the zeros
// from grain_end (rdd5: the picture's width; vtm: past the last block) and the reference
// deblocking and blending of each row. Tables hold random int8 rows of pitch 64, as the
// scaled tables do; grain_end takes the values the stripe passes and others. 16-bit samples
// at bit depths 9 to 16 (the AVX3 form takes 8x8 and 16x16 blocks up to 12 bits, the others
// the generic form).
template <typename Pixel>
void FgcSimdEquivalence::check_rows_from_blocks(int iterations) {
    constexpr std::ptrdiff_t kPitch = 64;
    std::vector<int8_t> table(64 * 64 * 4);
    for (auto& v : table)  // the extremes often
        v = int8_t(uniform(0, 9) == 0 ? (uniform(0, 1) ? 127 : -128) : uniform(-128, 127));
    for (int iter = 0; iter < iterations; iter++) {
        // 8 and 16 (the AVX3 forms) most often
        const int pick = uniform(0, 7), bs = pick < 4 ? 8 : pick < 7 ? 16 : 32;
        const int bd = sizeof(Pixel) == 1 ? 8 : uniform(9, 16);
        const int max_value = (1 << bd) - 1;
        const int width = uniform(0, 3) ? uniform(1, 300) : 64 * uniform(1, 6) + uniform(-1, 1);
        const int rows = uniform(1, 8);
        const int padded = (width + bs - 1) / bs * bs + (uniform(0, 1) ? bs : 0);  // the stripe's grain width
        const int grain_end = uniform(0, 2) == 0 ? width : uniform(0, 2) == 0 ? uniform(0, padded) : padded;
        const std::ptrdiff_t offset = kPitch * uniform(0, 7 - (rows - 1) / 2);
        const std::ptrdiff_t src_stride = width + uniform(0, 70), dst_stride = width + uniform(0, 70);
        // Luma's two 8x8 blocks of a 16x16 block often lie side by side in one table (one offset,
        // one interval): in half the iterations most pairs do, so that vectors of joined pairs,
        // of mixed pairs and of none all occur.
        const bool pairs = bs == 8 && uniform(0, 1) == 1;
        std::vector<const int8_t*> blocks;
        const int last = int(table.size() - offset - kPitch * (rows - 1));
        for (int j = 0; j < padded / bs; j++)
            if (pairs && j % 2 == 1 && uniform(0, 7) != 0 && blocks.back() + 2 * bs <= table.data() + last)
                blocks.push_back(blocks.back() + bs);
            else
                blocks.push_back(table.data() + uniform(0, last - bs));
        std::vector<Pixel> src(std::size_t(src_stride) * rows + 1);
        // 16-bit samples of any value in a quarter of the iterations (bad input above the bit depth)
        const int top = sizeof(Pixel) == 2 && uniform(0, 3) == 0 ? 65535 : max_value;
        for (auto& v : src) v = Pixel(uniform(0, 3) == 0 ? top * uniform(0, 1) : uniform(0, top));
        std::vector<Pixel> want(std::size_t(dst_stride) * rows + 1, Pixel(0xA5A5)), got(want);
        for (int r = 0; r < rows; r++) {
            std::vector<int32_t> grain(std::size_t(padded) + 2, 0);
            for (int x = 0; x < std::min(grain_end, padded); x++)
                grain[std::size_t(x)] = blocks[std::size_t(x / bs)][offset + r * kPitch + x % bs];
            fgc::deblock_stripe_vertical_edges(grain.data(), padded + 2, 1, width, bs);
            fgc::blend_row_additive<Pixel>(src.data() + r * src_stride, want.data() + r * dst_stride, grain.data(),
                                           width, bd);
        }
        // scratch of just the size the kernel asks for (the address sanitizer catches more)
        std::vector<int8_t> row(fgc::simd::deblock_blend_block_rows_scratch(rows, width, grain_end, bs),
                                int8_t(uniform(-128, 127)));
        // rows to prefetch (the next stripe's in the synthesis), each half the time: no effect
        test_support::PrefetchedRows<Pixel> ahead(src.size());
        const auto next = ahead.pick([&] { return uniform(0, 1) == 1; });
        if constexpr (sizeof(Pixel) == 1)
            fgc::simd::deblock_blend_block_rows_u8_i8(src.data(), src_stride, got.data(), dst_stride, blocks.data(),
                                                      offset, kPitch, rows, width, grain_end, bs, row.data(), next);
        else
            fgc::simd::deblock_blend_block_rows_u16_i8(src.data(), src_stride, got.data(), dst_stride, blocks.data(),
                                                       offset, kPitch, rows, width, grain_end, bs, bd, row.data(), next);
        ASSERT_TRUE(ahead.untouched()) << "a prefetched row was written";
        ASSERT_EQ(got, want) << "iteration " << iter << " width " << width << " rows " << rows << " bs " << bs
                             << " bit depth " << bd << " grain_end " << grain_end
                             << " (samples between and past the rows must stay untouched)";
    }
}

TEST_P(FgcSimdEquivalence, DeblockAndBlendFromBlocks8Bit) { check_rows_from_blocks<uint8_t>(2000); }

TEST_P(FgcSimdEquivalence, DeblockAndBlendFromBlocks16Bit) { check_rows_from_blocks<uint16_t>(2000); }

// Each whole block's table pointer from its sample sum: the reference is the element-wise
// sum, shift, clamp and look-up. Samples are often all at their largest value (the largest
// sums) and the shift runs from the bit depth's own down to 0, so that the clamp at 255 is
// exercised. 16-bit samples at bit depths 9 to 16, and any 16-bit value (bad input the sums
// must still add exactly).
template <typename Pixel>
void FgcSimdEquivalence::check_tables_from_sums(int iterations) {
    std::vector<int8_t> tables(1 << 16);
    std::vector<int32_t> offsets(256);
    for (int iter = 0; iter < iterations; iter++) {
        const int bs = uniform(0, 2) ? 8 : 8 << uniform(1, 2);
        const int bd = sizeof(Pixel) == 1 ? 8 : uniform(9, 16);
        const int max_value = sizeof(Pixel) == 1 || uniform(0, 3) ? (1 << bd) - 1 : 65535;
        const int rows = uniform(0, 3) ? bs : uniform(1, bs);
        const int width = uniform(0, 2) ? uniform(1, 700) : 64 * uniform(1, 10);
        const int own_shift = (bs == 8 ? 6 : bs == 16 ? 8 : 10) + bd - 8;
        const int shift = uniform(0, 3) ? own_shift : uniform(0, own_shift + 4);
        const std::ptrdiff_t pitch = width + uniform(0, 40);
        const bool flat = uniform(0, 3) == 0;
        std::vector<Pixel> src(std::size_t(pitch) * rows);
        for (auto& v : src) v = Pixel(flat ? max_value : uniform(0, max_value));
        for (auto& o : offsets) o = uniform(0, 4) * 8192;
        const int blocks = width / bs;
        std::vector<int32_t> places(static_cast<std::size_t>(blocks));
        for (auto& p : places) p = uniform(0, 8191);
        std::vector<const int8_t*> want(std::size_t(blocks) + 1, nullptr), got(want);
        for (int j = 0; j < blocks; j++) {
            uint32_t sum = 0;
            for (int y = 0; y < rows; y++)
                for (int k = 0; k < bs; k++) sum += src[std::size_t(y * pitch + j * bs + k)];
            want[std::size_t(j)] =
                tables.data() + offsets[std::min<uint32_t>(sum >> shift, 255)] + places[std::size_t(j)];
        }
        const std::ptrdiff_t stride = pitch * std::ptrdiff_t(sizeof(Pixel));
        if constexpr (sizeof(Pixel) == 1)
            fgc::simd::block_tables_u8(src.data(), stride, rows, width, bs, shift, offsets.data(), places.data(),
                                       tables.data(), got.data());
        else
            fgc::simd::block_tables_u16(src.data(), stride, rows, width, bs, shift, offsets.data(), places.data(),
                                        tables.data(), got.data());
        ASSERT_EQ(got, want) << "iteration " << iter << " width " << width << " rows " << rows << " bs " << bs
                             << " bit depth " << bd << " shift " << shift
                             << " (the entry past the last whole block must stay untouched)";
    }
}

TEST_P(FgcSimdEquivalence, BlockTablesFromSums8Bit) { check_tables_from_sums<uint8_t>(1000); }

TEST_P(FgcSimdEquivalence, BlockTablesFromSums16Bit) { check_tables_from_sums<uint16_t>(1000); }

INSTANTIATE_TEST_SUITE_P(Targets, FgcSimdEquivalence, ::testing::ValuesIn(simd::available_targets()),
                         [](const ::testing::TestParamInfo<simd::Target>& i) { return i.param.name; });

}  // namespace
