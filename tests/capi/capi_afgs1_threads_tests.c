/* Tests of the C API, in C: AFGS1 T.35 payloads (written by the project's AFGS1 writer, see
 * afgs1_fixture_gen.cpp) against the same parameter sets pushed as fg_av1_params, damaged
 * payloads, and the thread count option (every count gives the same samples). */
#include <dirent.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "afgs1_fixture.h"
#include "capi_test_support.h"

static fg_context* new_context(int threads) {
    fg_options o;
    fg_options_init(&o);
    o.threads = threads;
    fg_context* ctx = NULL;
    char msg[256];
    if (fg_context_create(&o, &ctx, msg, sizeof msg) != FG_OK) {
        fprintf(stderr, "fg_context_create: %s\n", msg);
        exit(1);
    }
    return ctx;
}

/* The picture `src` with grain from AV1 parameters pushed as the struct, into `out`. */
static void apply_struct(const fg_av1_params* p, const test_frame* src, test_frame* out, int* applied) {
    fg_context* ctx = new_context(1);
    CHECK_STATUS(ctx, fg_context_push_av1_params(ctx, p, 0), FG_OK, NULL);
    fg_frame_info info;
    fg_frame_info_init(&info);
    CHECK_STATUS(ctx, fg_context_apply(ctx, &src->frame, &out->frame, &info), FG_OK, NULL);
    if (applied) *applied = info.grain_applied;
    fg_context_destroy(ctx);
}

static int apply_to(fg_context* ctx, const test_frame* src, test_frame* out, const fg_frame_info* in) {
    fg_frame_info info;
    fg_frame_info_init(&info);
    if (in) info = *in;
    CHECK_STATUS(ctx, fg_context_apply(ctx, &src->frame, &out->frame, &info), FG_OK, NULL);
    return info.grain_applied;
}

/* A payload gives the picture exactly what its selected set gives as fg_av1_params: the
 * set signalled for the picture's size, a reseed (update_grain_flag = 0, no T.35 header)
 * resolved from the stored set, the seed override, and no grain when no set fits or no
 * payload arrived. */
void test_afgs1_payloads(void) {
    test_frame big, small, big8, out, want;
    frame_alloc(&big, 352, 288, 10, FG_CHROMA_420, LAYOUT_PADDED);
    frame_alloc(&small, 176, 144, 10, FG_CHROMA_420, LAYOUT_BOTTOM_UP);
    frame_alloc(&big8, 352, 288, 8, FG_CHROMA_420, LAYOUT_PACKED);
    frame_fill(&big, 1);
    frame_fill(&small, 2);
    frame_fill(&big8, 3);
    fg_av1_params p0, p1;
    afgs1_fixture_set0(&p0);
    afgs1_fixture_set1(&p1);
    fg_context* ctx = new_context(2);
    int applied = 0, want_applied = 0;

    /* 352x288: set 0 */
    frame_alloc(&out, 352, 288, 10, FG_CHROMA_420, LAYOUT_PACKED);
    frame_alloc(&want, 352, 288, 10, FG_CHROMA_420, LAYOUT_PACKED);
    CHECK_STATUS(ctx, fg_context_push_afgs1_t35(ctx, kAfgs1TwoSets, sizeof kAfgs1TwoSets), FG_OK, NULL);
    applied = apply_to(ctx, &big, &out, NULL);
    apply_struct(&p0, &big, &want, &want_applied);
    CHECK(applied == 1 && want_applied == 1);
    CHECK(frames_equal(&out.frame, &want.frame));
    for (int p = 0; p < 3; p++) CHECK(plane_differences(&big.frame, &out.frame, p) > 0);
    const uint32_t first = frame_checksum(&out.frame);

    /* the stored set 0 with a new seed, from a payload without the T.35 header */
    CHECK_STATUS(ctx, fg_context_push_afgs1_t35(ctx, kAfgs1ReseedBare, sizeof kAfgs1ReseedBare), FG_OK, NULL);
    applied = apply_to(ctx, &big, &out, NULL);
    fg_av1_params reseeded = p0;
    reseeded.grain_seed = kAfgs1NewSeed;
    apply_struct(&reseeded, &big, &want, NULL);
    CHECK(applied == 1);
    CHECK(frames_equal(&out.frame, &want.frame));
    CHECK(frame_checksum(&out.frame) != first);

    /* a picture with no payload of its own: no grain, and the reason */
    applied = apply_to(ctx, &big, &out, NULL);
    CHECK(applied == 0);
    CHECK(frames_equal(&out.frame, &big.frame));
    CHECK(strstr(fg_last_error(ctx), "no AFGS1 payload") != NULL);

    /* info->seed replaces the set's grain_seed, as for AV1 parameters */
    CHECK_STATUS(ctx, fg_context_push_afgs1_t35(ctx, kAfgs1TwoSets, sizeof kAfgs1TwoSets), FG_OK, NULL);
    fg_frame_info seeded;
    fg_frame_info_init(&seeded);
    seeded.has_seed = 1;
    seeded.seed = 77;
    applied = apply_to(ctx, &big, &out, &seeded);
    reseeded = p0;
    reseeded.grain_seed = 77;
    apply_struct(&reseeded, &big, &want, NULL);
    CHECK(applied == 1);
    CHECK(frames_equal(&out.frame, &want.frame));

    /* an 8-bit picture: both sets signal bit depth 10, none fits */
    test_frame out8;
    frame_alloc(&out8, 352, 288, 8, FG_CHROMA_420, LAYOUT_PACKED);
    CHECK_STATUS(ctx, fg_context_push_afgs1_t35(ctx, kAfgs1TwoSets, sizeof kAfgs1TwoSets), FG_OK, NULL);
    applied = apply_to(ctx, &big8, &out8, NULL);
    CHECK(applied == 0);
    CHECK(frames_equal(&out8.frame, &big8.frame));
    CHECK(strstr(fg_last_error(ctx), "no parameter set") != NULL && strstr(fg_last_error(ctx), "352x288") != NULL);
    frame_free(&out8);
    frame_free(&out);
    frame_free(&want);

    /* 176x144: set 1 (chroma from luma, restricted range), in place */
    test_frame small_in_place, small_want;
    frame_alloc(&small_in_place, 176, 144, 10, FG_CHROMA_420, LAYOUT_PACKED);
    frame_alloc(&small_want, 176, 144, 10, FG_CHROMA_420, LAYOUT_PACKED);
    frame_copy(&small, &small_in_place);
    CHECK_STATUS(ctx, fg_context_push_afgs1_t35(ctx, kAfgs1TwoSets, sizeof kAfgs1TwoSets), FG_OK, NULL);
    fg_frame_info info;
    fg_frame_info_init(&info);
    CHECK_STATUS(ctx, fg_context_apply(ctx, &small_in_place.frame, NULL, &info), FG_OK, NULL);
    apply_struct(&p1, &small, &small_want, NULL);
    CHECK(info.grain_applied == 1);
    CHECK(frames_equal(&small_in_place.frame, &small_want.frame));
    CHECK(plane_differences(&small.frame, &small_in_place.frame, 0) > 0);

    /* a reset forgets the stored sets: a reseed then has nothing to take */
    CHECK_STATUS(ctx, fg_context_reset(ctx), FG_OK, NULL);
    CHECK_STATUS(ctx, fg_context_push_afgs1_t35(ctx, kAfgs1ReseedBare, sizeof kAfgs1ReseedBare),
                 FG_ERROR_MALFORMED_PAYLOAD, "update_grain_flag = 0");

    frame_free(&small_in_place);
    frame_free(&small_want);
    frame_free(&big);
    frame_free(&small);
    frame_free(&big8);
    fg_context_destroy(ctx);
}

/* Truncated, mislabelled and unresolvable payloads are errors naming what is wrong; they
 * change nothing, so the payload that was waiting still applies and the context goes on. */
void test_afgs1_errors(void) {
    test_frame src, out, want;
    frame_alloc(&src, 352, 288, 10, FG_CHROMA_420, LAYOUT_PACKED);
    frame_alloc(&out, 352, 288, 10, FG_CHROMA_420, LAYOUT_PACKED);
    frame_alloc(&want, 352, 288, 10, FG_CHROMA_420, LAYOUT_PACKED);
    frame_fill(&src, 5);
    fg_av1_params p0;
    afgs1_fixture_set0(&p0);
    apply_struct(&p0, &src, &want, NULL);

    fg_context* ctx = new_context(0);
    CHECK_STATUS(ctx, fg_context_push_afgs1_t35(ctx, NULL, 10), FG_ERROR_INVALID_ARGUMENT, "payload");
    CHECK_STATUS(ctx, fg_context_push_afgs1_t35(ctx, kAfgs1TwoSets, 0), FG_ERROR_MALFORMED_PAYLOAD, "empty");
    /* a reseed before any set was signalled */
    CHECK_STATUS(ctx, fg_context_push_afgs1_t35(ctx, kAfgs1ReseedBare, sizeof kAfgs1ReseedBare),
                 FG_ERROR_MALFORMED_PAYLOAD, "film_grain_param_set_idx = 0");

    CHECK_STATUS(ctx, fg_context_push_afgs1_t35(ctx, kAfgs1TwoSets, sizeof kAfgs1TwoSets), FG_OK, NULL);
    /* every truncation of the payload is refused */
    int refused = 0;
    for (size_t n = 1; n < sizeof kAfgs1TwoSets; n++) {
        const fg_status st = fg_context_push_afgs1_t35(ctx, kAfgs1TwoSets, n);
        refused += st == FG_ERROR_MALFORMED_PAYLOAD && strlen(fg_last_error(ctx)) > 0;
    }
    CHECK(refused == (int)sizeof kAfgs1TwoSets - 1);
    CHECK_STATUS(ctx, fg_context_push_afgs1_t35(ctx, kAfgs1TwoSets, sizeof kAfgs1TwoSets / 2),
                 FG_ERROR_MALFORMED_PAYLOAD, "truncated");
    /* another provider's T.35 payload */
    uint8_t other[sizeof kAfgs1TwoSets];
    memcpy(other, kAfgs1TwoSets, sizeof other);
    other[2] = 0x91;
    CHECK_STATUS(ctx, fg_context_push_afgs1_t35(ctx, other, sizeof other), FG_ERROR_MALFORMED_PAYLOAD,
                 "itu_t_t35_terminal_provider_code = 22673");
    /* trailing garbage after the last set */
    uint8_t longer[sizeof kAfgs1TwoSets + 4];
    memcpy(longer, kAfgs1TwoSets, sizeof kAfgs1TwoSets);
    memset(longer + sizeof kAfgs1TwoSets, 0xFF, 4);
    CHECK_STATUS(ctx, fg_context_push_afgs1_t35(ctx, longer, sizeof longer), FG_ERROR_MALFORMED_PAYLOAD, "AFGS1");

    /* the valid payload pushed before the damaged ones is the one the picture takes */
    CHECK(apply_to(ctx, &src, &out, NULL) == 1);
    CHECK(frames_equal(&out.frame, &want.frame));
    /* and the context goes on */
    CHECK_STATUS(ctx, fg_context_push_afgs1_t35(ctx, kAfgs1TwoSets, sizeof kAfgs1TwoSets), FG_OK, NULL);
    CHECK(apply_to(ctx, &src, &out, NULL) == 1);
    CHECK(frames_equal(&out.frame, &want.frame));

    frame_free(&src);
    frame_free(&out);
    frame_free(&want);
    fg_context_destroy(ctx);
}

/* ---- thread counts ------------------------------------------------------------------ */

/* Threads of this process (Linux /proc/self/task); -1 when that cannot be read. */
static int process_threads(void) {
    DIR* d = opendir("/proc/self/task");
    if (!d) return -1;
    int n = 0;
    for (struct dirent* e = readdir(d); e; e = readdir(d)) n += e->d_name[0] != '.';
    closedir(d);
    return n;
}

/* Two pictures through a fresh context with `threads`; the outputs go to out[0..1]. Returns
 * the process's thread count while the context still lives. */
static int run_model(const char* model, int threads, const test_frame* src, test_frame out[2]) {
    fg_options o;
    fg_options_init(&o);
    o.threads = threads;
    if (!strcmp(model, "vtm")) o.flavour = FG_FLAVOUR_VTM;
    fg_context* ctx = NULL;
    char msg[256];
    CHECK(fg_context_create(&o, &ctx, msg, sizeof msg) == FG_OK);
    if (!ctx) return -1;
    for (int k = 0; k < 2; k++) {
        if (!strcmp(model, "av1")) {
            fg_av1_params p;
            av1_test_params(&p, 1000 + k);
            CHECK_STATUS(ctx, fg_context_push_av1_params(ctx, &p, 0), FG_OK, NULL);
        } else if (!strcmp(model, "afgs1")) {
            /* the fixture's sets target 352x288 and 176x144: the larger one is the largest
             * not above any bigger picture */
            CHECK_STATUS(ctx, fg_context_push_afgs1_t35(ctx, kAfgs1TwoSets, sizeof kAfgs1TwoSets), FG_OK, NULL);
        } else if (k == 0) {
            CHECK_STATUS(ctx, push_fgc_test_params(ctx, NULL), FG_OK, NULL);
        }
        fg_frame_info info;
        fg_frame_info_init(&info);
        info.ids.poc = 2 * k + 1;
        CHECK_STATUS(ctx, fg_context_apply(ctx, &src->frame, &out[k].frame, &info), FG_OK, NULL);
        CHECK(info.grain_applied == 1);
    }
    const int running = process_threads();
    fg_context_destroy(ctx);
    return running;
}

/* threads 1, 2, 3 and 0 (all cores) give the same samples, for the FGC flavours that split
 * pictures into stripes, AV1 parameters and AFGS1 payloads, at 1920x1080 and at an odd
 * size with many stripes of uneven share. The count reaches the synthesis: a context with
 * threads = n runs n - 1 workers beside the caller (this test starts no other thread). */
void test_thread_counts(void) {
    static const char* const models[] = {"rdd5", "vtm", "av1", "afgs1"};
    static const int sizes[][2] = {{1920, 1080}, {1001, 333}};
    static const int counts[] = {1, 2, 3, 0};
    for (int s = 0; s < 2; s++)
        for (int m = 0; m < 4; m++) {
            const int w = sizes[s][0], h = sizes[s][1];
            if (!strcmp(models[m], "vtm") && (w % 4 || h % 4)) continue; /* HM: multiples of 4 */
            test_frame src, ref[2], out[2];
            frame_alloc(&src, w, h, 10, FG_CHROMA_420, LAYOUT_PADDED);
            frame_fill(&src, 11);
            for (int k = 0; k < 2; k++) {
                frame_alloc(&ref[k], w, h, 10, FG_CHROMA_420, LAYOUT_PACKED);
                frame_alloc(&out[k], w, h, 10, FG_CHROMA_420, LAYOUT_BOTTOM_UP);
            }
            const int alone = process_threads();
            CHECK(alone >= 1);
            CHECK(run_model(models[m], counts[0], &src, ref) == alone);
            for (int k = 0; k < 2; k++) CHECK(plane_differences(&src.frame, &ref[k].frame, 0) > (long)w * h / 4);
            for (int c = 1; c < 4; c++) {
                const int running = run_model(models[m], counts[c], &src, out);
                if (counts[c] > 1) CHECK(running == alone + counts[c] - 1);
                for (int k = 0; k < 2; k++) {
                    const int same = frames_equal(&out[k].frame, &ref[k].frame);
                    if (!same)
                        fprintf(stderr, "%s %dx%d picture %d: threads %d differ from threads 1\n", models[m], w, h, k,
                                counts[c]);
                    CHECK(same);
                }
            }
            frame_free(&src);
            for (int k = 0; k < 2; k++) {
                frame_free(&ref[k]);
                frame_free(&out[k]);
            }
        }
}
