// Highway twin of block_grains() (vfgs_block_grains.hpp), compiled once per target and
// dispatched at run time; the scalar reference is vfgs_block_grains_scalar.cpp.
#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "fgc/vfgs/simd/vfgs_block_grains_hwy.cpp"
#include "hwy/foreach_target.h"  // IWYU pragma: keep
#include "hwy/highway.h"

#include "fgc/vfgs/vfgs_block_grains.hpp"

HWY_BEFORE_NAMESPACE();
namespace filmgrain::vfgs::simd {
namespace HWY_NAMESPACE {
namespace hn = hwy::HWY_NAMESPACE;

// The bit fields of one component (vfgs_random.hpp). Every 10-bit field is the register
// rotated right by some count and masked: Cb's vertical field takes R[31:24] with R[1:0]
// above them, which is R rotated by 24; the other fields never wrap.
struct Fields {
    int sign_bit, x_rotate, y_rotate;
    uint32_t x_unit, y_unit;  // 4 / subsampling
};

Fields FieldsOf(const BlockGrainsJob& job) {
    const uint32_t ux = 4u >> (job.subx - 1), uy = 4u >> (job.suby - 1);
    switch (job.component) {
        case 0: return {31, 0, 14, 4, 4};
        case 1: return {2, 10, 24, ux, uy};
        default: return {15, 20, 4, ux, uy};
    }
}

template <class D>
HWY_INLINE hn::Vec<D> RotateRight(D /*d*/, hn::Vec<D> r, int count) {
    return count ? hn::Or(hn::ShiftRightSame(r, count), hn::ShiftLeftSame(r, 32 - count)) : r;
}

// (offset, sign) of each lane's register value: bin_of(field, bins) = field * bins >> 10.
template <class D>
HWY_INLINE void OffsetsAndSigns(D d, const Fields& f, hn::Vec<D> r, hn::Vec<D>& offset, hn::Vec<D>& sign) {
    const auto field = hn::Set(d, 0x3FFu);
    const auto x = hn::ShiftRight<10>(hn::Mul(hn::And(RotateRight(d, r, f.x_rotate), field), hn::Set(d, 13u)));
    const auto y = hn::ShiftRight<10>(hn::Mul(hn::And(RotateRight(d, r, f.y_rotate), field), hn::Set(d, 12u)));
    offset = hn::Add(hn::Mul(y, hn::Set(d, f.y_unit * kTemplatePitch)), hn::Mul(x, hn::Set(d, f.x_unit)));
    // +1, or -1 (all ones) where the sign bit is set
    const auto bit = hn::And(hn::ShiftRightSame(r, f.sign_bit), hn::Set(d, 1u));
    sign = hn::Sub(hn::Set(d, 1u), hn::Add(bit, bit));
}

void BlockGrains(const BlockGrainsJob& job, GrainBlock* out) {
    static_assert(sizeof(GrainBlock) == 4 * sizeof(uint32_t), "GrainBlock is four 32-bit fields, stored interleaved");
    const hn::ScalableTag<uint32_t> d;
    const int n = static_cast<int>(hn::Lanes(d));
    const Fields f = FieldsOf(job);
    int b = 0;
    for (; b + n <= job.count; b += n) {
        hn::Vec<decltype(d)> offset, sign, offset_up, sign_up;
        OffsetsAndSigns(d, f, hn::LoadU(d, job.states + b), offset, sign);
        OffsetsAndSigns(d, f, hn::LoadU(d, job.states_up + b), offset_up, sign_up);
        // GrainBlock's field order: offset, offset_up, sign, sign_up
        hn::StoreInterleaved4(offset, offset_up, sign, sign_up, d, reinterpret_cast<uint32_t*>(out + b));
    }
    if (b < job.count) {
        BlockGrainsJob rest = job;
        rest.states += b;
        rest.states_up += b;
        rest.count -= b;
        scalar::block_grains(rest, out + b);
    }
}

}  // namespace HWY_NAMESPACE
}  // namespace filmgrain::vfgs::simd
HWY_AFTER_NAMESPACE();

#if HWY_ONCE
namespace filmgrain::vfgs::simd {

HWY_EXPORT(BlockGrains);

void block_grains(const BlockGrainsJob& job, GrainBlock* out) { HWY_DYNAMIC_DISPATCH(BlockGrains)(job, out); }

}  // namespace filmgrain::vfgs::simd
#endif  // HWY_ONCE
