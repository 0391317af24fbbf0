// libaom filmgrn1 grain table parser. A table that parses must survive
// format -> parse unchanged, and resolving every entry must not crash.
#include <cstdint>
#include <cstdlib>
#include <string_view>

#include "filmgrain/error.hpp"
#include "metadata/aom_grain_table.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    const std::string_view text(reinterpret_cast<const char*>(data), size);
    try {
        const filmgrain::AomGrainTable t = filmgrain::parse_aom_grain_table(text);
        for (std::size_t i = 0; i < t.entries.size(); ++i) {
            try {
                (void)t.resolved_params(i);
            } catch (const filmgrain::Error&) {
            }
        }
        const filmgrain::AomGrainTable again = filmgrain::parse_aom_grain_table(filmgrain::format_aom_grain_table(t));
        if (!(again.entries == t.entries)) std::abort();
    } catch (const filmgrain::Error&) {
    }
    return 0;
}
