/* Helpers of the C API tests: frames in any layout (packed, padded, bottom-up), sample
 * access, comparison, parameter sets, and a tiny check/report mechanism. */
#ifndef FILMGRAIN_CAPI_TEST_SUPPORT_H
#define FILMGRAIN_CAPI_TEST_SUPPORT_H

#include <filmgrain/filmgrain.h>
#include <stddef.h>
#include <stdint.h>

extern int g_failures;

#define CHECK(cond)                                                                      \
    do {                                                                                 \
        if (!(cond)) {                                                                   \
            g_failures++;                                                                \
            fprintf(stderr, "%s:%d: CHECK failed: %s\n", __FILE__, __LINE__, #cond);     \
        }                                                                                \
    } while (0)

/* status == want, and the context's message contains `needle` (when not NULL). */
#define CHECK_STATUS(ctx, call, want, needle) check_status((ctx), (call), (want), (needle), __FILE__, __LINE__, #call)
void check_status(const fg_context* ctx, fg_status got, fg_status want, const char* needle, const char* file, int line,
                  const char* expr);

typedef enum layout { LAYOUT_PACKED = 0, LAYOUT_PADDED = 1, LAYOUT_BOTTOM_UP = 2 } layout;

typedef struct test_frame {
    fg_frame frame;
    uint8_t* buffers[3];
} test_frame;

/* Allocates a frame; contents undefined. */
void frame_alloc(test_frame* f, int width, int height, int bit_depth, int chroma_format, layout l);
void frame_free(test_frame* f);
/* Deterministic mid-tone picture content, different per `k`. */
void frame_fill(test_frame* f, uint32_t k);
void frame_copy(const test_frame* src, test_frame* dst); /* any layouts, same format */
int frame_sample(const fg_frame* f, int plane, int x, int y);
int frames_equal(const fg_frame* a, const fg_frame* b);
/* Number of samples of plane p that differ. */
long plane_differences(const fg_frame* a, const fg_frame* b, int plane);
/* FNV-1a of every visible sample value, plane by plane. */
uint32_t frame_checksum(const fg_frame* f);
int plane_w(const fg_frame* f, int p);
int plane_h(const fg_frame* f, int p);

/* A valid FGC SEI with luma and both chroma components (persistence_flag 1): luma two
 * intervals [0,127] (120, 8, 8) and [128,255] (90, 10, 12), Cb (60, 9), Cr (50); scale 2^4. */
void fgc_test_params(fg_fgc_params* p);
/* fgc_test_params pushed for the next picture (NULL) or with `picture`. */
fg_status push_fgc_test_params(fg_context* ctx, const fg_picture_ids* picture);
/* A valid AV1 parameter set: luma and chroma points, lag 2 AR filter, overlap. */
void av1_test_params(fg_av1_params* p, int grain_seed);

/* A context for a model: "rdd5", "vtm", "vfgs" (FGC SEI from fgc_test_params) or "av1". */
fg_context* make_context(const char* model, int passthrough);

#endif
