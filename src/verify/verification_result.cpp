#include "verify/verification_result.hpp"

namespace filmgrain::verify {

int VerificationResult::mismatching() const {
    int n = 0;
    for (const FrameVerification& f : frames) n += !f.missing && !f.exact;
    return n;
}

int VerificationResult::missing() const {
    int n = 0;
    for (const FrameVerification& f : frames) n += f.missing;
    return n;
}

}  // namespace filmgrain::verify
