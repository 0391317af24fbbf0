// The Boolean model's Monte Carlo offsets in the tradeoff report: how isotropic the output of
// one plane is and how near its variance is to the closed-form limit, at every N, for the
// renderer's offsets and for independent Gaussian draws.
#pragma once
#include <string>
#include <vector>

#include "physical/boolean_model.hpp"

namespace filmgrain::cli {

// A Markdown section. `content_side`: the flat picture the rendered-output rows measure.
std::string boolean_offsets_section(const physical::BooleanModelParams& p, double grey, const std::vector<int>& ns,
                                    int content_side);

}  // namespace filmgrain::cli
