// Per-block measurements of the grain image over the flat regions, accumulated over the
// analysed pictures: (intensity, grain level) pairs for the scaling function, averaged 64x64
// DCT power per intensity range for the FGC cut-offs, and least-squares normal equations of
// the AV1 auto-regressive model.
#pragma once
#include <array>
#include <vector>

#include <opencv2/core.hpp>

namespace filmgrain::analysis {

// Blocks of the (intensity, level) observations, per model (ObservationRequest::level_block;
// each model's calibration measures with its own). AV1 takes small blocks: dark and bright
// areas of real pictures are often too small for 32x32 (a 48-sample-wide patch yields none),
// and the AV1 points, which follow the curve closely, missed the extreme bands. FGC keeps 32:
// its cut-off templates match a coarse grain's spectrum less closely than the AR filter
// does, and a 16x16 planar detrend removes more of the low frequencies both measure, so its
// calibration no longer cancels (strong coarse grain came out 8 % high).
inline constexpr int kFgcLevelBlock = 32;
inline constexpr int kAv1LevelBlock = 16;
// The AR fit needs longer rows than the level: its equations lose kMaxArLag samples per side
// and 16x16 blocks bias the normalized correlations low.
inline constexpr int kArBlock = 32;
inline constexpr int kDctBlock = 64;       // the FGC templates' transform size
inline constexpr int kPowerBins = 16;      // DCT power is kept per 16 8-bit intensity levels
inline constexpr int kMaxArLag = 3;
inline constexpr int kMaxArTerms = 2 * kMaxArLag * (kMaxArLag + 1) + 1;  // + the chroma's luma term

struct BlockSample {
    float intensity8;  // mean of the denoised block, 8-bit scale
    float sigma;       // grain standard deviation after planar trend removal, sample units
    // Mean of the co-located denoised luma, 8-bit scale (luma: intensity8). AV1 can index a
    // chroma plane's scaling by a mix of its own sample and the luma average (7.18.3.5).
    float luma8;
};

// The causal neighbours of the AV1 AR filter, in the order of AV1 7.18.3.3 for lag 3:
// rows -3..0, columns -3..3, up to (but excluding) the current sample.
struct ArOffset {
    int dy, dx;
};
const std::array<ArOffset, kMaxArTerms - 1>& ar_offsets_lag3();

// Normal equations sum(x x^T), sum(x y), sum(y^2) of y = a . x over normalized grain,
// with x the lag-3 neighbours and, for chroma, the co-located normalized luma grain last.
struct ArEquations {
    cv::Mat xtx = cv::Mat::zeros(kMaxArTerms, kMaxArTerms, CV_64F);
    cv::Mat xty = cv::Mat::zeros(kMaxArTerms, 1, CV_64F);
    double yty = 0.0;
    double n = 0.0;
};

// Products of detrended grain with itself shifted by k samples along each axis and by one
// sample along each diagonal, summed over blocks: the grain's autocorrelation at short lags,
// which FGC cut-offs are matched on.
inline constexpr int kMaxCorrelationLag = 3;
struct LagSums {
    std::array<double, kMaxCorrelationLag + 1> x{}, y{};              // [k]: sum g(x, y) g(x + k, y) / g(x, y + k)
    std::array<double, kMaxCorrelationLag + 1> x_pairs{}, y_pairs{};  // products summed
    std::array<double, 2> diagonal{}, diagonal_pairs{};               // [0]: lag (1,1), [1]: lag (1,-1)
    double energy = 0, samples = 0;
    void add(const LagSums& o);
    // Normalized autocorrelation at lag k (0 without observations).
    double rx(int k) const;
    double ry(int k) const;
    // ... at lag (1,1) (d = 0) or (1,-1) (d = 1).
    double rd(int d) const;
};

struct PlaneObservations {
    std::vector<BlockSample> blocks;  // ObservationRequest::level_block square
    std::array<cv::Mat, kPowerBins> dct_power;  // CV_64F 64x64 sums of squared coefficients
    std::array<int, kPowerBins> dct_blocks{};
    std::array<LagSums, kPowerBins> lags;       // over the same 64x64 blocks
    ArEquations ar;
    // Even and odd analysed pictures apart: two fits whose difference shows the fit's own noise
    // (grain realizations differ between pictures, not between blocks of one picture's template).
    std::array<ArEquations, 2> ar_halves;
    long long flat_samples = 0;
    long long total_samples = 0;
    // Samples outside the legal (studio) range and samples on its bounds: grain that never
    // leaves 16..235 (chroma 16..240) but piles up on the bounds was clipped there (AV1
    // clip_to_restricted_range; camera pipelines that clip in R'G'B' do the same to luma).
    long long outside_legal = 0, on_legal_bound = 0;
    PlaneObservations() {
        for (auto& m : dct_power) m = cv::Mat::zeros(kDctBlock, kDctBlock, CV_64F);
    }
    int total_dct_blocks() const {
        int n = 0;
        for (int c : dct_blocks) n += c;
        return n;
    }
};

struct ObservationRequest {
    bool dct_power = true;       // FGC cut-offs
    bool ar_equations = false;   // AV1 AR model
    int level_block = kFgcLevelBlock;  // kAv1LevelBlock for AV1
    int max_ar_blocks = 160;     // per picture and plane: enough equations, bounded time
    int half = 0;                // which of ar_halves this picture adds to
};

// Adds `part` (e.g. one picture's observations) to `total`: blocks appended, sums added.
// Pictures merged in the same order give the same sums, however they were gathered.
void merge_observations(PlaneObservations& total, const PlaneObservations& part);

// Counts `source`'s samples outside legal_min8..legal_max8 (8-bit scale) and on those bounds.
void count_legal_range(const cv::Mat& source, int bit_depth, int legal_min8, int legal_max8, PlaneObservations& out);

// The luma seen by a chroma plane, resampled to its size (empty for luma itself).
struct CoLocatedLuma {
    cv::Mat denoised;    // the denoised luma: each block's luma8
    cv::Mat normalized;  // the luma grain divided by its block level: the AR fit's luma term (may be empty)
};

// Adds one plane of one picture.
// Returns this plane's grain divided by its block level (for the chroma planes' luma term).
cv::Mat observe_plane(const cv::Mat& source, const cv::Mat& denoised, const cv::Mat& grain, const cv::Mat& usable,
                      int bit_depth, const CoLocatedLuma& luma, const ObservationRequest& request,
                      PlaneObservations& out);

// Grain standard deviation of a block after removing its least-squares plane.
double detrended_sigma(const cv::Mat& block, cv::Mat* residual);

// Lag sums of one block of grain after the same detrending as block_dct_power, without its
// DCT: what the cut-off calibration measures on synthesized grain.
void accumulate_block_lags(const cv::Mat& grain_block, LagSums& lags);

// Squared 64x64 DCT of a grain block after removing its plane (CV_64F), and its lag
// products added to `lags`: what the FGC observations sum.
cv::Mat block_dct_power(const cv::Mat& grain_block, LagSums* lags = nullptr);

// Lag products of one (detrended) block.
void accumulate_lags(const cv::Mat& residual, LagSums& sums);

}  // namespace filmgrain::analysis
