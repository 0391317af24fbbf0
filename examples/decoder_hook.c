/* decoder_hook: how a decoder adds film grain to each picture it outputs, through the
 * installed filmgrain C API.
 *
 *   decoder_hook                                   three generated frames through each way
 *                                                  metadata reaches a decoder: an FGC SEI as
 *                                                  a typed set (fg_fgc_params), AV1 frame
 *                                                  header grain de-biased (fg_av1_grain, as
 *                                                  dav1d holds it) and an AFGS1 T.35 payload
 *   decoder_hook IN.yuv WIDTH HEIGHT OUT.yuv [P]   grain on an 8-bit yuv420p file, with the
 *                                                  typed FGC set, or the FGC SEI payload in
 *                                                  file P (H.265 payloadType 19 body, as
 *                                                  `filmgrain params convert x.json -o P.bin
 *                                                  --to sei` writes it)
 *
 * Prints one line per picture (samples changed, a checksum of the output) and exits
 * non-zero on any error. */
#include <filmgrain/filmgrain.h>

#include <errno.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* An FGC SEI (H.265, frequency filtering, additive) as a decoder that parses the SEI itself
 * holds it; a decoder that does not hands over the payload bytes: fg_context_push_fgc_sei(). */
static void fgc_params(fg_fgc_params* p) {
    fg_fgc_params_init(p);
    p->log2_scale_factor = 5;
    for (int c = 0; c < 3; c++) {
        p->comp_model_present_flag[c] = 1;
        p->intensity_interval_upper_bound[c][0] = 255;
        p->comp_model_value[c][0][0] = 40;
    }
    p->num_intensity_intervals_minus1[0] = 1;
    p->num_model_values_minus1[0] = 2;
    p->intensity_interval_upper_bound[0][0] = 127;
    p->intensity_interval_lower_bound[0][1] = 128;
    p->intensity_interval_upper_bound[0][1] = 255;
    const int32_t luma[2][3] = {{100, 8, 8}, {80, 10, 10}};
    for (int i = 0; i < 2; i++)
        for (int j = 0; j < 3; j++) p->comp_model_value[0][i][j] = luma[i][j];
}

/* AV1 film grain as dav1d's Dav1dFilmGrainData holds it (biases removed). */
static void av1_grain(fg_av1_grain* g) {
    fg_av1_grain_init(g);
    g->apply_grain = 1;
    g->seed = 2024;
    g->num_y_points = 2;
    g->y_points[0][0] = 0;
    g->y_points[0][1] = 48;
    g->y_points[1][0] = 255;
    g->y_points[1][1] = 64;
    g->chroma_scaling_from_luma = 1;
    g->scaling_shift = 10;
    g->ar_coeff_lag = 1;
    const int ar[4] = {4, -6, 10, 20};
    for (int i = 0; i < 4; i++) g->ar_coeffs_y[i] = ar[i];
    g->ar_coeff_shift = 7;
    g->overlap_flag = 1;
}

/* An AFGS1 ITU-T T.35 payload (B5 5890 01 header; one set, luma grain, chroma from luma,
 * 0x0 resolution: fits any picture), as found in an AV1 metadata OBU or an H.26x T.35 SEI. */
static const uint8_t kAfgs1Payload[] = {0xb5, 0x58, 0x90, 0x01, 0x80, 0x08, 0x88, 0x3f, 0x44, 0x00, 0x00,
                                        0x00, 0x18, 0x5e, 0x00, 0x61, 0xff, 0x03, 0x01, 0x02, 0x09, 0x00};

enum { MODEL_FGC, MODEL_AV1, MODEL_AFGS1 };
static const char* const kModelNames[] = {"FGC SEI (fg_fgc_params)", "AV1 (fg_av1_grain)", "AFGS1 T.35"};

static char* read_file(const char* path, size_t* length) {
    FILE* f = fopen(path, "rb");
    if (!f) return NULL;
    char* text = NULL;
    size_t n = 0, cap = 0;
    for (;;) {
        if (n + 4096 > cap) {
            cap = cap ? cap * 2 : 8192;
            char* grown = realloc(text, cap);
            if (!grown) break;
            text = grown;
        }
        size_t got = fread(text + n, 1, cap - n, f);
        n += got;
        if (got == 0) break;
    }
    fclose(f);
    *length = n;
    return text;
}

/* One picture as a decoder would hold it: 8-bit 4:2:0 planes in one buffer. */
typedef struct picture {
    uint8_t* bytes;
    fg_frame frame;
    size_t size;
} picture;

static int picture_alloc(picture* p, int width, int height) {
    const int cw = (width + 1) / 2, ch = (height + 1) / 2;
    p->size = (size_t)width * height + 2 * (size_t)cw * ch;
    p->bytes = malloc(p->size);
    if (!p->bytes) return 0;
    memset(&p->frame, 0, sizeof p->frame);
    p->frame.planes[0] = p->bytes;
    p->frame.planes[1] = p->bytes + (size_t)width * height;
    p->frame.planes[2] = p->bytes + (size_t)width * height + (size_t)cw * ch;
    p->frame.strides[0] = width;
    p->frame.strides[1] = p->frame.strides[2] = cw;
    p->frame.width = width;
    p->frame.height = height;
    p->frame.bit_depth = 8;
    p->frame.chroma_format = FG_CHROMA_420;
    return 1;
}

static void generate(picture* p, int k) {
    const int w = p->frame.width, h = p->frame.height;
    uint8_t* y = p->frame.planes[0];
    for (int r = 0; r < h; r++)
        for (int c = 0; c < w; c++) y[(size_t)r * w + c] = (uint8_t)(16 + (c * 219) / w + k);
    memset(p->frame.planes[1], 128, p->size - (size_t)w * h);
}

static uint32_t checksum(const uint8_t* b, size_t n) {
    uint32_t s = 2166136261u; /* FNV-1a */
    for (size_t i = 0; i < n; i++) s = (s ^ b[i]) * 16777619u;
    return s;
}

/* One stream: `frames` pictures (from `fin`, or generated when it is NULL) through a context
 * that gets its metadata the way `model` arrives. Returns 0 when every picture got grain. */
static int run_stream(int model, const uint8_t* sei, size_t sei_length, int width, int height, FILE* fin,
                      FILE* fout, int frames) {
    fg_options options;
    fg_options_init(&options);
    options.flavour = FG_FLAVOUR_RDD5;
    fg_context* ctx = NULL;
    char message[256];
    if (fg_context_create(&options, &ctx, message, sizeof message) != FG_OK) {
        fprintf(stderr, "decoder_hook: %s\n", message);
        return 1;
    }
    picture in, out;
    if (width <= 0 || height <= 0 || !picture_alloc(&in, width, height) || !picture_alloc(&out, width, height)) {
        fprintf(stderr, "decoder_hook: bad size %dx%d\n", width, height);
        fg_context_destroy(ctx);
        return 1;
    }
    printf("%s\n", kModelNames[model]);
    int status = 0;
    for (int k = 0; fin || k < frames; k++) {
        if (fin) {
            if (fread(in.bytes, 1, in.size, fin) != in.size) break;
        } else {
            generate(&in, k);
        }
        /* Metadata arrives with its picture. The FGC SEI persists for the pictures after it;
         * the AV1 set stays until replaced; an AFGS1 payload is for its own picture. */
        fg_status pushed = FG_OK;
        if (model == MODEL_FGC && k == 0) {
            if (sei) {
                pushed = fg_context_push_fgc_sei(ctx, sei, sei_length, FG_CODEC_HEVC, NULL);
            } else {
                static fg_fgc_params p; /* 18 KB: not on the stack */
                fgc_params(&p);
                pushed = fg_context_push_fgc_params(ctx, &p, FG_CODEC_HEVC, NULL);
            }
        } else if (model == MODEL_AV1 && k == 0) {
            fg_av1_grain g;
            av1_grain(&g);
            pushed = fg_context_push_av1_grain(ctx, &g);
        } else if (model == MODEL_AFGS1) {
            pushed = fg_context_push_afgs1_t35(ctx, kAfgs1Payload, sizeof kAfgs1Payload);
        }
        if (pushed != FG_OK) {
            fprintf(stderr, "decoder_hook: parameters: %s\n", fg_last_error(ctx));
            status = 1;
            break;
        }
        fg_frame_info info;
        fg_frame_info_init(&info);
        info.ids.poc = k; /* the decoder's PicOrderCnt of this picture */
        if (fg_context_apply(ctx, &in.frame, &out.frame, &info) != FG_OK) {
            fprintf(stderr, "decoder_hook: frame %d: %s\n", k, fg_last_error(ctx));
            status = 1;
            break;
        }
        size_t changed = 0;
        for (size_t i = 0; i < in.size; i++) changed += in.bytes[i] != out.bytes[i];
        printf("frame %d: grain %s, %zu samples changed, checksum %08x\n", k, info.grain_applied ? "applied" : "not applied",
               changed, (unsigned)checksum(out.bytes, out.size));
        if (!info.grain_applied || changed == 0) status = 1;
        if (fout && fwrite(out.bytes, 1, out.size, fout) != out.size) {
            fprintf(stderr, "decoder_hook: write error\n");
            status = 1;
            break;
        }
    }
    free(in.bytes);
    free(out.bytes);
    fg_context_destroy(ctx);
    return status;
}

/* A picture dimension: digits only, 1..65536; 0 for anything else (atoi wraps and takes
 * "12x" as 12). */
static int dimension(const char* text) {
    char* end = NULL;
    errno = 0;
    const long v = strtol(text, &end, 10);
    if (errno || end == text || *end || v < 1 || v > 65536) return 0;
    return (int)v;
}

int main(int argc, char** argv) {
    if (argc != 1 && argc != 5 && argc != 6) {
        fprintf(stderr, "usage: %s [IN.yuv WIDTH HEIGHT OUT.yuv [sei_payload.bin]]\n", argv[0]);
        return 2;
    }
    if (argc == 1) {
        int status = 0;
        for (int model = MODEL_FGC; model <= MODEL_AFGS1; model++)
            status |= run_stream(model, NULL, 0, 192, 128, NULL, NULL, 3);
        return status;
    }
    size_t params_length = 0;
    char* params = NULL;
    if (argc == 6 && !(params = read_file(argv[5], &params_length))) {
        fprintf(stderr, "decoder_hook: cannot read %s\n", argv[5]);
        return 1;
    }
    FILE* fin = fopen(argv[1], "rb");
    FILE* fout = fopen(argv[4], "wb");
    if (!fin || !fout) {
        fprintf(stderr, "decoder_hook: cannot open %s or %s\n", argv[1], argv[4]);
        return 1;
    }
    const int width = dimension(argv[2]), height = dimension(argv[3]);
    int status = run_stream(MODEL_FGC, (const uint8_t*)params, params_length, width, height, fin, fout, 0);
    free(params);
    fclose(fin);
    if (fclose(fout) != 0) status = 1;
    return status;
}
