#include "physical/gaussian_approximation.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <thread>

#include "filmgrain/error.hpp"
#include "physical/cell_random.hpp"
#include "physical/monte_carlo_estimators.hpp"

namespace filmgrain::physical {

namespace {
constexpr double kPi = 3.141592653589793;
constexpr double kCroppedEnergy = 1e-4;
constexpr int kMaxKernelRadius = 24;

int next_pow2(int v) {
    int p = 1;
    while (p < v) p <<= 1;
    return p;
}

// Even-symmetric 2-D cosine transform of a G x G grid indexed with wrap-around lags.
std::vector<double> even_transform(const std::vector<double>& in, int g) {
    std::vector<double> cs(std::size_t(g) * g), tmp(in.size()), out(in.size());
    for (int f = 0; f < g; f++)
        for (int d = 0; d < g; d++) cs[std::size_t(f) * g + d] = std::cos(2 * kPi * f * d / g);
    for (int y = 0; y < g; y++)
        for (int f = 0; f < g; f++) {
            double s = 0;
            for (int x = 0; x < g; x++) s += in[std::size_t(y) * g + x] * cs[std::size_t(f) * g + x];
            tmp[std::size_t(y) * g + f] = s;
        }
    for (int f = 0; f < g; f++)
        for (int fx = 0; fx < g; fx++) {
            double s = 0;
            for (int y = 0; y < g; y++) s += tmp[std::size_t(y) * g + fx] * cs[std::size_t(f) * g + y];
            out[std::size_t(f) * g + fx] = s;
        }
    return out;
}
}  // namespace

GaussianApproximation::GaussianApproximation(const BooleanModelParams& p, int levels)
    : p_(p), levels_(levels), base_(p, 0.5) {
    validate(p);
    if (levels < 2 || levels > 65536)
        throw Error(ErrorCode::kInvalidParams, "gaussian approximation: levels = " + std::to_string(levels) +
                                                   ", allowed range [2, 65536]");
    // Support of the filtered covariance in output pixels: the grain lens plus six
    // standard deviations of the doubled filter.
    const double support = (base_.coverage_support() + 6 * std::sqrt(2.0) * p.filter_sigma / p.zoom) * p.zoom;
    grid_ = std::clamp(next_pow2(int(std::ceil(4 * support)) + 4), 16, 256);
    radius_ = grid_ / 2 - 1;
    kernels_.resize(levels_);
    // The crop radius comes from the mid-grey kernel and holds for every level.
    const std::vector<float> mid = build_kernel(levels_ / 2);
    const int n = 2 * radius_ + 1;
    double total = 0;
    for (float v : mid) total += double(v) * v;
    int r = 0;
    for (; r < std::min(radius_, kMaxKernelRadius); r++) {
        double inside = 0;
        for (int y = -r; y <= r; y++)
            for (int x = -r; x <= r; x++) inside += double(mid[std::size_t(y + radius_) * n + x + radius_]) * mid[std::size_t(y + radius_) * n + x + radius_];
        if (total <= 0 || inside >= (1 - kCroppedEnergy) * total) break;
    }
    radius_ = r;
}

std::vector<float> GaussianApproximation::build_kernel(int level) const {
    const double u = double(level) / (levels_ - 1);
    const BooleanCovariance cov = base_.at_grey(u);
    const int g = grid_;
    std::map<int, double> by_distance2;
    std::vector<double> c(std::size_t(g) * g);
    for (int y = 0; y < g; y++)
        for (int x = 0; x < g; x++) {
            const int dx = x < g / 2 ? x : x - g, dy = y < g / 2 ? y : y - g;
            const int d2 = dx * dx + dy * dy;
            auto it = by_distance2.find(d2);
            if (it == by_distance2.end()) it = by_distance2.emplace(d2, cov.filtered(std::sqrt(double(d2)) / p_.zoom)).first;
            c[std::size_t(y) * g + x] = it->second;
        }
    std::vector<double> spectrum = even_transform(c, g);
    for (double& s : spectrum) s = std::sqrt(std::max(s, 0.0));
    const std::vector<double> h = even_transform(spectrum, g);
    const int R = radius_, n = 2 * R + 1;
    std::vector<float> k(std::size_t(n) * n);
    for (int y = -R; y <= R; y++)
        for (int x = -R; x <= R; x++)
            k[std::size_t(y + R) * n + x + R] = float(h[std::size_t((y + g) % g) * g + (x + g) % g] / (double(g) * g));
    return k;
}

const std::vector<float>& GaussianApproximation::kernel(int level) const {
    std::lock_guard<std::mutex> lock(mutex_);
    auto& slot = kernels_[std::clamp(level, 0, levels_ - 1)];
    if (!slot) slot = std::make_unique<std::vector<float>>(build_kernel(std::clamp(level, 0, levels_ - 1)));
    return *slot;
}

int GaussianApproximation::kernels_built() const {
    std::lock_guard<std::mutex> lock(mutex_);
    return int(std::count_if(kernels_.begin(), kernels_.end(), [](const auto& k) { return bool(k); }));
}

double GaussianApproximation::target_covariance(double u, double dx, double dy) const {
    return base_.at_grey(u).filtered_output_lag(dx, dy);
}

double GaussianApproximation::kernel_covariance(int level, int dx, int dy) const {
    const std::vector<float>& k = kernel(level);
    const int R = radius_, n = 2 * R + 1;
    double s = 0;
    for (int y = -R; y <= R; y++)
        for (int x = -R; x <= R; x++) {
            const int x2 = x + dx, y2 = y + dy;
            if (std::abs(x2) > R || std::abs(y2) > R) continue;
            s += double(k[std::size_t(y + R) * n + x + R]) * k[std::size_t(y2 + R) * n + x2 + R];
        }
    return s;
}

void GaussianApproximation::render(const FloatPlane& u, const OutputRegion& region_in, uint64_t seed,
                                   FloatPlane& out) const {
    if (u.width <= 0 || u.height <= 0 || u.v.size() != std::size_t(u.width) * u.height)
        throw Error(ErrorCode::kInvalidArgument, "gaussian approximation: empty or inconsistent input plane");
    const int full_w = zoomed_size(u.width, p_.zoom), full_h = zoomed_size(u.height, p_.zoom);
    OutputRegion r = region_in;
    if (r.w == 0 && r.h == 0) r = {0, 0, full_w, full_h};
    if (r.x < 0 || r.y < 0 || r.w <= 0 || r.h <= 0 || r.x + r.w > full_w || r.y + r.h > full_h)
        throw Error(ErrorCode::kInvalidArgument, "gaussian approximation: region is not inside the output picture");
    out = FloatPlane(r.w, r.h);
    const int R = radius_, n = 2 * R + 1;

    // Grey level (and kernel) of every output pixel; kernels only for the levels present.
    std::vector<float> grey(std::size_t(r.w) * r.h);
    std::vector<int> level(grey.size());
    std::vector<char> used(levels_, 0);
    for (int y = 0; y < r.h; y++) {
        const int iy = std::clamp(int(std::floor(output_to_input(r.y + y, p_.zoom))), 0, u.height - 1);
        for (int x = 0; x < r.w; x++) {
            const int ix = std::clamp(int(std::floor(output_to_input(r.x + x, p_.zoom))), 0, u.width - 1);
            float g = u.at(ix, iy);
            if (!(g > 0)) g = 0;
            g = std::min(g, 1.f);
            const std::size_t i = std::size_t(y) * r.w + x;
            grey[i] = g;
            level[i] = int(std::lround(g * (levels_ - 1)));
            used[level[i]] = 1;
        }
    }
    std::vector<const float*> kernel_of(levels_, nullptr);
    for (int l = 0; l < levels_; l++)
        if (used[l]) kernel_of[l] = kernel(l).data();

    // White noise keyed by global output coordinates: regions agree with the full picture.
    const int ww = r.w + 2 * R, wh = r.h + 2 * R;
    std::vector<float> white(std::size_t(ww) * wh);
    auto rows = [&](int y0, int y1, auto&& body) {
        const int nt = std::max(1, std::min(p_.threads, y1 - y0));
        std::vector<std::thread> pool;
        const int step = (y1 - y0 + nt - 1) / nt;
        for (int t = 1; t < nt; t++)
            pool.emplace_back([&, t]() { body(y0 + t * step, std::min(y1, y0 + (t + 1) * step)); });
        body(y0, std::min(y1, y0 + step));
        for (auto& th : pool) th.join();
    };
    rows(0, wh, [&](int a, int b) {
        for (int y = a; y < b; y++)
            for (int x = 0; x < ww; x++) {
                CellRandom rng(hash_coordinates(r.x - R + x, r.y - R + y, seed));
                white[std::size_t(y) * ww + x] = float(rng.normal());
            }
    });
    rows(0, r.h, [&](int a, int b) {
        for (int y = a; y < b; y++)
            for (int x = 0; x < r.w; x++) {
                const std::size_t i = std::size_t(y) * r.w + x;
                const float* k = kernel_of[level[i]];
                float s = 0;
                for (int ky = 0; ky < n; ky++) {
                    const float* wrow = &white[std::size_t(y + ky) * ww + x];
                    const float* krow = k + std::size_t(ky) * n;
                    for (int kx = 0; kx < n; kx++) s += krow[kx] * wrow[kx];
                }
                out.v[i] = grey[i] + s;
            }
    });
}

}  // namespace filmgrain::physical
