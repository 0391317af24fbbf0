#include "io/file_pattern.hpp"

#include <string_view>

namespace filmgrain::io {

std::optional<FilePattern> FilePattern::parse(const std::string& name) {
    FilePattern p;
    p.text_ = name;
    bool found = false;
    std::string literal;
    for (std::size_t i = 0; i < name.size(); i++) {
        if (name[i] != '%') {
            literal.push_back(name[i]);
            continue;
        }
        if (i + 1 < name.size() && name[i + 1] == '%') {
            literal.push_back('%');
            i++;
            continue;
        }
        // %[0][width](d|u|i)
        std::size_t j = i + 1;
        bool zero = j < name.size() && name[j] == '0';
        if (zero) j++;
        const std::size_t digits_start = j;
        while (j < name.size() && name[j] >= '0' && name[j] <= '9' && j - digits_start < 3) j++;
        if (j >= name.size() || (name[j] != 'd' && name[j] != 'u' && name[j] != 'i') || found) return std::nullopt;
        const std::string_view width(name.data() + digits_start, j - digits_start);
        if (width.size() > 2) return std::nullopt;
        p.width_ = 0;
        for (char d : width) p.width_ = p.width_ * 10 + (d - '0');
        p.zero_pad_ = zero;
        p.prefix_ = literal;
        literal.clear();
        found = true;
        i = j;
    }
    if (!found) return std::nullopt;
    p.suffix_ = literal;
    return p;
}

std::string FilePattern::name_for(long long k) const {
    std::string number = std::to_string(k);
    if (int(number.size()) < width_) number.insert(0, std::size_t(width_) - number.size(), zero_pad_ ? '0' : ' ');
    return prefix_ + number + suffix_;
}

}  // namespace filmgrain::io
