// The message of the filmgrain::Error a call throws, for tests that check what an error
// names: "" when the call throws none.
#pragma once
#include <string>

#include "filmgrain/error.hpp"

namespace filmgrain::test_support {

template <typename Call>
std::string error_of(Call&& call) {
    try {
        call();
    } catch (const Error& e) {
        return e.what();
    }
    return "";
}

}  // namespace filmgrain::test_support
