// RFC 1321 MD5, used to compare frames with the conformance goldens (which are MD5s).
#pragma once
#include <cstddef>
#include <cstdint>
#include <string>

namespace filmgrain {

class Md5 {
public:
    Md5();
    void update(const void* data, std::size_t len);
    std::string hex_digest();  // finalizes

private:
    void block(const uint8_t* p);
    uint32_t h_[4];
    uint64_t total_ = 0;
    uint8_t buf_[64];
    std::size_t used_ = 0;
};

std::string md5_hex(const void* data, std::size_t len);

}  // namespace filmgrain
