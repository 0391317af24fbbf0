#include "metadata/bit_reader.hpp"

#include <cstdint>

namespace filmgrain {

void BitReader::truncated(const char* field) const {
    throw Error(ErrorCode::kMalformedPayload, std::string("payload truncated while reading ") + field + " (at bit " +
                                                  std::to_string(pos_) + " of " + std::to_string(size_ * 8) + ")");
}

uint32_t BitReader::u(int bits, const char* field) {
    if (bits == 0) return 0;
    if (std::size_t(bits) > bits_left()) truncated(field);
    uint32_t v = 0;
    for (int i = 0; i < bits; i++, pos_++) v = (v << 1) | ((data_[pos_ >> 3] >> (7 - (pos_ & 7))) & 1u);
    return v;
}

uint32_t BitReader::ue(const char* field) {
    int zeros = 0;
    while (true) {
        if (bits_left() == 0) truncated(field);
        if (u(1, field)) break;
        if (++zeros > 31)
            throw Error(ErrorCode::kMalformedPayload,
                        std::string("Exp-Golomb code of ") + field + " has more than 31 leading zero bits (value too large)");
    }
    uint64_t v = (uint64_t(1) << zeros) - 1 + u(zeros, field);
    if (v > 0xFFFFFFFEull)
        throw Error(ErrorCode::kMalformedPayload, std::string("Exp-Golomb value of ") + field + " exceeds 2^32 - 2");
    return uint32_t(v);
}

int32_t BitReader::se(const char* field) {
    uint32_t k = ue(field);
    int64_t v = (k & 1) ? (int64_t(k) + 1) / 2 : -(int64_t(k) / 2);
    return int32_t(v);
}

bool BitReader::only_trailing_bits_left() const {
    std::size_t p = pos_;
    bool seen_stop = false;
    for (; p < size_ * 8; p++) {
        int bit = (data_[p >> 3] >> (7 - (p & 7))) & 1;
        if (bit) {
            if (seen_stop) return false;
            seen_stop = true;
        }
    }
    return true;
}

void BitWriter::u(int bits, uint32_t value) {
    for (int i = bits - 1; i >= 0; i--) {
        if (bits_ == 0) out_.push_back(0);
        if ((value >> i) & 1) out_.back() |= uint8_t(0x80 >> bits_);
        bits_ = (bits_ + 1) & 7;
    }
}

void BitWriter::ue(uint32_t value) {
    // 2^32 - 1 would need 32 leading zeros, which no reader (this one included) accepts.
    if (value == 0xFFFFFFFFu)
        throw Error(ErrorCode::kInvalidParams, out_of_range_message("an ue(v) value", value, 0, 0xFFFFFFFEll));
    uint64_t v = uint64_t(value) + 1;
    int len = 0;
    while ((v >> len) > 1) len++;
    u(len, 0);
    for (int i = len; i >= 0; i--) u(1, uint32_t((v >> i) & 1));
}

void BitWriter::se(int32_t value) {
    // INT32_MIN maps to code number 2^32, one more than ue(v) carries.
    if (value == INT32_MIN)
        throw Error(ErrorCode::kInvalidParams, out_of_range_message("an se(v) value", value, -0x7FFFFFFFll, 0x7FFFFFFFll));
    uint32_t k = value > 0 ? uint32_t(2 * int64_t(value) - 1) : uint32_t(-2 * int64_t(value));
    ue(k);
}

void BitWriter::byte_align_with_stop_bit() {
    if (bits_ == 0) return;
    u(1, 1);
    while (bits_) u(1, 0);
}

void BitWriter::byte_align_zero() {
    while (bits_) u(1, 0);
}

}  // namespace filmgrain
