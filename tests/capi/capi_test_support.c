#include "capi_test_support.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

int g_failures = 0;

void check_status(const fg_context* ctx, fg_status got, fg_status want, const char* needle, const char* file, int line,
                  const char* expr) {
    const char* msg = ctx ? fg_last_error(ctx) : "";
    if (got != want) {
        g_failures++;
        fprintf(stderr, "%s:%d: %s returned %s, expected %s (message: %s)\n", file, line, expr, fg_status_name(got),
                fg_status_name(want), msg);
        return;
    }
    if (needle && !strstr(msg, needle)) {
        g_failures++;
        fprintf(stderr, "%s:%d: %s: message \"%s\" does not name \"%s\"\n", file, line, expr, msg, needle);
    }
}

int plane_w(const fg_frame* f, int p) {
    const int sx = p > 0 && (f->chroma_format == FG_CHROMA_420 || f->chroma_format == FG_CHROMA_422);
    return (f->width + sx) >> sx;
}
int plane_h(const fg_frame* f, int p) {
    const int sy = p > 0 && f->chroma_format == FG_CHROMA_420;
    return (f->height + sy) >> sy;
}
static int plane_count(const fg_frame* f) { return f->chroma_format == FG_CHROMA_400 ? 1 : 3; }
static int bps(const fg_frame* f) { return f->bit_depth > 8 ? 2 : 1; }

void frame_alloc(test_frame* t, int width, int height, int bit_depth, int chroma_format, layout l) {
    memset(t, 0, sizeof *t);
    fg_frame* f = &t->frame;
    f->width = width;
    f->height = height;
    f->bit_depth = bit_depth;
    f->chroma_format = chroma_format;
    for (int p = 0; p < plane_count(f); p++) {
        const ptrdiff_t row = (ptrdiff_t)plane_w(f, p) * bps(f);
        const ptrdiff_t stride = l == LAYOUT_PACKED ? row : row + 64 + 2 * p; /* odd-ish padding */
        const int h = plane_h(f, p);
        t->buffers[p] = malloc((size_t)(stride * h));
        if (l == LAYOUT_BOTTOM_UP) {
            f->planes[p] = t->buffers[p] + stride * (h - 1);
            f->strides[p] = -stride;
        } else {
            f->planes[p] = t->buffers[p];
            f->strides[p] = stride;
        }
        memset(t->buffers[p], 0xA5, (size_t)(stride * h)); /* padding must stay untouched */
    }
}

void frame_free(test_frame* t) {
    for (int p = 0; p < 3; p++) free(t->buffers[p]);
    memset(t, 0, sizeof *t);
}

int frame_sample(const fg_frame* f, int p, int x, int y) {
    const uint8_t* row = (const uint8_t*)f->planes[p] + f->strides[p] * y;
    if (f->bit_depth > 8) {
        uint16_t v;
        memcpy(&v, row + 2 * x, 2);
        return v;
    }
    return row[x];
}

static void set_sample(fg_frame* f, int p, int x, int y, int v) {
    uint8_t* row = (uint8_t*)f->planes[p] + f->strides[p] * y;
    if (f->bit_depth > 8) {
        const uint16_t s = (uint16_t)v;
        memcpy(row + 2 * x, &s, 2);
    } else {
        row[x] = (uint8_t)v;
    }
}

void frame_fill(test_frame* t, uint32_t k) {
    fg_frame* f = &t->frame;
    uint32_t state = 0x9E3779B9u ^ (k * 2654435761u);
    const int shift = f->bit_depth - 8;
    for (int p = 0; p < plane_count(f); p++)
        for (int y = 0; y < plane_h(f, p); y++)
            for (int x = 0; x < plane_w(f, p); x++) {
                state = state * 1664525u + 1013904223u;
                /* a ramp over the whole intensity range with a little texture */
                const int base = p == 0 ? 20 + (x * 200) / plane_w(f, p) : 100 + (y * 60) / plane_h(f, p);
                const int v = ((base + (int)(state >> 29)) << shift) + (int)((state >> 8) & ((1u << shift) - 1));
                set_sample(f, p, x, y, v);
            }
}

void frame_copy(const test_frame* src, test_frame* dst) {
    for (int p = 0; p < plane_count(&src->frame); p++)
        for (int y = 0; y < plane_h(&src->frame, p); y++)
            for (int x = 0; x < plane_w(&src->frame, p); x++)
                set_sample(&dst->frame, p, x, y, frame_sample(&src->frame, p, x, y));
}

long plane_differences(const fg_frame* a, const fg_frame* b, int p) {
    long n = 0;
    for (int y = 0; y < plane_h(a, p); y++)
        for (int x = 0; x < plane_w(a, p); x++) n += frame_sample(a, p, x, y) != frame_sample(b, p, x, y);
    return n;
}

int frames_equal(const fg_frame* a, const fg_frame* b) {
    if (a->width != b->width || a->height != b->height || a->bit_depth != b->bit_depth ||
        a->chroma_format != b->chroma_format)
        return 0;
    for (int p = 0; p < plane_count(a); p++)
        if (plane_differences(a, b, p)) return 0;
    return 1;
}

uint32_t frame_checksum(const fg_frame* f) {
    uint32_t h = 2166136261u;
    for (int p = 0; p < plane_count(f); p++)
        for (int y = 0; y < plane_h(f, p); y++)
            for (int x = 0; x < plane_w(f, p); x++) {
                const int v = frame_sample(f, p, x, y);
                h = (h ^ (uint32_t)(v & 0xFF)) * 16777619u;
                h = (h ^ (uint32_t)(v >> 8)) * 16777619u;
            }
    return h;
}

void fgc_test_params(fg_fgc_params* p) {
    fg_fgc_params_init(p);
    p->log2_scale_factor = 4;
    for (int c = 0; c < 3; c++) {
        p->comp_model_present_flag[c] = 1;
        p->intensity_interval_upper_bound[c][0] = 255;
    }
    p->num_intensity_intervals_minus1[0] = 1;
    p->num_model_values_minus1[0] = 2;
    p->num_model_values_minus1[1] = 1;
    p->intensity_interval_upper_bound[0][0] = 127;
    p->intensity_interval_lower_bound[0][1] = 128;
    p->intensity_interval_upper_bound[0][1] = 255;
    const int32_t luma[2][3] = {{120, 8, 8}, {90, 10, 12}};
    for (int i = 0; i < 2; i++)
        for (int j = 0; j < 3; j++) p->comp_model_value[0][i][j] = luma[i][j];
    p->comp_model_value[1][0][0] = 60;
    p->comp_model_value[1][0][1] = 9;
    p->comp_model_value[2][0][0] = 50;
    p->persistence_flag = 1;
}

fg_status push_fgc_test_params(fg_context* ctx, const fg_picture_ids* picture) {
    /* 18 KB, on the heap: test_concurrency makes contexts on several threads at once, and a
       shared static set was being refilled by one while another pushed it (a vfgs context
       once got log2_scale_factor 0 in a fresh-clone CI run) */
    fg_fgc_params* p = malloc(sizeof *p);
    if (!p) return FG_ERROR_OUT_OF_MEMORY;
    fgc_test_params(p);
    const fg_status st = fg_context_push_fgc_params(ctx, p, FG_CODEC_HEVC, picture);
    free(p);
    return st;
}

void av1_test_params(fg_av1_params* p, int grain_seed) {
    fg_av1_params_init(p);
    p->apply_grain = 1;
    p->grain_seed = grain_seed;
    p->num_y_points = 3;
    const int yv[3] = {0, 128, 255}, ys[3] = {60, 90, 40};
    for (int i = 0; i < 3; i++) {
        p->point_y_value[i] = yv[i];
        p->point_y_scaling[i] = ys[i];
    }
    p->num_cb_points = 2;
    p->point_cb_value[0] = 0;
    p->point_cb_scaling[0] = 40;
    p->point_cb_value[1] = 255;
    p->point_cb_scaling[1] = 70;
    p->num_cr_points = 1;
    p->point_cr_value[0] = 128;
    p->point_cr_scaling[0] = 50;
    p->grain_scaling_minus_8 = 3;
    p->ar_coeff_lag = 2;
    for (int i = 0; i < 12; i++) p->ar_coeffs_y_plus_128[i] = 128 + ((i * 7) % 11) - 5;
    for (int i = 0; i < 13; i++) {
        p->ar_coeffs_cb_plus_128[i] = 128 + ((i * 5) % 9) - 4;
        p->ar_coeffs_cr_plus_128[i] = 128 - ((i * 3) % 7) + 3;
    }
    p->ar_coeff_shift_minus_6 = 1;
    p->overlap_flag = 1;
}

fg_context* make_context(const char* model, int passthrough) {
    fg_options o;
    fg_options_init(&o);
    o.passthrough_invalid = passthrough;
    if (!strcmp(model, "vtm")) o.flavour = FG_FLAVOUR_VTM;
    if (!strcmp(model, "vfgs")) {
        o.flavour = FG_FLAVOUR_VFGS;
        o.vfgs_has_seed = 1;
        o.vfgs_seed = 1234;
    }
    fg_context* ctx = NULL;
    char msg[256];
    if (fg_context_create(&o, &ctx, msg, sizeof msg) != FG_OK) {
        fprintf(stderr, "make_context(%s): %s\n", model, msg);
        g_failures++;
        return NULL;
    }
    if (!strcmp(model, "av1")) {
        fg_av1_params p;
        av1_test_params(&p, 4321);
        CHECK_STATUS(ctx, fg_context_push_av1_params(ctx, &p, 0), FG_OK, NULL);
    } else {
        CHECK_STATUS(ctx, push_fgc_test_params(ctx, NULL), FG_OK, NULL);
    }
    return ctx;
}
