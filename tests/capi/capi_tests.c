/* Tests of the C API, in C, through the shared library: layouts (padded and negative
 * strides), in place against out of place, odd sizes, every chroma format and bit depth,
 * error codes with messages naming the field, SEI matching by picture ids, persistence,
 * AV1 reference slots, and concurrent contexts. Run as `filmgrain_capi_tests NAME`. */
#include <pthread.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "capi_test_support.h"

/* capi_afgs1_threads_tests.c */
void test_afgs1_payloads(void);
void test_afgs1_errors(void);
void test_thread_counts(void);

static const char* const kModels[] = {"rdd5", "vtm", "vfgs", "av1"};

/* Picture formats each model's reference handles (others are refused with a message):
 * vtm follows HM (128..7680 x 128..4320, multiples of 4); vfgs its reference (width > 128,
 * height >= 128, even where chroma is subsampled, 8 and 10 bit, no 4:0:0); AV1 8, 10 and 12 bit. */
static int model_supports(const char* model, int w, int h, int bit_depth, int chroma_format) {
    if (!strcmp(model, "vtm")) return w >= 128 && h >= 128 && w % 4 == 0 && h % 4 == 0;
    if (!strcmp(model, "vfgs"))
        return w > 128 && h >= 128 && bit_depth <= 10 && chroma_format != FG_CHROMA_400 &&
               (chroma_format == FG_CHROMA_444 || w % 2 == 0) && (chroma_format != FG_CHROMA_420 || h % 2 == 0);
    if (!strcmp(model, "av1")) return bit_depth <= 12;
    return 1;
}

/* vfgs has chroma grain in 4:2:0 only, as its reference: other formats take luma-only SEIs. */
/* One luma interval [0,255] with scale `scale` and cut-offs 9, 9; no chroma. */
static void luma_only_params(fg_fgc_params* p, int32_t scale) {
    fg_fgc_params_init(p);
    p->log2_scale_factor = 4;
    p->comp_model_present_flag[0] = 1;
    p->num_model_values_minus1[0] = 2;
    p->intensity_interval_upper_bound[0][0] = 255;
    p->comp_model_value[0][0][0] = scale;
    p->comp_model_value[0][0][1] = 9;
    p->comp_model_value[0][0][2] = 9;
}

static void push_luma_only(fg_context* ctx) {
    static fg_fgc_params luma;
    luma_only_params(&luma, 110);
    CHECK_STATUS(ctx, fg_context_push_fgc_params(ctx, &luma, FG_CODEC_HEVC, NULL), FG_OK, NULL);
}

/* Packed, padded and bottom-up buffers (src and dst in every combination) give the same
 * samples; the padding bytes stay untouched. */
static void test_strides(void) {
    for (int m = 0; m < 4; m++) {
        uint32_t reference = 0;
        for (int ls = 0; ls < 3; ls++)
            for (int ld = 0; ld < 3; ld++) {
                fg_context* ctx = make_context(kModels[m], 0);
                test_frame src, dst;
                frame_alloc(&src, 256, 144, 10, FG_CHROMA_420, (layout)ls);
                frame_alloc(&dst, 256, 144, 10, FG_CHROMA_420, (layout)ld);
                frame_fill(&src, 1);
                fg_frame_info info;
                fg_frame_info_init(&info);
                info.ids.poc = 3;
                CHECK_STATUS(ctx, fg_context_apply(ctx, &src.frame, &dst.frame, &info), FG_OK, NULL);
                CHECK(info.grain_applied == 1);
                const uint32_t sum = frame_checksum(&dst.frame);
                if (ls == 0 && ld == 0) reference = sum;
                if (sum != reference) fprintf(stderr, "%s: layouts %d -> %d differ from packed\n", kModels[m], ls, ld);
                CHECK(sum == reference);
                if (ld == LAYOUT_PADDED) {
                    /* the 64 bytes after each luma row are padding */
                    const uint8_t* row_end = (const uint8_t*)dst.frame.planes[0] + 256 * 2;
                    int untouched = 1;
                    for (int y = 0; y < 144; y++)
                        for (int i = 0; i < 64; i++) untouched &= row_end[dst.frame.strides[0] * y + i] == 0xA5;
                    CHECK(untouched);
                }
                frame_free(&src);
                frame_free(&dst);
                fg_context_destroy(ctx);
            }
    }
}

/* Out of place leaves src untouched; in place (dst NULL, or dst == src) gives the same
 * output. Three pictures in a row, so persistence and seeds per picture are covered. */
static void test_in_place(void) {
    for (int m = 0; m < 4; m++) {
        fg_context* a = make_context(kModels[m], 0);
        fg_context* b = make_context(kModels[m], 0);
        for (int k = 0; k < 3; k++) {
            test_frame src, orig, out, inplace;
            frame_alloc(&src, 320, 180, 8, FG_CHROMA_420, LAYOUT_PACKED);
            frame_alloc(&orig, 320, 180, 8, FG_CHROMA_420, LAYOUT_PACKED);
            frame_alloc(&out, 320, 180, 8, FG_CHROMA_420, LAYOUT_PADDED);
            frame_alloc(&inplace, 320, 180, 8, FG_CHROMA_420, LAYOUT_BOTTOM_UP);
            frame_fill(&src, (uint32_t)k);
            frame_fill(&orig, (uint32_t)k);
            frame_fill(&inplace, (uint32_t)k);
            CHECK_STATUS(a, fg_context_apply(a, &src.frame, &out.frame, NULL), FG_OK, NULL);
            CHECK(frames_equal(&src.frame, &orig.frame));
            CHECK(!frames_equal(&out.frame, &orig.frame));
            CHECK_STATUS(b, fg_context_apply(b, &inplace.frame, k == 1 ? &inplace.frame : NULL, NULL), FG_OK, NULL);
            CHECK(frames_equal(&out.frame, &inplace.frame));
            frame_free(&src);
            frame_free(&orig);
            frame_free(&out);
            frame_free(&inplace);
        }
        fg_context_destroy(a);
        fg_context_destroy(b);
    }
}

/* Odd luma sizes (chroma rounds up): grain is added, out of place equals in place, and
 * a second context gives the same samples. vfgs refuses what its reference cannot do. */
static void test_odd_sizes(void) {
    const int sizes[][2] = {{97, 61}, {33, 17}, {1, 1}, {131, 129}};
    const int formats[] = {FG_CHROMA_420, FG_CHROMA_422, FG_CHROMA_444};
    for (int m = 0; m < 4; m++)
        for (int s = 0; s < 4; s++)
            for (int fi = 0; fi < 3; fi++) {
                const int w = sizes[s][0], h = sizes[s][1];
                fg_context* a = make_context(kModels[m], 0);
                fg_context* b = make_context(kModels[m], 0);
                test_frame src, out, inplace;
                frame_alloc(&src, w, h, 8, formats[fi], LAYOUT_PADDED);
                frame_alloc(&out, w, h, 8, formats[fi], LAYOUT_PACKED);
                frame_alloc(&inplace, w, h, 8, formats[fi], LAYOUT_BOTTOM_UP);
                frame_fill(&src, 7);
                frame_copy(&src, &inplace);
                if (!strcmp(kModels[m], "vfgs") && formats[fi] != FG_CHROMA_420) {
                    push_luma_only(a);
                    push_luma_only(b);
                }
                const fg_status st = fg_context_apply(a, &src.frame, &out.frame, NULL);
                if (!model_supports(kModels[m], w, h, 8, formats[fi])) {
                    CHECK_STATUS(a, st, FG_ERROR_UNSUPPORTED, NULL);
                    CHECK(strlen(fg_last_error(a)) > 0);
                } else {
                    CHECK_STATUS(a, st, FG_OK, NULL);
                    CHECK_STATUS(b, fg_context_apply(b, &inplace.frame, NULL, NULL), FG_OK, NULL);
                    CHECK(frames_equal(&out.frame, &inplace.frame));
                    if (w * h > 100) CHECK(plane_differences(&src.frame, &out.frame, 0) > 0);
                }
                frame_free(&src);
                frame_free(&out);
                frame_free(&inplace);
                fg_context_destroy(a);
                fg_context_destroy(b);
            }
}

/* Every chroma format at every bit depth each model supports: grain in luma, in chroma
 * where the format has it, samples within the bit depth. Unsupported combinations fail
 * with a code and a message, never a crash. */
static void test_formats(void) {
    const int depths[] = {8, 10, 12, 16};
    const int formats[] = {FG_CHROMA_400, FG_CHROMA_420, FG_CHROMA_422, FG_CHROMA_444};
    for (int m = 0; m < 4; m++)
        for (int d = 0; d < 4; d++)
            for (int fi = 0; fi < 4; fi++) {
                const char* model = kModels[m];
                const int bd = depths[d], cf = formats[fi];
                fg_context* ctx = make_context(model, 0);
                test_frame src, out;
                frame_alloc(&src, 256, 128, bd, cf, LAYOUT_PADDED);
                frame_alloc(&out, 256, 128, bd, cf, LAYOUT_PADDED);
                frame_fill(&src, (uint32_t)(d * 4 + fi));
                fg_frame_info info;
                fg_frame_info_init(&info);
                const int av1 = !strcmp(model, "av1"), vfgs = !strcmp(model, "vfgs");
                if (av1 && cf == FG_CHROMA_400) {
                    /* a monochrome stream signals no chroma points */
                    fg_av1_params p;
                    av1_test_params(&p, 77);
                    p.num_cb_points = p.num_cr_points = 0;
                    CHECK_STATUS(ctx, fg_context_push_av1_params(ctx, &p, 0), FG_OK, NULL);
                }
                if (vfgs && cf != FG_CHROMA_420) push_luma_only(ctx);
                const fg_status st = fg_context_apply(ctx, &src.frame, &out.frame, &info);
                if (!model_supports(model, 256, 128, bd, cf)) {
                    CHECK(st != FG_OK);
                    CHECK(strlen(fg_last_error(ctx)) > 0);
                } else {
                    if (st != FG_OK) fprintf(stderr, "%s %d-bit format %d: %s\n", model, bd, cf, fg_last_error(ctx));
                    CHECK(st == FG_OK);
                    CHECK(info.grain_applied == 1);
                    CHECK(plane_differences(&src.frame, &out.frame, 0) > 0);
                    /* vfgs adds chroma grain to 4:2:0 only (as its reference) */
                    if (cf != FG_CHROMA_400 && (!vfgs || cf == FG_CHROMA_420)) {
                        CHECK(plane_differences(&src.frame, &out.frame, 1) > 0);
                        CHECK(plane_differences(&src.frame, &out.frame, 2) > 0);
                    }
                    int in_range = 1;
                    for (int y = 0; y < 128; y++)
                        for (int x = 0; x < 256; x++) in_range &= frame_sample(&out.frame, 0, x, y) < (1 << bd);
                    CHECK(in_range);
                }
                frame_free(&src);
                frame_free(&out);
                fg_context_destroy(ctx);
            }
}

static fg_status apply_simple(fg_context* ctx, test_frame* f) { return fg_context_apply(ctx, &f->frame, NULL, NULL); }

/* Bad arguments and bad parameters: an error code, and a message naming the field. */
static void test_errors(void) {
    char msg[256];
    fg_context* ctx = NULL;
    fg_options o;

    /* options */
    fg_options_init(&o);
    o.flavour = 7;
    CHECK(fg_context_create(&o, &ctx, msg, sizeof msg) == FG_ERROR_INVALID_ARGUMENT);
    CHECK(ctx == NULL);
    CHECK(strstr(msg, "flavour") && strstr(msg, "7"));
    fg_options_init(&o);
    o.threads = -1;
    CHECK(fg_context_create(&o, &ctx, msg, sizeof msg) == FG_ERROR_INVALID_ARGUMENT);
    CHECK(strstr(msg, "threads") != NULL);
    fg_options_init(&o);
    o.threads = 257;
    CHECK(fg_context_create(&o, &ctx, msg, sizeof msg) == FG_ERROR_INVALID_ARGUMENT);
    CHECK(strstr(msg, "threads") && strstr(msg, "257") && strstr(msg, "256"));
    fg_options_init(&o);
    o.persistence = 2;
    CHECK(fg_context_create(&o, &ctx, msg, sizeof msg) == FG_ERROR_INVALID_ARGUMENT);
    CHECK(strstr(msg, "persistence") != NULL);
    fg_options_init(&o);
    o.struct_size = 4;
    CHECK(fg_context_create(&o, &ctx, msg, sizeof msg) == FG_ERROR_INVALID_ARGUMENT);
    CHECK(strstr(msg, "struct_size") != NULL);
    CHECK(fg_context_create(NULL, NULL, msg, sizeof msg) == FG_ERROR_INVALID_ARGUMENT);
    /* a message buffer too small is truncated, not overrun */
    char tiny[8];
    memset(tiny, 'x', sizeof tiny);
    o.struct_size = 4;
    CHECK(fg_context_create(&o, &ctx, tiny, 5) == FG_ERROR_INVALID_ARGUMENT);
    CHECK(strlen(tiny) == 4 && tiny[5] == 'x');
    fg_options_init(&o);
    o.threads = 0; /* all cores */
    CHECK(fg_context_create(&o, &ctx, msg, sizeof msg) == FG_OK);
    fg_context_destroy(ctx);
    fg_context_destroy(NULL);

    /* NULL pointers */
    test_frame f;
    frame_alloc(&f, 64, 64, 8, FG_CHROMA_420, LAYOUT_PACKED);
    frame_fill(&f, 1);
    CHECK(fg_context_apply(NULL, &f.frame, NULL, NULL) == FG_ERROR_INVALID_ARGUMENT);
    CHECK(strlen(fg_last_error(NULL)) > 0);
    CHECK(push_fgc_test_params(NULL, NULL) == FG_ERROR_INVALID_ARGUMENT);
    CHECK(fg_context_reset(NULL) == FG_ERROR_INVALID_ARGUMENT);
    ctx = make_context("rdd5", 0);
    CHECK_STATUS(ctx, fg_context_apply(ctx, NULL, NULL, NULL), FG_ERROR_INVALID_ARGUMENT, "src is NULL");
    CHECK_STATUS(ctx, fg_context_push_fgc_sei(ctx, NULL, 10, FG_CODEC_HEVC, NULL), FG_ERROR_INVALID_ARGUMENT, "payload");
    CHECK_STATUS(ctx, fg_context_push_av1_params(ctx, NULL, 0), FG_ERROR_INVALID_ARGUMENT, "params");
    CHECK_STATUS(ctx, fg_context_push_fgc_params(ctx, NULL, FG_CODEC_HEVC, NULL), FG_ERROR_INVALID_ARGUMENT, "params");
    void* saved = f.frame.planes[1];
    f.frame.planes[1] = NULL;
    CHECK_STATUS(ctx, apply_simple(ctx, &f), FG_ERROR_INVALID_ARGUMENT, "src.planes[1]");
    f.frame.planes[1] = saved;

    /* frame description */
    f.frame.strides[0] = 10;
    CHECK_STATUS(ctx, apply_simple(ctx, &f), FG_ERROR_INVALID_ARGUMENT, "strides[0]");
    f.frame.strides[0] = 64;
    f.frame.bit_depth = 7;
    CHECK_STATUS(ctx, apply_simple(ctx, &f), FG_ERROR_INVALID_ARGUMENT, "bit_depth");
    f.frame.bit_depth = 8;
    f.frame.chroma_format = 9;
    CHECK_STATUS(ctx, apply_simple(ctx, &f), FG_ERROR_INVALID_ARGUMENT, "chroma_format");
    f.frame.chroma_format = FG_CHROMA_420;
    f.frame.width = 0;
    CHECK_STATUS(ctx, apply_simple(ctx, &f), FG_ERROR_INVALID_ARGUMENT, "width");
    f.frame.width = 64;
    test_frame other;
    frame_alloc(&other, 64, 32, 8, FG_CHROMA_420, LAYOUT_PACKED);
    CHECK_STATUS(ctx, fg_context_apply(ctx, &f.frame, &other.frame, NULL), FG_ERROR_INVALID_ARGUMENT, "dst");
    frame_free(&other);
    fg_frame_info info;
    fg_frame_info_init(&info);
    info.struct_size = 3;
    CHECK_STATUS(ctx, fg_context_apply(ctx, &f.frame, NULL, &info), FG_ERROR_INVALID_ARGUMENT, "struct_size");
    CHECK_STATUS(ctx, apply_simple(ctx, &f), FG_OK, NULL);
    CHECK(strcmp(fg_last_error(ctx), "") == 0);

    /* metadata */
    static fg_fgc_params typed;
    fgc_test_params(&typed);
    typed.log2_scale_factor = 99;
    CHECK_STATUS(ctx, fg_context_push_fgc_params(ctx, &typed, FG_CODEC_HEVC, NULL), FG_ERROR_INVALID_PARAMS,
                 "log2_scale_factor");
    fgc_test_params(&typed);
    CHECK_STATUS(ctx, fg_context_push_fgc_params(ctx, &typed, 5, NULL), FG_ERROR_INVALID_ARGUMENT, "codec");
    const uint8_t truncated[1] = {0x00}; /* cancel_flag 0, then the payload ends */
    CHECK_STATUS(ctx, fg_context_push_fgc_sei(ctx, truncated, sizeof truncated, FG_CODEC_HEVC, NULL),
                 FG_ERROR_MALFORMED_PAYLOAD, NULL);
    CHECK(strlen(fg_last_error(ctx)) > 0);
    /* 0x80: a bare av1_film_grain_param_sets() (no T.35 header) announcing one set, then the
     * payload ends; 0x00 is complete (afgs1_enable_flag = 0: no grain) */
    const uint8_t afgs1_truncated[1] = {0x80};
    CHECK_STATUS(ctx, fg_context_push_afgs1_t35(ctx, afgs1_truncated, sizeof afgs1_truncated),
                 FG_ERROR_MALFORMED_PAYLOAD, "truncated");
    CHECK_STATUS(ctx, fg_context_push_afgs1_t35(ctx, truncated, sizeof truncated), FG_OK, NULL);
    CHECK_STATUS(ctx, fg_context_show_existing_av1_frame(ctx, 9), FG_ERROR_INVALID_ARGUMENT, "frame_to_show_map_idx");
    CHECK_STATUS(ctx, fg_context_show_existing_av1_frame(ctx, 2), FG_ERROR_INVALID_PARAMS, "frame_to_show_map_idx");

    /* An SEI valid in syntax but not for this picture: an interval bound above 255 is
     * impossible in JSON (checked at push), so use comp_model_value beyond its range
     * for the bit depth: the check runs at apply time, naming the element. */
    static fg_fgc_params too_strong;
    luma_only_params(&too_strong, 300);
    too_strong.num_model_values_minus1[0] = 0;
    CHECK_STATUS(ctx, fg_context_push_fgc_params(ctx, &too_strong, FG_CODEC_HEVC, NULL), FG_OK, NULL);
    CHECK_STATUS(ctx, apply_simple(ctx, &f), FG_ERROR_INVALID_PARAMS, "comp_model_value");
    fg_context_destroy(ctx);

    /* passthrough: the same set leaves the picture untouched, with the reason */
    ctx = make_context("rdd5", 1);
    CHECK_STATUS(ctx, fg_context_push_fgc_params(ctx, &too_strong, FG_CODEC_HEVC, NULL), FG_OK, NULL);
    test_frame orig;
    frame_alloc(&orig, 64, 64, 8, FG_CHROMA_420, LAYOUT_PACKED);
    frame_copy(&f, &orig);
    fg_frame_info_init(&info);
    CHECK_STATUS(ctx, fg_context_apply(ctx, &f.frame, NULL, &info), FG_OK, "comp_model_value");
    CHECK(info.grain_applied == 0);
    CHECK(frames_equal(&f.frame, &orig.frame));
    fg_context_destroy(ctx);

    /* AV1 */
    ctx = make_context("av1", 0);
    fg_av1_params p;
    av1_test_params(&p, 1);
    p.num_y_points = 15;
    CHECK_STATUS(ctx, fg_context_push_av1_params(ctx, &p, 0), FG_OK, NULL);
    CHECK_STATUS(ctx, apply_simple(ctx, &f), FG_ERROR_INVALID_PARAMS, "num_y_points");
    av1_test_params(&p, 1);
    p.update_grain = 0;
    p.film_grain_params_ref_idx = 3;
    CHECK_STATUS(ctx, fg_context_push_av1_params(ctx, &p, 0), FG_ERROR_INVALID_PARAMS, "film_grain_params_ref_idx");
    av1_test_params(&p, 1);
    CHECK_STATUS(ctx, fg_context_push_av1_params(ctx, &p, 0x100), FG_ERROR_INVALID_ARGUMENT, "refresh_frame_flags");
    p.struct_size = 0;
    CHECK_STATUS(ctx, fg_context_push_av1_params(ctx, &p, 0), FG_ERROR_INVALID_ARGUMENT, "struct_size");
    fg_context_destroy(ctx);

    /* vfgs cannot reseed per picture */
    ctx = make_context("vfgs", 0);
    test_frame big;
    frame_alloc(&big, 256, 128, 8, FG_CHROMA_420, LAYOUT_PACKED);
    frame_fill(&big, 2);
    fg_frame_info_init(&info);
    info.has_seed = 1;
    CHECK_STATUS(ctx, fg_context_apply(ctx, &big.frame, NULL, &info), FG_ERROR_UNSUPPORTED, "seed");
    frame_free(&big);
    fg_context_destroy(ctx);
    frame_free(&orig);
    frame_free(&f);
}

/* One picture through a fresh context with the given SEI handling; returns its checksum. */
static uint32_t grain_checksum(fg_context* ctx, int poc, int idr_pic_id, int use_seed, uint32_t seed, int* applied) {
    test_frame f;
    frame_alloc(&f, 128, 128, 8, FG_CHROMA_420, LAYOUT_PACKED);
    frame_fill(&f, 5);
    fg_frame_info info;
    fg_frame_info_init(&info);
    info.ids.poc = poc;
    info.ids.idr_pic_id = idr_pic_id;
    info.has_seed = use_seed;
    info.seed = seed;
    CHECK_STATUS(ctx, fg_context_apply(ctx, &f.frame, NULL, &info), FG_OK, NULL);
    if (applied) *applied = info.grain_applied;
    const uint32_t sum = frame_checksum(&f.frame);
    frame_free(&f);
    return sum;
}

/* SEIs pushed with picture ids wait for that picture (decode order != output order);
 * the seed derivation follows the ids; persistence and cancel follow the options. */
static void test_picture_ids_and_persistence(void) {
    test_frame clean;
    frame_alloc(&clean, 128, 128, 8, FG_CHROMA_420, LAYOUT_PACKED);
    frame_fill(&clean, 5);
    const uint32_t clean_sum = frame_checksum(&clean.frame);
    frame_free(&clean);

    /* decode order: picture POC 4 (with SEI) before POC 2; output order 2, 4 */
    fg_context* reordered = make_context("rdd5", 0);
    fg_context_reset(reordered);
    fg_picture_ids ids4 = {4, 0};
    CHECK_STATUS(reordered, push_fgc_test_params(reordered, &ids4), FG_OK, NULL);
    int applied = -1;
    CHECK(grain_checksum(reordered, 2, 0, 0, 0, &applied) == clean_sum);
    CHECK(applied == 0);
    const uint32_t poc4 = grain_checksum(reordered, 4, 0, 0, 0, &applied);
    CHECK(applied == 1 && poc4 != clean_sum);
    fg_context* direct = make_context("rdd5", 0);
    CHECK(grain_checksum(direct, 4, 0, 0, 0, NULL) == poc4);
    /* rdd5: the seed follows POC + (idr_pic_id << 5); an explicit seed gives the same */
    const uint32_t idr = grain_checksum(direct, 3, 1, 0, 0, NULL);
    CHECK(idr != poc4);
    fg_context* seeded = make_context("rdd5", 0);
    CHECK(grain_checksum(seeded, 99, 7, 1, 3 + (1 << 5), NULL) == idr);
    fg_context_destroy(seeded);
    fg_context_destroy(direct);
    fg_context_destroy(reordered);

    /* persistence_flag = 0: HM reuses it (reference), the semantics do not (semantic) */
    static fg_fgc_params once;
    fgc_test_params(&once);
    once.persistence_flag = 0;
    for (int semantic = 0; semantic < 2; semantic++) {
        fg_options o;
        fg_options_init(&o);
        o.persistence = semantic ? FG_PERSISTENCE_SEMANTIC : FG_PERSISTENCE_REFERENCE;
        fg_context* ctx = NULL;
        CHECK(fg_context_create(&o, &ctx, NULL, 0) == FG_OK);
        CHECK_STATUS(ctx, fg_context_push_fgc_params(ctx, &once, FG_CODEC_HEVC, NULL), FG_OK, NULL);
        grain_checksum(ctx, 0, 0, 0, 0, &applied);
        CHECK(applied == 1);
        const uint32_t next = grain_checksum(ctx, 1, 0, 0, 0, &applied);
        CHECK(applied == !semantic);
        CHECK((next == clean_sum) == semantic);
        fg_context_destroy(ctx);
    }

    /* cancel: no grain from that picture on */
    fg_context* ctx = make_context("vtm", 0);
    CHECK(grain_checksum(ctx, 0, 0, 0, 0, &applied) != clean_sum);
    static fg_fgc_params cancel;
    fg_fgc_params_init(&cancel);
    cancel.cancel_flag = 1;
    CHECK_STATUS(ctx, fg_context_push_fgc_params(ctx, &cancel, FG_CODEC_HEVC, NULL), FG_OK, NULL);
    CHECK(grain_checksum(ctx, 1, 0, 0, 0, &applied) == clean_sum && applied == 0);
    CHECK(grain_checksum(ctx, 2, 0, 0, 0, &applied) == clean_sum && applied == 0);
    fg_context_destroy(ctx);

    /* reset: nothing in force, picture count restarts */
    ctx = make_context("rdd5", 0);
    CHECK(grain_checksum(ctx, 0, 0, 0, 0, NULL) != clean_sum);
    CHECK_STATUS(ctx, fg_context_reset(ctx), FG_OK, NULL);
    CHECK(grain_checksum(ctx, 1, 0, 0, 0, &applied) == clean_sum && applied == 0);
    fg_context_destroy(ctx);

    /* without info, pictures count 0, 1, 2: the third equals POC 2 */
    fg_context* counted = make_context("vtm", 0);
    fg_context* explicit_ids = make_context("vtm", 0);
    test_frame f;
    frame_alloc(&f, 128, 128, 8, FG_CHROMA_420, LAYOUT_PACKED);
    for (int k = 0; k < 3; k++) {
        frame_fill(&f, 5);
        CHECK_STATUS(counted, fg_context_apply(counted, &f.frame, NULL, NULL), FG_OK, NULL);
    }
    CHECK(frame_checksum(&f.frame) == grain_checksum(explicit_ids, 2, 0, 0, 0, NULL));
    frame_free(&f);
    fg_context_destroy(counted);
    fg_context_destroy(explicit_ids);
}

/* AV1 reference slots: update_grain = 0 loads a stored set with the new seed;
 * show_existing_frame shows a stored set as it was. */
static void test_av1_reference_slots(void) {
    fg_av1_params a, b, load;
    av1_test_params(&a, 1000);
    av1_test_params(&b, 2000);
    b.num_y_points = 2; /* a different set */
    fg_context* ctx = make_context("av1", 0);
    CHECK_STATUS(ctx, fg_context_push_av1_params(ctx, &a, 0x05), FG_OK, NULL); /* slots 0 and 2 */
    CHECK_STATUS(ctx, fg_context_push_av1_params(ctx, &b, 0x02), FG_OK, NULL); /* slot 1 */
    fg_av1_params_init(&load);
    load.apply_grain = 1;
    load.update_grain = 0;
    load.film_grain_params_ref_idx = 2;
    load.grain_seed = 3000;
    CHECK_STATUS(ctx, fg_context_push_av1_params(ctx, &load, 0), FG_OK, NULL);
    const uint32_t loaded = grain_checksum(ctx, 0, 0, 0, 0, NULL);

    fg_context* ref = make_context("av1", 0);
    fg_av1_params a3000 = a;
    a3000.grain_seed = 3000;
    CHECK_STATUS(ref, fg_context_push_av1_params(ref, &a3000, 0), FG_OK, NULL);
    CHECK(grain_checksum(ref, 0, 0, 0, 0, NULL) == loaded);
    /* the per-frame seed replaces grain_seed */
    CHECK_STATUS(ref, fg_context_push_av1_params(ref, &a, 0), FG_OK, NULL);
    CHECK(grain_checksum(ref, 0, 0, 1, 3000, NULL) == loaded);

    CHECK_STATUS(ctx, fg_context_show_existing_av1_frame(ctx, 1), FG_OK, NULL);
    const uint32_t shown = grain_checksum(ctx, 0, 0, 0, 0, NULL);
    CHECK_STATUS(ref, fg_context_push_av1_params(ref, &b, 0), FG_OK, NULL);
    CHECK(grain_checksum(ref, 0, 0, 0, 0, NULL) == shown);
    CHECK(shown != loaded);
    fg_context_destroy(ref);
    fg_context_destroy(ctx);
}

/* Contexts on several threads at once give what one thread gives. */
enum { kThreads = 4, kFrames = 4 };
typedef struct job {
    const char* model;
    uint32_t sums[kFrames];
} job;

static void run_job(job* j) {
    fg_context* ctx = make_context(j->model, 0);
    test_frame src, dst;
    frame_alloc(&src, 320, 192, 10, FG_CHROMA_420, LAYOUT_PADDED);
    frame_alloc(&dst, 320, 192, 10, FG_CHROMA_420, LAYOUT_BOTTOM_UP);
    for (int k = 0; k < kFrames; k++) {
        frame_fill(&src, (uint32_t)k);
        fg_frame_info info;
        fg_frame_info_init(&info);
        info.ids.poc = 2 * k;
        /* a failure says why (a context or pool that could not be made on a loaded machine
           is not a wrong picture) */
        const fg_status st = ctx ? fg_context_apply(ctx, &src.frame, &dst.frame, &info) : FG_ERROR_OUT_OF_MEMORY;
        if (st != FG_OK)
            fprintf(stderr, "%s frame %d: %s: %s\n", j->model, k, fg_status_name(st), ctx ? fg_last_error(ctx) : "no context");
        j->sums[k] = st == FG_OK ? frame_checksum(&dst.frame) : 0;
    }
    frame_free(&src);
    frame_free(&dst);
    fg_context_destroy(ctx);
}

static void* job_thread(void* arg) {
    run_job((job*)arg);
    return NULL;
}

static void test_concurrency(void) {
    job serial[kThreads];
    for (int t = 0; t < kThreads; t++) {
        serial[t].model = kModels[t % 4];
        run_job(&serial[t]);
    }
    /* twice as many threads as models: two contexts of each model at once */
    pthread_t threads[2 * kThreads];
    job doubled[2 * kThreads];
    for (int t = 0; t < 2 * kThreads; t++) {
        doubled[t].model = kModels[t % 4];
        CHECK(pthread_create(&threads[t], NULL, job_thread, &doubled[t]) == 0);
    }
    for (int t = 0; t < 2 * kThreads; t++) pthread_join(threads[t], NULL);
    for (int t = 0; t < 2 * kThreads; t++)
        for (int k = 0; k < kFrames; k++) {
            CHECK(serial[t % kThreads].sums[k] != 0);
            CHECK(doubled[t].sums[k] == serial[t % kThreads].sums[k]);
        }
}

static void test_version(void) {
    CHECK(fg_version() == FG_VERSION);
    CHECK(strcmp(fg_version_string(), "2.0.0") == 0);
    CHECK(strcmp(fg_status_name(FG_ERROR_INVALID_PARAMS), "FG_ERROR_INVALID_PARAMS") == 0);
    CHECK(strcmp(fg_status_name(99), "unknown fg_status") == 0);
}

/* ---- issue 24 (hardening): reproducers of undefined behaviour and unchecked values ---- */

/* A minimal MSB-first bit writer for hand-made SEI payloads. */
typedef struct bit_buffer {
    uint8_t bytes[64];
    int bits;
} bit_buffer;

static void put_bits(bit_buffer* b, int n, uint32_t v) {
    for (int i = n - 1; i >= 0; i--) {
        if ((v >> i) & 1) b->bytes[b->bits >> 3] |= (uint8_t)(0x80 >> (b->bits & 7));
        b->bits++;
    }
}

static void put_ue(bit_buffer* b, uint32_t v) { /* v < 2^32 - 1 */
    const uint32_t x = v + 1;
    int len = 0;
    while ((x >> len) > 1) len++;
    put_bits(b, len, 0);
    put_bits(b, len + 1, x);
}

static void put_se(bit_buffer* b, int32_t v) {
    put_ue(b, v > 0 ? (uint32_t)(2 * (int64_t)v - 1) : (uint32_t)(-2 * (int64_t)v));
}

/* An H.265 FGC SEI body: frequency filtering, luma only, one interval, (scale, 9, 9). */
static size_t fgc_sei_with_scale(uint8_t* out, int32_t scale) {
    bit_buffer b;
    memset(&b, 0, sizeof b);
    put_bits(&b, 1, 0); /* film_grain_characteristics_cancel_flag */
    put_bits(&b, 2, 0); /* film_grain_model_id */
    put_bits(&b, 1, 0); /* separate_colour_description_present_flag */
    put_bits(&b, 2, 0); /* blending_mode_id */
    put_bits(&b, 4, 4); /* log2_scale_factor */
    put_bits(&b, 3, 4); /* comp_model_present_flag[0..2] = 1, 0, 0 */
    put_bits(&b, 8, 0); /* num_intensity_intervals_minus1[0] */
    put_bits(&b, 3, 2); /* num_model_values_minus1[0] */
    put_bits(&b, 8, 0);
    put_bits(&b, 8, 255);
    put_se(&b, scale);
    put_se(&b, 9);
    put_se(&b, 9);
    put_bits(&b, 1, 1); /* film_grain_characteristics_persistence_flag */
    put_bits(&b, 1, 1); /* payload stop bit, then zeros */
    const size_t n = (size_t)(b.bits + 7) / 8;
    memcpy(out, b.bytes, n);
    return n;
}

/* A negative scale factor (comp_model_value[c][i][0]) went through rdd5 and vtm with FG_OK,
 * destroying the picture (grey 128 became mean 64.6, std 84.6). It is refused by every
 * flavour, from SEI bytes and from JSON, naming the element, the value and the range;
 * passthrough leaves the picture untouched. */
static void test_negative_scale(void) {
    const int32_t values[] = {-1, -1073741824};
    for (int m = 0; m < 3; m++)
        for (int k = 0; k < 2; k++)
            for (int passthrough = 0; passthrough < 2; passthrough++)
                for (int json = 0; json < 2; json++) {
                    char needle[160];
                    /* vfgs checks at set_params, before it knows the picture: the widest range */
                    snprintf(needle, sizeof needle, "comp_model_value[0][0][0] = %ld is out of range (allowed 0..%d)",
                             (long)values[k], m == 2 ? 65535 : 255);
                    fg_context* ctx = make_context(kModels[m], passthrough);
                    fg_status pushed;
                    if (json) { /* the typed set (what a JSON reader produces) */
                        static fg_fgc_params typed_scale;
                        luma_only_params(&typed_scale, values[k]);
                        pushed = fg_context_push_fgc_params(ctx, &typed_scale, FG_CODEC_HEVC, NULL);
                    } else {
                        uint8_t sei[64];
                        const size_t n = fgc_sei_with_scale(sei, values[k]);
                        pushed = fg_context_push_fgc_sei(ctx, sei, n, FG_CODEC_HEVC, NULL);
                    }
                    if (pushed != FG_OK) {
                        /* the typed push refuses it already (the same check, before the
                         * picture is known: the widest range, a 16-bit picture's) */
                        CHECK(json);
                        char at_push[160];
                        snprintf(at_push, sizeof at_push,
                                 "comp_model_value[0][0][0] = %ld is out of range (allowed 0..65535)", (long)values[k]);
                        CHECK_STATUS(ctx, pushed, FG_ERROR_INVALID_PARAMS, at_push);
                        fg_context_destroy(ctx);
                        continue;
                    }
                    test_frame src, dst;
                    frame_alloc(&src, 256, 144, 8, FG_CHROMA_420, LAYOUT_PACKED);
                    frame_alloc(&dst, 256, 144, 8, FG_CHROMA_420, LAYOUT_PACKED);
                    frame_fill(&src, 2);
                    fg_frame_info info;
                    fg_frame_info_init(&info);
                    info.grain_applied = 7;
                    CHECK_STATUS(ctx, fg_context_apply(ctx, &src.frame, &dst.frame, &info),
                                 passthrough ? FG_OK : FG_ERROR_INVALID_PARAMS, needle);
                    CHECK(info.grain_applied == 0);
                    if (passthrough) CHECK(frames_equal(&src.frame, &dst.frame));
                    frame_free(&src);
                    frame_free(&dst);
                    fg_context_destroy(ctx);
                }
}

/* fg_options 2.0: the tr flavour and the options the tool offers are reachable from C; a
 * caller built against 1.0 passes the smaller struct_size and gets the defaults; a value
 * outside its range is refused naming the field. tr equals rdd5 on a set both take. */
static void test_options_v2(void) {
    fg_options o;
    fg_options_init(&o);
    CHECK(o.clip_to_restricted_range == -1 && o.block_size == 0 && o.single_line_blocks == 0);
    test_frame src, a, b;
    frame_alloc(&src, 200, 136, 8, FG_CHROMA_420, LAYOUT_PACKED);
    frame_alloc(&a, 200, 136, 8, FG_CHROMA_420, LAYOUT_PACKED);
    frame_alloc(&b, 200, 136, 8, FG_CHROMA_420, LAYOUT_PACKED);
    frame_fill(&src, 4);
    fg_context *rdd5 = NULL, *tr = NULL, *old = NULL;
    o.flavour = FG_FLAVOUR_TR;
    CHECK(fg_context_create(&o, &tr, NULL, 0) == FG_OK);
    o.flavour = FG_FLAVOUR_RDD5;
    o.struct_size = (uint32_t)offsetof(fg_options, block_size); /* a 1.0 caller */
    o.block_size = 99;                                         /* past its struct: ignored */
    CHECK(fg_context_create(&o, &old, NULL, 0) == FG_OK);
    fg_options_init(&o);
    CHECK(fg_context_create(&o, &rdd5, NULL, 0) == FG_OK);
    if (tr && rdd5 && old) {
        fg_context* const all[3] = {tr, rdd5, old};
        test_frame* const dst[3] = {&a, &b, &b};
        for (int i = 0; i < 3; i++) {
            CHECK_STATUS(all[i], push_fgc_test_params(all[i], NULL), FG_OK, NULL);
            CHECK_STATUS(all[i], fg_context_apply(all[i], &src.frame, &dst[i]->frame, NULL), FG_OK, NULL);
            if (i == 1) CHECK(frames_equal(&a.frame, &b.frame)); /* tr = rdd5 */
            if (i == 2) CHECK(frames_equal(&a.frame, &b.frame)); /* 1.0 layout = defaults */
        }
    }
    /* ffmpeg: the test set signals chroma with fewer than 3 model values, where FFmpeg infers
     * no cut-off (departure (a)): its picture differs from rdd5's, the same on every run. */
    fg_context *ff1 = NULL, *ff2 = NULL;
    fg_options_init(&o);
    o.flavour = FG_FLAVOUR_FFMPEG;
    CHECK(fg_context_create(&o, &ff1, NULL, 0) == FG_OK);
    o.threads = 3;
    CHECK(fg_context_create(&o, &ff2, NULL, 0) == FG_OK);
    if (ff1 && ff2 && rdd5) {
        test_frame c1, c2;
        frame_alloc(&c1, 200, 136, 8, FG_CHROMA_420, LAYOUT_PACKED);
        frame_alloc(&c2, 200, 136, 8, FG_CHROMA_420, LAYOUT_PACKED);
        CHECK_STATUS(ff1, push_fgc_test_params(ff1, NULL), FG_OK, NULL);
        CHECK_STATUS(ff1, fg_context_apply(ff1, &src.frame, &c1.frame, NULL), FG_OK, NULL);
        CHECK_STATUS(ff2, push_fgc_test_params(ff2, NULL), FG_OK, NULL);
        CHECK_STATUS(ff2, fg_context_apply(ff2, &src.frame, &c2.frame, NULL), FG_OK, NULL);
        CHECK(frames_equal(&c1.frame, &c2.frame));
        CHECK(!frames_equal(&c1.frame, &b.frame));
        frame_free(&c1);
        frame_free(&c2);
    }
    fg_context_destroy(ff1);
    fg_context_destroy(ff2);
    fg_context_destroy(tr);
    fg_context_destroy(rdd5);
    fg_context_destroy(old);
    char message[256];
    fg_context* bad = NULL;
    fg_options_init(&o);
    o.block_size = 12;
    CHECK(fg_context_create(&o, &bad, message, sizeof message) == FG_ERROR_INVALID_ARGUMENT && bad == NULL);
    CHECK(strstr(message, "block_size = 12") != NULL);
    fg_options_init(&o);
    o.flavour = 5;
    CHECK(fg_context_create(&o, &bad, message, sizeof message) == FG_ERROR_INVALID_ARGUMENT);
    CHECK(strstr(message, "options.flavour = 5 is out of range (allowed 0..4)") != NULL);
    frame_free(&src);
    frame_free(&a);
    frame_free(&b);
}

/* Typed parameter sets (2.0): the FGC set as syntax elements gives the samples of its SEI
 * payload bytes, and round-trips through them; the de-biased AV1 set gives the biased one's
 * samples and round-trips; values outside their field are refused naming it. */
static fg_fgc_params kfgc_as_struct(void) {
    fg_fgc_params p;
    fg_fgc_params_init(&p);
    p.log2_scale_factor = 4;
    for (int c = 0; c < 3; c++) p.comp_model_present_flag[c] = 1;
    p.num_intensity_intervals_minus1[0] = 1;
    p.num_model_values_minus1[0] = 2;
    p.num_model_values_minus1[1] = 1;
    p.intensity_interval_upper_bound[0][0] = 127;
    p.intensity_interval_lower_bound[0][1] = 128;
    p.intensity_interval_upper_bound[0][1] = 255;
    p.intensity_interval_upper_bound[1][0] = 255;
    p.intensity_interval_upper_bound[2][0] = 255;
    const int32_t v0[2][3] = {{120, 8, 8}, {90, 10, 12}};
    for (int i = 0; i < 2; i++)
        for (int j = 0; j < 3; j++) p.comp_model_value[0][i][j] = v0[i][j];
    p.comp_model_value[1][0][0] = 60;
    p.comp_model_value[1][0][1] = 9;
    p.comp_model_value[2][0][0] = 50;
    return p;
}

static void test_typed_params(void) {
    test_frame src, a, b;
    frame_alloc(&src, 176, 144, 10, FG_CHROMA_420, LAYOUT_PADDED);
    frame_alloc(&a, 176, 144, 10, FG_CHROMA_420, LAYOUT_PACKED);
    frame_alloc(&b, 176, 144, 10, FG_CHROMA_420, LAYOUT_PACKED);
    frame_fill(&src, 6);
    for (int m = 0; m < 2; m++) { /* rdd5, vtm */
        fg_context* bytes = make_context(kModels[m], 0);
        fg_context* typed = make_context(kModels[m], 0);
        const fg_fgc_params p = kfgc_as_struct();
        uint8_t payload[256];
        size_t length = 0;
        CHECK(fg_fgc_params_to_sei(&p, FG_CODEC_HEVC, payload, sizeof payload, &length, NULL, 0) == FG_OK);
        CHECK_STATUS(bytes, fg_context_push_fgc_sei(bytes, payload, length, FG_CODEC_HEVC, NULL), FG_OK, NULL);
        CHECK_STATUS(typed, fg_context_push_fgc_params(typed, &p, FG_CODEC_HEVC, NULL), FG_OK, NULL);
        CHECK_STATUS(bytes, fg_context_apply(bytes, &src.frame, &a.frame, NULL), FG_OK, NULL);
        CHECK_STATUS(typed, fg_context_apply(typed, &src.frame, &b.frame, NULL), FG_OK, NULL);
        CHECK(frames_equal(&a.frame, &b.frame));
        /* and the typed set is the one make_context pushes (fgc_test_params) */
        fg_fgc_params q;
        fgc_test_params(&q);
        CHECK(memcmp(&q, &p, sizeof q) == 0);
        fg_context_destroy(bytes);
        fg_context_destroy(typed);
    }
    /* SEI round trip: struct -> bytes -> struct -> the same bytes */
    const fg_fgc_params p = kfgc_as_struct();
    uint8_t sei[256], again[256];
    size_t n = 0, m = 0;
    CHECK(fg_fgc_params_to_sei(&p, FG_CODEC_HEVC, sei, sizeof sei, &n, NULL, 0) == FG_OK && n > 0);
    fg_fgc_params q;
    CHECK(fg_fgc_params_from_sei(sei, n, FG_CODEC_HEVC, &q, NULL, 0) == FG_OK);
    CHECK(fg_fgc_params_to_sei(&q, FG_CODEC_HEVC, again, sizeof again, &m, NULL, 0) == FG_OK);
    CHECK(m == n && memcmp(sei, again, n) == 0);
    CHECK(q.comp_model_value[0][1][2] == 12 && q.intensity_interval_lower_bound[0][1] == 128);
    char message[256];
    size_t need = 0;
    CHECK(fg_fgc_params_to_sei(&p, FG_CODEC_HEVC, sei, 3, &need, message, sizeof message) == FG_ERROR_INVALID_ARGUMENT);
    CHECK(need == n && strstr(message, "capacity = 3") != NULL);
    CHECK(fg_fgc_params_from_sei(sei, 2, FG_CODEC_HEVC, &q, message, sizeof message) == FG_ERROR_MALFORMED_PAYLOAD);
    fg_fgc_params bad = kfgc_as_struct();
    bad.num_intensity_intervals_minus1[1] = 300;
    fg_context* ctx = make_context("rdd5", 0);
    CHECK_STATUS(ctx, fg_context_push_fgc_params(ctx, &bad, FG_CODEC_HEVC, NULL), FG_ERROR_INVALID_PARAMS,
                 "num_intensity_intervals_minus1[1] = 300 is out of range (allowed 0..255)");
    bad = kfgc_as_struct();
    bad.comp_model_value[0][0][0] = -5;
    CHECK_STATUS(ctx, fg_context_push_fgc_params(ctx, &bad, FG_CODEC_HEVC, NULL), FG_ERROR_INVALID_PARAMS,
                 "comp_model_value[0][0][0] = -5 is out of range");
    fg_context_destroy(ctx);

    /* AV1: biased -> de-biased -> the same samples, and back to the same biased values */
    fg_av1_params biased, back;
    av1_test_params(&biased, 1234);
    fg_av1_grain grain;
    CHECK(fg_av1_grain_from_params(&biased, &grain, message, sizeof message) == FG_OK);
    CHECK(grain.seed == 1234 && grain.scaling_shift == biased.grain_scaling_minus_8 + 8);
    CHECK(grain.ar_coeffs_y[0] == biased.ar_coeffs_y_plus_128[0] - 128);
    CHECK(grain.uv_offset[1] == biased.cr_offset - 256);
    CHECK(fg_av1_grain_to_params(&grain, &back, NULL, 0) == FG_OK);
    CHECK(memcmp(back.ar_coeffs_cb_plus_128, biased.ar_coeffs_cb_plus_128, sizeof back.ar_coeffs_cb_plus_128) == 0);
    CHECK(back.cb_mult == biased.cb_mult && back.point_y_scaling[1] == biased.point_y_scaling[1]);
    fg_context* x = make_context("av1", 0);
    fg_context* y = make_context("av1", 0);
    CHECK_STATUS(x, fg_context_push_av1_params(x, &biased, 0), FG_OK, NULL);
    CHECK_STATUS(y, fg_context_push_av1_grain(y, &grain), FG_OK, NULL);
    CHECK_STATUS(x, fg_context_apply(x, &src.frame, &a.frame, NULL), FG_OK, NULL);
    CHECK_STATUS(y, fg_context_apply(y, &src.frame, &b.frame, NULL), FG_OK, NULL);
    CHECK(frames_equal(&a.frame, &b.frame));
    grain.uv_offset[0] = 300;
    CHECK_STATUS(y, fg_context_push_av1_grain(y, &grain), FG_ERROR_INVALID_PARAMS,
                 "uv_offset[0] = 300 is out of range (allowed -256..255)");
    biased.update_grain = 0;
    CHECK(fg_av1_grain_from_params(&biased, &grain, message, sizeof message) == FG_ERROR_INVALID_PARAMS);
    CHECK(strstr(message, "update_grain = 0") != NULL);
    fg_context_destroy(x);
    fg_context_destroy(y);
    frame_free(&src);
    frame_free(&a);
    frame_free(&b);
}

/* strides[0] = PTRDIFF_MIN overflowed the magnitude computation (-PTRDIFF_MIN); strides whose
 * plane would span more than PTRDIFF_MAX bytes overflowed the row addressing. Both are
 * refused naming the field, its value and the allowed magnitudes. */
static void test_extreme_strides(void) {
    const ptrdiff_t strides[] = {PTRDIFF_MIN, PTRDIFF_MAX, -PTRDIFF_MAX, PTRDIFF_MAX / 2, PTRDIFF_MIN / 64};
    for (int m = 0; m < 4; m++)
        for (int k = 0; k < 5; k++)
            for (int plane = 0; plane < 3; plane++) {
                fg_context* ctx = make_context(kModels[m], 0);
                test_frame f;
                frame_alloc(&f, 256, 144, 10, FG_CHROMA_420, LAYOUT_PACKED);
                frame_fill(&f, 1);
                const ptrdiff_t saved = f.frame.strides[plane];
                f.frame.strides[plane] = strides[k];
                char needle[160];
                snprintf(needle, sizeof needle, "src.strides[%d] = %td is out of range (allowed ", plane, strides[k]);
                CHECK_STATUS(ctx, fg_context_apply(ctx, &f.frame, NULL, NULL), FG_ERROR_INVALID_ARGUMENT, needle);
                /* the same as dst */
                test_frame d;
                frame_alloc(&d, 256, 144, 10, FG_CHROMA_420, LAYOUT_PACKED);
                f.frame.strides[plane] = saved;
                d.frame.strides[plane] = strides[k];
                snprintf(needle, sizeof needle, "dst.strides[%d] = %td is out of range (allowed ", plane, strides[k]);
                CHECK_STATUS(ctx, fg_context_apply(ctx, &f.frame, &d.frame, NULL), FG_ERROR_INVALID_ARGUMENT, needle);
                frame_free(&d);
                frame_free(&f);
                fg_context_destroy(ctx);
            }
    /* a one-row plane never steps by its stride: any value is fine there */
    fg_context* ctx = make_context("rdd5", 0);
    test_frame f;
    frame_alloc(&f, 64, 1, 8, FG_CHROMA_400, LAYOUT_PACKED);
    frame_fill(&f, 1);
    f.frame.strides[0] = PTRDIFF_MIN;
    CHECK_STATUS(ctx, fg_context_apply(ctx, &f.frame, NULL, NULL), FG_OK, NULL);
    frame_free(&f);
    fg_context_destroy(ctx);
}

/* POC = INT32_MAX (a legal value) overflowed the seed derivation; the seed uses
 * (POC + (idr_pic_id << 5) + colour offset) mod 256 (RDD 5, HM), so it is computed modulo
 * 2^32: INT32_MAX gives what 255 gives, INT32_MIN what 0 gives, in rdd5 and vtm. */
static void test_extreme_picture_ids(void) {
    for (int m = 0; m < 2; m++) {
        fg_context* ctx = make_context(kModels[m], 0);
        const uint32_t p255 = grain_checksum(ctx, 255, 0, 0, 0, NULL);
        const uint32_t p0 = grain_checksum(ctx, 0, 0, 0, 0, NULL);
        CHECK(p255 != p0);
        CHECK(grain_checksum(ctx, INT32_MAX, 0, 0, 0, NULL) == p255);
        CHECK(grain_checksum(ctx, INT32_MIN, 0, 0, 0, NULL) == p0);
        CHECK(grain_checksum(ctx, -1, 0, 0, 0, NULL) == p255);
        /* idr_pic_id << 5 wraps as well: INT32_MAX << 5 = 0xFFFFFFE0 (rdd5; vtm ignores it) */
        const uint32_t wrapped = grain_checksum(ctx, INT32_MAX, INT32_MAX, 0, 0, NULL);
        CHECK(wrapped == (m == 0 ? grain_checksum(ctx, 255 + 0xE0, 0, 0, 0, NULL) : p255));
        CHECK(grain_checksum(ctx, 0, INT32_MIN, 0, 0, NULL) == p0);
        /* an explicit seed is the picture offset: UINT32_MAX is -1, i.e. 255 */
        CHECK(grain_checksum(ctx, 0, 0, 1, UINT32_MAX, NULL) == p255);
        fg_context_destroy(ctx);
    }
}

/* 16-bit samples at odd addresses gave misaligned loads (UBSan). They are refused with
 * FG_ERROR_INVALID_ARGUMENT naming the plane: an odd planes[p] or an odd strides[p] when
 * bit_depth > 8. 8-bit planes may start anywhere. */
static void test_misaligned_planes(void) {
    for (int m = 0; m < 4; m++)
        for (int plane = 0; plane < 3; plane++)
            for (int what = 0; what < 4; what++) {
                fg_context* ctx = make_context(kModels[m], 0);
                test_frame src, dst;
                frame_alloc(&src, 256, 144, 10, FG_CHROMA_420, LAYOUT_PADDED);
                frame_alloc(&dst, 256, 144, 10, FG_CHROMA_420, LAYOUT_PADDED);
                frame_fill(&src, 1);
                test_frame* t = what < 2 ? &src : &dst;
                char needle[96];
                if (what % 2 == 0) {
                    t->frame.planes[plane] = (uint8_t*)t->frame.planes[plane] + 1; /* 64 bytes of padding per row */
                    snprintf(needle, sizeof needle, "%s.planes[%d]", what < 2 ? "src" : "dst", plane);
                } else {
                    t->frame.strides[plane] -= 1;
                    snprintf(needle, sizeof needle, "%s.strides[%d]", what < 2 ? "src" : "dst", plane);
                }
                CHECK_STATUS(ctx, fg_context_apply(ctx, &src.frame, &dst.frame, NULL), FG_ERROR_INVALID_ARGUMENT, needle);
                CHECK(strstr(fg_last_error(ctx), "2-byte aligned") != NULL);
                frame_free(&src);
                frame_free(&dst);
                fg_context_destroy(ctx);
            }
    /* 8 bits: any address, any stride */
    for (int m = 0; m < 4; m++) {
        fg_context* ctx = make_context(kModels[m], 0);
        test_frame src, dst;
        frame_alloc(&src, 256, 144, 8, FG_CHROMA_420, LAYOUT_PADDED);
        frame_alloc(&dst, 256, 144, 8, FG_CHROMA_420, LAYOUT_PADDED);
        frame_fill(&src, 1);
        src.frame.planes[0] = (uint8_t*)src.frame.planes[0] + 1;
        src.frame.strides[1] -= 1;
        dst.frame.planes[2] = (uint8_t*)dst.frame.planes[2] + 3;
        CHECK_STATUS(ctx, fg_context_apply(ctx, &src.frame, &dst.frame, NULL), FG_OK, NULL);
        frame_free(&src);
        frame_free(&dst);
        fg_context_destroy(ctx);
    }
}

typedef struct named_test {
    const char* name;
    void (*run)(void);
} named_test;

static const named_test kTests[] = {
    {"strides", test_strides},
    {"in_place", test_in_place},
    {"odd_sizes", test_odd_sizes},
    {"formats", test_formats},
    {"errors", test_errors},
    {"picture_ids_and_persistence", test_picture_ids_and_persistence},
    {"av1_reference_slots", test_av1_reference_slots},
    {"concurrency", test_concurrency},
    {"version", test_version},
    {"afgs1_payloads", test_afgs1_payloads},
    {"afgs1_errors", test_afgs1_errors},
    {"thread_counts", test_thread_counts},
    {"negative_scale", test_negative_scale},
    {"extreme_strides", test_extreme_strides},
    {"extreme_picture_ids", test_extreme_picture_ids},
    {"misaligned_planes", test_misaligned_planes},
    {"options_v2", test_options_v2},
    {"typed_params", test_typed_params},
};

int main(int argc, char** argv) {
    int ran = 0;
    for (size_t i = 0; i < sizeof kTests / sizeof kTests[0]; i++) {
        if (argc > 1 && strcmp(argv[1], kTests[i].name) != 0) continue;
        const int before = g_failures;
        kTests[i].run();
        printf("%s: %s\n", kTests[i].name, g_failures == before ? "ok" : "FAILED");
        ran++;
    }
    if (!ran) {
        fprintf(stderr, "no test named %s\n", argc > 1 ? argv[1] : "");
        return 2;
    }
    return g_failures ? 1 : 0;
}
