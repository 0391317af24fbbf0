// MSB-first bit reading and writing for SEI, T.35 and OBU payloads, with Exp-Golomb codes.
// Reads past the end throw Error(kMalformedPayload) naming the field being read.
#pragma once
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "filmgrain/error.hpp"

namespace filmgrain {

class BitReader {
public:
    BitReader(const uint8_t* data, std::size_t size) : data_(data), size_(size) {}
    explicit BitReader(const std::vector<uint8_t>& v) : BitReader(v.data(), v.size()) {}

    uint32_t u(int bits, const char* field);
    bool flag(const char* field) { return u(1, field) != 0; }
    uint32_t ue(const char* field);
    int32_t se(const char* field);

    std::size_t bits_left() const { return size_ * 8 - pos_; }
    std::size_t bit_position() const { return pos_; }
    bool byte_aligned() const { return (pos_ & 7) == 0; }
    // True when the rest is empty, or is rbsp/payload trailing bits (a 1 then zeros) or zeros.
    bool only_trailing_bits_left() const;

private:
    [[noreturn]] void truncated(const char* field) const;
    const uint8_t* data_;
    std::size_t size_;
    std::size_t pos_ = 0;
};

class BitWriter {
public:
    void u(int bits, uint32_t value);
    void flag(bool v) { u(1, v ? 1 : 0); }
    void ue(uint32_t value);
    void se(int32_t value);
    // SEI payload style: a 1 bit then zeros up to the byte boundary (only if not aligned).
    void byte_align_with_stop_bit();
    void byte_align_zero();
    bool byte_aligned() const { return bits_ == 0; }
    std::size_t bit_count() const { return out_.size() * 8 - (bits_ ? std::size_t(8 - bits_) : 0); }
    const std::vector<uint8_t>& bytes() const { return out_; }

private:
    std::vector<uint8_t> out_;
    int bits_ = 0;  // bits used in the last byte
};

}  // namespace filmgrain
