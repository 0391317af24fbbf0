// FGC SEI frequency-filtering conformance through the library: every conformance/vtm_*
// and rdd5_* case, decoder style (the SEI payload of each access unit parsed from
// frameK.fgc.bin and handed to one FgcStreamSynthesis in output order), and again with the
// case.json parameters, which must describe the same SEI.
#include <gtest/gtest.h>

#include <filesystem>
#include <optional>

#include "conformance_case.hpp"
#include "core/md5.hpp"
#include "fgc/fgc_stream_synthesis.hpp"
#include "io/xz_file.hpp"
#include "metadata/fgc_json.hpp"
#include "metadata/fgc_sei.hpp"

using namespace filmgrain;
using namespace filmgrain::test_support;
namespace fs = std::filesystem;

namespace {

std::vector<std::string> fgc_cases() {
    auto v = list_cases("vtm_");
    auto r = list_cases("rdd5_");
    v.insert(v.end(), r.begin(), r.end());
    return v;
}

enum class Source { kSeiPayload, kCaseJson };

// flavour_override: run the case through another flavour that must give the same pictures
// (tr on the rdd5 cases: the tr flavour is the rdd5 arithmetic where rdd5 accepts the SEI).
void run(const std::string& name, Source source, FgcPersistence persistence,
         std::optional<FgcFlavour> flavour_override = std::nullopt) {
    const ConformanceCase c = load_case(name);
    const bool avc = c.json.at("codec") == "h264";
    const FgcCodec codec = avc ? FgcCodec::kAvc : FgcCodec::kHevc;
    FgcOptions opt;
    opt.flavour = c.json.at("family") == "vtm" ? FgcFlavour::kVtm : FgcFlavour::kRdd5;
    const FgcFlavour family_flavour = opt.flavour;
    if (flavour_override) opt.flavour = *flavour_override;
    opt.passthrough_invalid = true;  // the references output the clean picture
    opt.persistence = persistence;
    FgcStreamSynthesis synth(opt);
    FgcStreamSynthesis synth_in_place(opt);  // the same stream, every picture synthesized in place
    int mismatches = 0;
    for (int k = 0; k < c.frames; k++) {
        const auto& fi = c.frame_info(k);
        if (fi.at("sei_present").get<bool>()) {
            const fs::path bin = fs::path(c.dir) / ("frame" + std::to_string(k) + ".fgc.bin");
            ASSERT_TRUE(fs::exists(bin)) << bin;
            FgcParams from_sei = parse_fgc_sei_payload(read_whole_file(bin.string()), codec);
            FgcParams from_json = fgc_params_from_json(fi.at("params").at("fgc"));
            // The parser and the JSON reader must agree on every syntax element.
            EXPECT_EQ(fgc_params_to_json(from_sei), fgc_params_to_json(from_json)) << name << " frame " << k;
            // And the writer must reproduce the payload byte for byte.
            EXPECT_EQ(write_fgc_sei_payload(from_sei, codec), read_whole_file(bin.string())) << name << " frame " << k;
            synth.receive_sei(source == Source::kSeiPayload ? from_sei : from_json, codec);
            synth_in_place.receive_sei(source == Source::kSeiPayload ? from_sei : from_json, codec);
        }
        FgcPictureIds ids;
        ids.poc = fi.at("poc").get<int>();
        ids.idr_pic_id = fi.at("idr_pic_id").is_null() ? 0 : fi.at("idr_pic_id").get<int>();
        if (family_flavour == FgcFlavour::kRdd5) {
            EXPECT_EQ(ids.poc + (ids.idr_pic_id << 5), fi.at("pic_offset").get<int>());
        }
        FrameBuffer in = c.input_frame(k), out(c.width, c.height, c.format);
        synth.apply(in.view(), out.view(), ids);
        std::string want = c.expected_md5(k);
        // Under the SEI semantics a picture after a persistence_flag = 0 SEI gets no grain;
        // HM applies it anyway (conformance/README.md caveat 3).
        if (persistence == FgcPersistence::kSemantic && fi.value("reference_specific", false))
            want = fi.at("clean_md5").get<std::string>();
        const std::string got = md5_hex(out.bytes(), out.byte_size());
        if (got != want) {
            mismatches++;
            ADD_FAILURE() << (want == c.expected_md5(k) ? describe_mismatch(c, k, out.bytes(), out.byte_size())
                                                        : name + " frame " + std::to_string(k) + " != clean_md5");
        }
        // The same picture in place gives the same output.
        FrameBuffer inplace = c.input_frame(k);
        synth_in_place.apply(inplace.view(), inplace.view(), ids);
        EXPECT_EQ(md5_hex(inplace.bytes(), inplace.byte_size()), got) << name << " frame " << k << ": in place differs";
    }
    EXPECT_EQ(mismatches, 0);
}

class FgcConformance : public ::testing::TestWithParam<std::string> {};

TEST_P(FgcConformance, SeiPayloadsThroughLibrary) { run(GetParam(), Source::kSeiPayload, FgcPersistence::kReference); }
TEST_P(FgcConformance, CaseJsonThroughLibrary) { run(GetParam(), Source::kCaseJson, FgcPersistence::kReference); }

INSTANTIATE_TEST_SUITE_P(Cases, FgcConformance, ::testing::ValuesIn(fgc_cases()),
                         [](const auto& info) { return info.param; });

// The tr flavour must reproduce every rdd5 golden: it is the rdd5 arithmetic wherever rdd5
// accepts the SEI, and only adds what rdd5 rejects.
class FgcConformanceTr : public ::testing::TestWithParam<std::string> {};
TEST_P(FgcConformanceTr, Rdd5GoldensThroughTrFlavour) {
    run(GetParam(), Source::kSeiPayload, FgcPersistence::kReference, FgcFlavour::kTr);
}
INSTANTIATE_TEST_SUITE_P(Cases, FgcConformanceTr, ::testing::ValuesIn(list_cases("rdd5_")),
                         [](const auto& info) { return info.param; });

TEST(FgcConformanceSet, AllCasesPresent) { EXPECT_EQ(fgc_cases().size(), 16u); }

TEST(FgcConformanceSemantic, PersistenceFlagZeroGivesCleanNextPicture) {
    run("vtm_352x288_420p8_invalid_mix", Source::kSeiPayload, FgcPersistence::kSemantic);
}

}  // namespace
