#include "tradeoff_offsets.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "physical/boolean_covariance.hpp"
#include "physical/monte_carlo_offsets.hpp"
#include "stats/grain_statistics.hpp"
#include "tradeoff_methods.hpp"

namespace filmgrain::cli {

namespace {

constexpr int kFrames = 4;
constexpr int kMaxLag = 3;

struct OffsetFigures {
    double worst_h_minus_v = 0;  // max over lags 1..3 of |C(l,0) - C(0,l)|, relative to the limit's variance
    double var_lo = 1e300, var_hi = 0;  // realized variance / limit, over frames
};

OffsetFigures figures(const physical::BooleanCovariance& cov, const std::vector<std::vector<double>>& sets) {
    OffsetFigures f;
    const double limit = cov.filtered(0);
    for (const auto& xi : sets) {
        for (int l = 1; l <= kMaxLag; l++)
            f.worst_h_minus_v =
                std::max(f.worst_h_minus_v, std::abs(cov.given_offsets(l, 0, xi) - cov.given_offsets(0, l, xi)) / limit);
        const double v = cov.given_offsets(0, 0, xi) / limit;
        f.var_lo = std::min(f.var_lo, v);
        f.var_hi = std::max(f.var_hi, v);
    }
    return f;
}

}  // namespace

std::string boolean_offsets_section(const physical::BooleanModelParams& p, double grey, const std::vector<int>& ns,
                                    int content_side) {
    const physical::BooleanCovariance cov(p, grey);
    std::ostringstream md;
    md << "## Boolean model: isotropy and variance against the closed form\n\n"
       << "The N Monte Carlo offsets are shared by every pixel of a plane, so each plane's grain carries the realized "
       << "filter of its own offsets. For given offsets the output's covariance is known in closed form, "
       << "(1/N^2) sum_{k,l} C(d + xi_k - xi_l), so these figures have no sampling error of their own. "
       << "Each row takes " << kFrames << " planes (seeds 1.." << kFrames
       << "): **|H - V|** is the largest |C(l,0) - C(0,l)| over lags l = 1.." << kMaxLag
       << " and planes, as a fraction of the N -> infinity variance C_sigma(0); **variance / limit** is the realized "
       << "variance C(0,0) over C_sigma(0), smallest..largest over the planes. The renderer's offsets are a randomly "
       << "shifted R2 low-discrepancy set mapped through the normal quantile function (src/physical/"
       << "monte_carlo_offsets.hpp); independent Gaussian draws (the renderer before, and the Monte Carlo error the "
       << "issue's isotropy criterion names) are shown beside them. For independent draws the expected variance / limit is "
       << "1 + (C(0) - C_sigma(0)) / (N C_sigma(0)).\n\n"
       << "| N | \\|H - V\\|, renderer | \\|H - V\\|, independent | variance / limit, renderer | variance / limit, "
          "independent | expected, independent |\n|---|---|---|---|---|---|\n";
    for (int n : ns) {
        std::vector<std::vector<double>> ours, iid;
        for (int s = 1; s <= kFrames; s++) {
            ours.push_back(physical::monte_carlo_offsets(p, uint64_t(s), n));
            iid.push_back(physical::independent_gaussian_offsets(p, 1000 + uint64_t(s), n));
        }
        const OffsetFigures a = figures(cov, ours), b = figures(cov, iid);
        const double expected = 1 + (cov.coverage(0) - cov.filtered(0)) / (n * cov.filtered(0));
        md << "| " << n << " | " << fixed_decimals(a.worst_h_minus_v, 4) << " | " << fixed_decimals(b.worst_h_minus_v, 4) << " | "
           << fixed_decimals(a.var_lo, 4) << "..." << fixed_decimals(a.var_hi, 4) << " | " << fixed_decimals(b.var_lo, 4) << "..."
           << fixed_decimals(b.var_hi, 4) << " | " << fixed_decimals(expected, 4) << " |\n";
    }
    // The same on rendered output, as a user would measure it (with the spatial sampling error
    // of one picture on top).
    physical::BooleanModelParams rp = p;
    rp.samples = 800;
    const FloatPlane u(content_side, content_side, float(grey));
    md << "\nMeasured on rendered output (" << content_side << "x" << content_side << ", N = 800), correlation "
       << "H / V at lags 1.." << kMaxLag << "; closed form (N -> infinity):";
    for (int l = 1; l <= kMaxLag; l++) md << " " << fixed_decimals(cov.filtered_output_lag(l, 0) / cov.filtered(0), 3);
    md << "\n\n| plane seed | lag 1 H / V | lag 2 H / V | lag 3 H / V |\n|---|---|---|---|\n";
    for (int s = 0; s < 2; s++) {
        FloatPlane out;
        physical::render_boolean_model(u, rp, {}, uint64_t(s), out);
        md << "| " << s;
        const stats::Autocovariance c = stats::autocovariance(out, kMaxLag);
        for (int l = 1; l <= kMaxLag; l++)
            md << " | " << fixed_decimals(c.at(l, 0) / c.at(0, 0), 3) << " / " << fixed_decimals(c.at(0, l) / c.at(0, 0), 3);
        md << " |\n";
    }
    return md.str();
}

}  // namespace filmgrain::cli
