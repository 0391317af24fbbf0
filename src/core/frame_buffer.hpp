// An owning, tightly packed planar frame, laid out exactly as FFmpeg's raw planar
// pix_fmts (Y, then U, then V), so one frame's bytes are what a .yuv file holds.
#pragma once
#include <cstdint>
#include <memory>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

#include "core/cache_line.hpp"
#include "filmgrain/frame.hpp"

namespace filmgrain {

struct PixelFormat {
    ChromaFormat chroma = ChromaFormat::k420;
    int bit_depth = 8;
};

// FFmpeg pix_fmt name <-> format. Accepts gray, gray10le, gray12le, gray16le,
// yuv4{20,22,44}p and their 10/12/16-bit little-endian forms. Throws Error naming the value.
PixelFormat parse_pix_fmt(const std::string& name);
std::string pix_fmt_name(const PixelFormat& f);

// The largest picture any FrameBuffer (so any file the tool reads) may hold: width and height
// 1..kMaxPictureDimension and at most kMaxPictureSamples luma samples (2^28 = 16384x16384; a
// 4:4:4 16-bit frame of that size is 1.5 GiB). Checked before anything is allocated.
inline constexpr int kMaxPictureDimension = 65536;
inline constexpr long long kMaxPictureSamples = 1LL << 28;

// Throws Error(kInvalidArgument) naming the size and the limit when width x height is outside it.
void check_picture_size(int width, int height);

// A picture's first row starts on a cache line: malloc gives 16 mod 64 for the sizes it
// maps (any picture from 256 KiB up), where every 64-byte store of a vector kernel
// straddles two lines.
inline constexpr std::size_t kFrameAlignment = kCacheLineBytes;

// A std::allocator whose value-less construct() leaves bytes uninitialized, so that a vector
// resized for data about to be read is not zero-filled first (its pages stay untouched until
// the data arrives), and whose storage starts at kFrameAlignment.
template <typename T>
struct DefaultInitAllocator : std::allocator<T> {
    template <typename U>
    struct rebind {
        using other = DefaultInitAllocator<U>;
    };
    DefaultInitAllocator() = default;
    template <typename U>
    DefaultInitAllocator(const DefaultInitAllocator<U>&) noexcept {}
    T* allocate(std::size_t n) {
        return static_cast<T*>(::operator new(n * sizeof(T), std::align_val_t(kFrameAlignment)));
    }
    // unsized: clang declares the sized aligned delete only with -fsized-deallocation
    void deallocate(T* p, std::size_t) noexcept {
        ::operator delete(p, std::align_val_t(kFrameAlignment));
    }
    template <typename U>
    void construct(U* p) noexcept(std::is_nothrow_default_constructible_v<U>) {
        ::new (static_cast<void*>(p)) U;
    }
    template <typename U, typename... Args>
    void construct(U* p, Args&&... args) {
        std::allocator_traits<std::allocator<T>>::construct(*this, p, std::forward<Args>(args)...);
    }
};

class FrameBuffer {
public:
    FrameBuffer() = default;
    // Every sample 0. Throws Error(kInvalidArgument) outside the picture limit (check_picture_size)
    // or for a bit depth outside 8..16.
    FrameBuffer(int width, int height, PixelFormat fmt);
    // The same size checks, but the samples are left unset: for a frame that is read or
    // computed in full right after (a reader's frame, a synthesizer's output).
    static FrameBuffer uninitialized(int width, int height, PixelFormat fmt);

    int width() const { return width_; }
    int height() const { return height_; }
    PixelFormat format() const { return fmt_; }
    std::size_t byte_size() const { return bytes_.size(); }
    uint8_t* bytes() { return bytes_.data(); }
    const uint8_t* bytes() const { return bytes_.data(); }

    FrameView view();
    std::size_t plane_offset(int p) const { return offsets_[p]; }
    std::size_t plane_bytes(int p) const;

    static std::size_t frame_bytes(int width, int height, PixelFormat fmt);

private:
    struct Uninitialized {};
    FrameBuffer(int width, int height, PixelFormat fmt, Uninitialized);
    int width_ = 0, height_ = 0;
    PixelFormat fmt_;
    std::vector<uint8_t, DefaultInitAllocator<uint8_t>> bytes_;
    std::size_t offsets_[3] = {0, 0, 0};
};

// Copies every plane of src into dst (same format and size, any strides; nothing when they
// are the same planes).
void copy_frame(const FrameView& src, const FrameView& dst);

// Sets every sample of every plane of dst to `value` (a flat picture, e.g. the mid-grey one
// grain is calibrated on).
void fill_frame(const FrameView& dst, int value);

}  // namespace filmgrain
