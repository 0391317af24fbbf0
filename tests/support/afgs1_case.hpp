// The afgs1 conformance family (conformance/afgs1-*, README "Family afgs1"): each picture's
// AFGS1 T.35 payload file (afgs1_<k>.bin, k = output order; missing = no payload) through a
// stream session, as a decoder hands them over.
#pragma once
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "conformance_case.hpp"
#include "filmgrain/session.hpp"

namespace filmgrain::test_support {

// The payload of picture k, or nothing when that access unit carried none.
std::optional<std::vector<uint8_t>> afgs1_payload(const ConformanceCase& c, int k);

// Every picture through one Session with `options` (in place when `in_place`); the number of
// pictures whose output differs from expected_md5 (each reported as a test failure).
int run_afgs1_case(const ConformanceCase& c, const SessionOptions& options, bool in_place);

}  // namespace filmgrain::test_support
