#include "analysis/observation_records.hpp"

#include <cstring>
#include <string>

#include "filmgrain/error.hpp"

namespace filmgrain::analysis {
namespace {

constexpr char kTag[8] = {'F', 'G', 'O', 'B', 'S', '0', '0', '5'};

class Writer {
public:
    template <typename T> void put(const T& v) {
        const auto* p = reinterpret_cast<const uint8_t*>(&v);
        out.insert(out.end(), p, p + sizeof(T));
    }
    void mat(const cv::Mat& m) {
        const cv::Mat c = m.isContinuous() ? m : m.clone();
        const auto* p = c.ptr<uint8_t>();
        out.insert(out.end(), p, p + c.total() * c.elemSize());
    }
    std::vector<uint8_t> out;
};

class Reader {
public:
    Reader(const uint8_t* d, std::size_t n) : data(d), size(n) {}
    template <typename T> T get(const char* what) {
        T v;
        need(sizeof(T), what);
        std::memcpy(&v, data + pos, sizeof(T));
        pos += sizeof(T);
        return v;
    }
    void mat(cv::Mat& m, const char* what) {
        const std::size_t n = m.total() * m.elemSize();
        need(n, what);
        std::memcpy(m.ptr<uint8_t>(), data + pos, n);
        pos += n;
    }
    void need(std::size_t n, const char* what) const {
        if (size - pos < n)
            throw Error(ErrorCode::kMalformedPayload, std::string("observation record: truncated in ") + what + " (" +
                                                          std::to_string(size) + " bytes)");
    }
    const uint8_t* data;
    std::size_t size, pos = 0;
};

}  // namespace

std::vector<uint8_t> serialize_picture_observations(const PictureObservations& picture) {
    Writer w;
    for (char c : kTag) w.put(c);
    w.put<int32_t>(picture.index);
    w.put<int64_t>(picture.flat_samples);
    w.put<int64_t>(picture.reliable_samples);
    for (const PlaneObservations& p : picture.planes) {
        w.put<uint64_t>(p.blocks.size());
        for (const BlockSample& b : p.blocks) {
            w.put(b.intensity8);
            w.put(b.sigma);
            w.put(b.luma8);
        }
        for (int b = 0; b < kPowerBins; b++) {
            w.put<int32_t>(p.dct_blocks[b]);
            if (!p.dct_blocks[b]) continue;  // only the bins that hold blocks
            w.mat(p.dct_power[b]);
            const LagSums& l = p.lags[b];
            for (const auto* a : {&l.x, &l.y, &l.x_pairs, &l.y_pairs})
                for (double v : *a) w.put<double>(v);
            for (const auto* a : {&l.diagonal, &l.diagonal_pairs})
                for (double v : *a) w.put<double>(v);
            w.put<double>(l.energy);
            w.put<double>(l.samples);
        }
        for (const ArEquations& e : p.ar_halves) {
            w.mat(e.xtx);
            w.mat(e.xty);
            w.put(e.yty);
            w.put(e.n);
        }
        w.put<int64_t>(p.flat_samples);
        w.put<int64_t>(p.total_samples);
        w.put<int64_t>(p.outside_legal);
        w.put<int64_t>(p.on_legal_bound);
    }
    return std::move(w.out);
}

PictureObservations deserialize_picture_observations(const uint8_t* data, std::size_t size) {
    Reader r(data, size);
    for (char c : kTag)
        if (r.get<char>("the tag") != c)
            throw Error(ErrorCode::kMalformedPayload, "observation record: not a filmgrain observation record (tag)");
    PictureObservations pic;
    pic.index = r.get<int32_t>("index");
    pic.flat_samples = r.get<int64_t>("flat_samples");
    pic.reliable_samples = r.get<int64_t>("reliable_samples");
    for (PlaneObservations& p : pic.planes) {
        const uint64_t n = r.get<uint64_t>("block count");
        if (n > (r.size - r.pos) / (3 * sizeof(float)))
            throw Error(ErrorCode::kMalformedPayload, "observation record: block count " + std::to_string(n) +
                                                          " exceeds the record's " + std::to_string(r.size) + " bytes");
        p.blocks.resize(n);
        for (BlockSample& b : p.blocks) {
            b.intensity8 = r.get<float>("blocks");
            b.sigma = r.get<float>("blocks");
            b.luma8 = r.get<float>("blocks");
        }
        for (int b = 0; b < kPowerBins; b++) {
            p.dct_blocks[b] = r.get<int32_t>("dct_blocks");
            if (p.dct_blocks[b] < 0)
                throw Error(ErrorCode::kMalformedPayload,
                            "observation record: dct_blocks = " + std::to_string(p.dct_blocks[b]) + " (allowed 0..)");
            if (!p.dct_blocks[b]) continue;
            r.mat(p.dct_power[b], "dct_power");
            LagSums& l = p.lags[b];
            for (auto* a : {&l.x, &l.y, &l.x_pairs, &l.y_pairs})
                for (double& v : *a) v = r.get<double>("lag sums");
            for (auto* a : {&l.diagonal, &l.diagonal_pairs})
                for (double& v : *a) v = r.get<double>("lag sums");
            l.energy = r.get<double>("lag sums");
            l.samples = r.get<double>("lag sums");
        }
        for (ArEquations& e : p.ar_halves) {
            r.mat(e.xtx, "ar xtx");
            r.mat(e.xty, "ar xty");
            e.yty = r.get<double>("ar yty");
            e.n = r.get<double>("ar n");
        }
        p.ar.xtx = p.ar_halves[0].xtx + p.ar_halves[1].xtx;
        p.ar.xty = p.ar_halves[0].xty + p.ar_halves[1].xty;
        p.ar.yty = p.ar_halves[0].yty + p.ar_halves[1].yty;
        p.ar.n = p.ar_halves[0].n + p.ar_halves[1].n;
        p.flat_samples = r.get<int64_t>("flat_samples");
        p.total_samples = r.get<int64_t>("total_samples");
        p.outside_legal = r.get<int64_t>("outside_legal");
        p.on_legal_bound = r.get<int64_t>("on_legal_bound");
    }
    if (r.pos != r.size)
        throw Error(ErrorCode::kMalformedPayload, "observation record: " + std::to_string(r.size - r.pos) +
                                                      " bytes after the record's end");
    return pic;
}

}  // namespace filmgrain::analysis
