#include "stats/grain_statistics.hpp"

#include <algorithm>
#include <cmath>

#include "filmgrain/error.hpp"

namespace filmgrain::stats {

namespace {
constexpr double kPi = 3.141592653589793;

double mean_of(const FloatPlane& f) {
    double s = 0;
    for (float v : f.v) s += v;
    return f.v.empty() ? 0 : s / double(f.v.size());
}

// sum over the overlap of (a(x) - m)(a(x + d) - m) / number of pairs
double lag_covariance(const FloatPlane& g, double m, int dx, int dy) {
    const int x0 = std::max(0, -dx), x1 = std::min(g.width, g.width - dx);
    const int y0 = std::max(0, -dy), y1 = std::min(g.height, g.height - dy);
    if (x1 <= x0 || y1 <= y0) return 0;
    double s = 0;
    for (int y = y0; y < y1; y++) {
        const float* a = &g.v[std::size_t(y) * g.width];
        const float* b = &g.v[std::size_t(y + dy) * g.width + dx];
        double row = 0;
        for (int x = x0; x < x1; x++) row += (double(a[x]) - m) * (double(b[x]) - m);
        s += row;
    }
    return s / (double(x1 - x0) * (y1 - y0));
}
}  // namespace

FloatPlane grain_of(const FloatPlane& clean, const FloatPlane& grainy) {
    if (clean.width != grainy.width || clean.height != grainy.height)
        throw Error(ErrorCode::kInvalidArgument, "stats: clean is " + std::to_string(clean.width) + "x" +
                                                     std::to_string(clean.height) + " but grainy is " +
                                                     std::to_string(grainy.width) + "x" + std::to_string(grainy.height));
    FloatPlane g(clean.width, clean.height);
    for (std::size_t i = 0; i < g.v.size(); i++) g.v[i] = grainy.v[i] - clean.v[i];
    return g;
}

std::vector<IntensityBin> variance_vs_intensity(const FloatPlane& clean, const FloatPlane& grain, int bins) {
    std::vector<IntensityBin> out(std::max(1, bins));
    std::vector<double> s1(out.size()), s2(out.size());
    for (std::size_t i = 0; i < out.size(); i++) {
        out[i].lo = double(i) / out.size();
        out[i].hi = double(i + 1) / out.size();
    }
    for (std::size_t i = 0; i < grain.v.size(); i++) {
        const int b = std::clamp(int(clean.v[i] * out.size()), 0, int(out.size()) - 1);
        out[b].count++;
        s1[b] += grain.v[i];
        s2[b] += double(grain.v[i]) * grain.v[i];
    }
    for (std::size_t b = 0; b < out.size(); b++)
        if (out[b].count) {
            out[b].mean = s1[b] / out[b].count;
            out[b].variance = std::max(0.0, s2[b] / out[b].count - out[b].mean * out[b].mean);
        }
    return out;
}

Autocovariance autocovariance(const FloatPlane& grain, int max_lag) {
    Autocovariance c;
    c.max_lag = max_lag;
    const int n = 2 * max_lag + 1;
    c.values.assign(std::size_t(n) * n, 0);
    const double m = mean_of(grain);
    // C(d) = C(-d): compute half the table.
    for (int dy = 0; dy <= max_lag; dy++)
        for (int dx = -max_lag; dx <= max_lag; dx++) {
            if (dy == 0 && dx < 0) continue;
            const double v = lag_covariance(grain, m, dx, dy);
            c.values[std::size_t(dy + max_lag) * n + (dx + max_lag)] = v;
            c.values[std::size_t(-dy + max_lag) * n + (-dx + max_lag)] = v;
        }
    return c;
}

PowerSpectrum power_spectrum(const FloatPlane& grain, int block) {
    PowerSpectrum ps;
    ps.block = block;
    const int b = block;
    ps.values.assign(std::size_t(b) * b, 0);
    std::vector<double> cs(std::size_t(b) * b), sn(cs.size());
    for (int f = 0; f < b; f++)
        for (int x = 0; x < b; x++) {
            cs[std::size_t(f) * b + x] = std::cos(2 * kPi * f * x / b);
            sn[std::size_t(f) * b + x] = -std::sin(2 * kPi * f * x / b);
        }
    std::vector<double> tile(std::size_t(b) * b), re(tile.size()), im(tile.size());
    int tiles = 0;
    for (int ty = 0; ty + b <= grain.height; ty += b)
        for (int tx = 0; tx + b <= grain.width; tx += b) {
            double m = 0;
            for (int y = 0; y < b; y++)
                for (int x = 0; x < b; x++) m += tile[std::size_t(y) * b + x] = grain.at(tx + x, ty + y);
            m /= double(b) * b;
            for (double& v : tile) v -= m;
            // rows, then columns
            for (int y = 0; y < b; y++)
                for (int f = 0; f < b; f++) {
                    double r = 0, i = 0;
                    for (int x = 0; x < b; x++) {
                        r += tile[std::size_t(y) * b + x] * cs[std::size_t(f) * b + x];
                        i += tile[std::size_t(y) * b + x] * sn[std::size_t(f) * b + x];
                    }
                    re[std::size_t(y) * b + f] = r;
                    im[std::size_t(y) * b + f] = i;
                }
            for (int fy = 0; fy < b; fy++)
                for (int fx = 0; fx < b; fx++) {
                    double r = 0, i = 0;
                    for (int y = 0; y < b; y++) {
                        const double c = cs[std::size_t(fy) * b + y], s = sn[std::size_t(fy) * b + y];
                        const double ar = re[std::size_t(y) * b + fx], ai = im[std::size_t(y) * b + fx];
                        r += ar * c - ai * s;
                        i += ar * s + ai * c;
                    }
                    ps.values[std::size_t(fy) * b + fx] += (r * r + i * i) / (double(b) * b);
                }
            tiles++;
        }
    if (tiles)
        for (double& v : ps.values) v /= tiles;
    ps.radial.assign(b / 2 + 1, 0);
    std::vector<int> count(ps.radial.size(), 0);
    for (int fy = 0; fy < b; fy++)
        for (int fx = 0; fx < b; fx++) {
            const int ux = fx <= b / 2 ? fx : fx - b, uy = fy <= b / 2 ? fy : fy - b;
            const int r = int(std::lround(std::hypot(ux, uy)));
            if (r <= b / 2) {
                ps.radial[r] += ps.values[std::size_t(fy) * b + fx];
                count[r]++;
            }
        }
    for (std::size_t r = 0; r < ps.radial.size(); r++)
        if (count[r]) ps.radial[r] /= count[r];
    return ps;
}

GrainSize grain_size(const Autocovariance& c) {
    GrainSize g;
    const double c0 = c.at(0, 0);
    if (!(c0 > 0)) return g;
    auto crossing = [&](bool along_x) {
        double prev = 1;
        for (int d = 1; d <= c.max_lag; d++) {
            const double rho = (along_x ? c.at(d, 0) : c.at(0, d)) / c0;
            if (rho < std::exp(-1.0)) return (d - 1) + (prev - std::exp(-1.0)) / (prev - rho);
            prev = rho;
        }
        return double(c.max_lag);
    };
    g.correlation_length = 0.5 * (crossing(true) + crossing(false));
    double area = 0;
    for (double v : c.values) area += v / c0;
    g.equivalent_diameter = 2 * std::sqrt(std::max(area, 0.0) / kPi);
    return g;
}

BoundaryVariance block_boundary_variance(const FloatPlane& grain, int block) {
    // a block needs a boundary and an interior: 2 samples at least
    if (block < 2 || block > 4096)
        throw Error(ErrorCode::kInvalidArgument, out_of_range_message("stats: block size", block, 2, 4096));
    BoundaryVariance r;
    r.block = block;
    const double m = mean_of(grain);
    double bc = 0, ic = 0, br = 0, ir = 0;
    long long nbc = 0, nic = 0, nbr = 0, nir = 0;
    for (int y = 0; y < grain.height; y++) {
        const bool row_edge = (y % block == 0) || (y % block == block - 1);
        for (int x = 0; x < grain.width; x++) {
            const double d = grain.at(x, y) - m, d2 = d * d;
            const bool col_edge = (x % block == 0) || (x % block == block - 1);
            if (col_edge) bc += d2, nbc++;
            else ic += d2, nic++;
            if (row_edge) br += d2, nbr++;
            else ir += d2, nir++;
        }
    }
    r.boundary_columns = nbc ? bc / nbc : 0;
    r.interior_columns = nic ? ic / nic : 0;
    r.boundary_rows = nbr ? br / nbr : 0;
    r.interior_rows = nir ? ir / nir : 0;
    return r;
}

std::vector<RepetitionPeak> repetition_at_periods(const FloatPlane& grain, const std::vector<int>& periods) {
    std::vector<RepetitionPeak> out;
    const double m = mean_of(grain);
    const double c0 = lag_covariance(grain, m, 0, 0);
    for (int p : periods)
        if (p < 1 || p > 65536)
            throw Error(ErrorCode::kInvalidArgument, out_of_range_message("stats: template period", p, 1, 65536));
    for (int p : periods)
        for (auto [dx, dy] : {std::pair{p, 0}, {0, p}, {p, p}}) {
            const double c = (c0 > 0 && dx < grain.width && dy < grain.height) ? lag_covariance(grain, m, dx, dy) / c0 : 0;
            out.push_back({dx, dy, c});
        }
    return out;
}

std::vector<RepetitionPeak> strongest_repetitions(const FloatPlane& grain, int min_lag, int max_lag, int count) {
    std::vector<int> periods;
    for (int p = min_lag; p <= max_lag; p++) periods.push_back(p);
    std::vector<RepetitionPeak> all = repetition_at_periods(grain, periods);
    std::sort(all.begin(), all.end(), [](const RepetitionPeak& a, const RepetitionPeak& b) { return a.correlation > b.correlation; });
    if (int(all.size()) > count) all.resize(count);
    return all;
}

double frame_to_frame_correlation(const FloatPlane& a, const FloatPlane& b) {
    if (a.width != b.width || a.height != b.height)
        throw Error(ErrorCode::kInvalidArgument, "stats: frames of different sizes");
    const double ma = mean_of(a), mb = mean_of(b);
    double sab = 0, saa = 0, sbb = 0;
    for (std::size_t i = 0; i < a.v.size(); i++) {
        const double x = a.v[i] - ma, y = b.v[i] - mb;
        sab += x * y;
        saa += x * x;
        sbb += y * y;
    }
    return (saa > 0 && sbb > 0) ? sab / std::sqrt(saa * sbb) : 0;
}

}  // namespace filmgrain::stats
