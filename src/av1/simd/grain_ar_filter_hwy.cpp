// Highway implementation of grain_ar_filter.hpp, compiled once per target (foreach_target).
//
// The filter of 7.18.3.3 is a recurrence, but along a row it is serial only through the
// `lag` left neighbours on the current row: the rows above are final before the row
// starts. So each row is done in two passes: the rows-above taps (and chroma's luma term)
// for the whole row in vector lanes, then a short scalar pass that adds the left taps,
// shifts and clips, sample by sample. Integer sums are exact, so regrouping the taps
// cannot change a result. The vector pass also folds in the white noise and the rounding:
// noise + Round2(sum, s) equals ((noise << s) + sum + (1 << (s - 1))) >> s exactly (floor
// division by 2^s of a multiple of 2^s plus a remainder), which leaves only a multiply,
// an add and a shift on the serial dependency chain.
#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "av1/simd/grain_ar_filter_hwy.cpp"
#include "hwy/foreach_target.h"  // IWYU pragma: keep
#include "hwy/highway.h"

#include <cstddef>

#include "av1/grain_template_generation.hpp"
#include "av1/simd/grain_ar_filter.hpp"

HWY_BEFORE_NAMESPACE();
namespace filmgrain::av1::simd {
namespace HWY_NAMESPACE {
namespace hn = hwy::HWY_NAMESPACE;

// The templates are at most 82 wide (kLumaTemplateWidth), so one row of partial sums fits
// on the stack.
constexpr int kMaxColumns = kLumaTemplateWidth;

// Luma row co-sited with chroma row y (the reference's ly).
inline const int16_t* CositedLumaRow(const ArFilterJob& j, int y) {
    const int ly = ((y - kArPadding) << j.subsampling_y) + kArPadding;
    return j.luma + static_cast<std::ptrdiff_t>(ly) * j.luma_width;
}

// Round2 of the sum of the 1, 2 or 4 luma samples under chroma column x, in scalar.
inline int LumaAverage(const ArFilterJob& j, const int16_t* lrow, int x) {
    const int lx = ((x - kArPadding) << j.subsampling_x) + kArPadding;
    int sum = 0;
    for (int i = 0; i <= j.subsampling_y; ++i)
        for (int k = 0; k <= j.subsampling_x; ++k) sum += lrow[i * j.luma_width + lx + k];
    const int n = j.subsampling_x + j.subsampling_y;
    return (sum + ((1 << n) >> 1)) >> n;
}

// The same for lanes [x, x + lanes). A horizontal luma pair is read as one int32 lane and
// split into its sign-extended halves, which needs no shuffles (little-endian lanes).
template <class D32>
HWY_INLINE hn::Vec<D32> LumaAverageLanes(D32 d32, const ArFilterJob& j, const int16_t* lrow, int x) {
    const hn::Rebind<int16_t, D32> d16;
    const int lx = ((x - kArPadding) << j.subsampling_x) + kArPadding;
    auto row_sum = [&](const int16_t* r) {
        if (!j.subsampling_x) return hn::PromoteTo(d32, hn::LoadU(d16, r + lx));
        const auto pairs = hn::LoadU(d32, reinterpret_cast<const int32_t*>(r + lx));
        return hn::Add(hn::ShiftRight<16>(hn::ShiftLeft<16>(pairs)), hn::ShiftRight<16>(pairs));
    };
    auto sum = row_sum(lrow);
    if (j.subsampling_y) sum = hn::Add(sum, row_sum(lrow + j.luma_width));
    const int n = j.subsampling_x + j.subsampling_y;
    return hn::ShiftRightSame(hn::Add(sum, hn::Set(d32, (1 << n) >> 1)), n);
}

// (noise << shift) + rounding + rows-above taps + luma term for lanes [x, x + lanes) of
// row y, into partial[x - 3].
template <int Lag, class D32>
HWY_INLINE void AboveLanes(D32 d32, const ArFilterJob& j, const int16_t* row, const int16_t* lrow, int luma_coeff,
                           int x, int32_t* partial) {
    const hn::Rebind<int16_t, D32> d16;
    auto acc = hn::Add(hn::ShiftLeftSame(hn::PromoteTo(d32, hn::LoadU(d16, row + x)), j.shift),
                       hn::Set(d32, 1 << (j.shift - 1)));
    int pos = 0;
    for (int dy = -Lag; dy < 0; ++dy) {
        const int16_t* r = row + static_cast<std::ptrdiff_t>(dy) * j.width + x;
        for (int dx = -Lag; dx <= Lag; ++dx)
            acc = hn::Add(acc, hn::Mul(hn::Set(d32, j.coeffs[pos++]), hn::PromoteTo(d32, hn::LoadU(d16, r + dx))));
    }
    if (lrow) acc = hn::Add(acc, hn::Mul(hn::Set(d32, luma_coeff), LumaAverageLanes(d32, j, lrow, x)));
    hn::StoreU(acc, d32, partial + (x - kArPadding));
}

// The same in scalar, for rows narrower than a vector.
template <int Lag>
void AboveScalar(const ArFilterJob& j, const int16_t* row, const int16_t* lrow, int luma_coeff, int x0, int x1,
                 int32_t* partial) {
    for (int x = x0; x < x1; ++x) {
        int sum = row[x] * (1 << j.shift) + (1 << (j.shift - 1)), pos = 0;
        for (int dy = -Lag; dy < 0; ++dy)
            for (int dx = -Lag; dx <= Lag; ++dx)
                sum += j.coeffs[pos++] * row[static_cast<std::ptrdiff_t>(dy) * j.width + x + dx];
        if (lrow) sum += luma_coeff * LumaAverage(j, lrow, x);
        partial[x - kArPadding] = sum;
    }
}

// The serial part: left taps, shift and clip. The previous outputs stay in registers
// rather than being re-read from the row just written, and the taps of the older ones
// are added first, off the chain through the newest. Clipping is rare with the
// coefficients encoders produce, so it is a predicted branch rather than on the chain.
template <int Lag>
HWY_INLINE void LeftSerial(const ArFilterJob& j, int16_t* row, int x0, int x1, const int32_t* partial) {
    const int* left = j.coeffs + Lag * (2 * Lag + 1);  // dx = -Lag .. -1
    const int c1 = Lag >= 1 ? left[Lag - 1] : 0, c2 = Lag >= 2 ? left[Lag - 2] : 0, c3 = Lag >= 3 ? left[0] : 0;
    const int shift = j.shift, gmin = j.grain_min, gmax = j.grain_max;
    int n1 = row[x0 - 1], n2 = row[x0 - 2], n3 = row[x0 - 3];
    for (int x = x0; x < x1; ++x) {
        int sum = partial[x - kArPadding];
        if constexpr (Lag >= 3) sum += c3 * n3;
        if constexpr (Lag >= 2) sum += c2 * n2;
        if constexpr (Lag >= 1) sum += c1 * n1;
        int v = sum >> shift;
        if (HWY_UNLIKELY(v < gmin || v > gmax)) v = v < gmin ? gmin : gmax;
        row[x] = static_cast<int16_t>(v);
        n3 = n2;
        n2 = n1;
        n1 = v;
    }
}

// Vector pass of row y: partial[x - 3] for every filtered column.
template <int Lag>
HWY_INLINE void AbovePass(const ArFilterJob& j, int y, int32_t* partial) {
    const hn::ScalableTag<int32_t> d32;
    const int lanes = static_cast<int>(hn::Lanes(d32));
    const int x0 = kArPadding, x1 = j.width - kArPadding;
    const int luma_coeff = j.luma ? j.coeffs[2 * Lag * (Lag + 1)] : 0;
    const int16_t* row = j.grain + static_cast<std::ptrdiff_t>(y) * j.width;
    const int16_t* lrow = j.luma ? CositedLumaRow(j, y) : nullptr;
    if (x1 - x0 >= lanes) {
        int x = x0;
        for (; x + lanes <= x1; x += lanes) AboveLanes<Lag>(d32, j, row, lrow, luma_coeff, x, partial);
        // The last partial vector is redone overlapping the previous one: partial sums
        // only read finished rows, so recomputing a lane gives the same value.
        if (x < x1) AboveLanes<Lag>(d32, j, row, lrow, luma_coeff, x1 - lanes, partial);
    } else {
        AboveScalar<Lag>(j, row, lrow, luma_coeff, x0, x1, partial);
    }
}

template <int Lag>
void FilterRows(const ArFilterJob& j) {
    HWY_ALIGN int32_t partial[kMaxColumns];
    for (int y = kArPadding; y < j.height; ++y) {
        AbovePass<Lag>(j, y, partial);
        LeftSerial<Lag>(j, j.grain + static_cast<std::ptrdiff_t>(y) * j.width, kArPadding, j.width - kArPadding,
                        partial);
    }
}

// Two templates of the same size (Cb and Cr): their serial chains are independent, so
// they are interleaved sample by sample for the CPU to overlap them.
template <int Lag>
void FilterRowsPair(const ArFilterJob& a, const ArFilterJob& b) {
    HWY_ALIGN int32_t pa[kMaxColumns];
    HWY_ALIGN int32_t pb[kMaxColumns];
    const int* la = a.coeffs + Lag * (2 * Lag + 1);
    const int* lb = b.coeffs + Lag * (2 * Lag + 1);
    const int a1 = Lag >= 1 ? la[Lag - 1] : 0, a2 = Lag >= 2 ? la[Lag - 2] : 0, a3 = Lag >= 3 ? la[0] : 0;
    const int b1 = Lag >= 1 ? lb[Lag - 1] : 0, b2 = Lag >= 2 ? lb[Lag - 2] : 0, b3 = Lag >= 3 ? lb[0] : 0;
    const int shift = a.shift, gmin = a.grain_min, gmax = a.grain_max;
    const int x0 = kArPadding, x1 = a.width - kArPadding;
    for (int y = kArPadding; y < a.height; ++y) {
        AbovePass<Lag>(a, y, pa);
        AbovePass<Lag>(b, y, pb);
        int16_t* ra = a.grain + static_cast<std::ptrdiff_t>(y) * a.width;
        int16_t* rb = b.grain + static_cast<std::ptrdiff_t>(y) * b.width;
        int an1 = ra[x0 - 1], an2 = ra[x0 - 2], an3 = ra[x0 - 3];
        int bn1 = rb[x0 - 1], bn2 = rb[x0 - 2], bn3 = rb[x0 - 3];
        for (int x = x0; x < x1; ++x) {
            int sa = pa[x - kArPadding], sb = pb[x - kArPadding];
            if constexpr (Lag >= 3) sa += a3 * an3, sb += b3 * bn3;
            if constexpr (Lag >= 2) sa += a2 * an2, sb += b2 * bn2;
            if constexpr (Lag >= 1) sa += a1 * an1, sb += b1 * bn1;
            int va = sa >> shift, vb = sb >> shift;
            if (HWY_UNLIKELY(va < gmin || va > gmax)) va = va < gmin ? gmin : gmax;
            if (HWY_UNLIKELY(vb < gmin || vb > gmax)) vb = vb < gmin ? gmin : gmax;
            ra[x] = static_cast<int16_t>(va);
            rb[x] = static_cast<int16_t>(vb);
            an3 = an2, an2 = an1, an1 = va;
            bn3 = bn2, bn2 = bn1, bn1 = vb;
        }
    }
}

void ArFilterTemplate(const ArFilterJob& j) {
    switch (j.lag) {
        case 0: return FilterRows<0>(j);
        case 1: return FilterRows<1>(j);
        case 2: return FilterRows<2>(j);
        default: return FilterRows<3>(j);
    }
}

void ArFilterTemplatePair(const ArFilterJob& a, const ArFilterJob& b) {
    switch (a.lag) {
        case 0: return FilterRowsPair<0>(a, b);
        case 1: return FilterRowsPair<1>(a, b);
        case 2: return FilterRowsPair<2>(a, b);
        default: return FilterRowsPair<3>(a, b);
    }
}

}  // namespace HWY_NAMESPACE
}  // namespace filmgrain::av1::simd
HWY_AFTER_NAMESPACE();

#if HWY_ONCE
namespace filmgrain::av1::simd {

HWY_EXPORT(ArFilterTemplate);
HWY_EXPORT(ArFilterTemplatePair);

void ar_filter_template(const ArFilterJob& job) { HWY_DYNAMIC_DISPATCH(ArFilterTemplate)(job); }
void ar_filter_template_pair(const ArFilterJob& first, const ArFilterJob& second) {
    HWY_DYNAMIC_DISPATCH(ArFilterTemplatePair)(first, second);
}

}  // namespace filmgrain::av1::simd
#endif  // HWY_ONCE
