/* decoder_hook: how a decoder adds film grain to each picture it outputs, through the
 * installed filmgrain C API.
 *
 *   decoder_hook                                   grain on three generated frames
 *   decoder_hook IN.yuv WIDTH HEIGHT OUT.yuv [P]   grain on an 8-bit yuv420p file, with the
 *                                                  FGC parameter set of JSON file P
 *
 * Prints one line per picture (samples changed, a checksum of the output) and exits
 * non-zero on any error. */
#include <filmgrain/filmgrain.h>

#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* An FGC SEI (H.265, frequency filtering, additive) in the project's JSON form. A real
 * decoder hands over the SEI payload bytes instead: fg_context_push_fgc_sei(). */
static const char* const kDefaultParams =
    "{\"film_grain_model_id\": 0, \"blending_mode_id\": 0, \"log2_scale_factor\": 5,"
    " \"comp_model_present_flag\": [1, 1, 1],"
    " \"num_intensity_intervals_minus1\": [1, 0, 0], \"num_model_values_minus1\": [2, 0, 0],"
    " \"intensity_interval_lower_bound\": [[0, 128], [0], [0]],"
    " \"intensity_interval_upper_bound\": [[127, 255], [255], [255]],"
    " \"comp_model_value\": [[[100, 8, 8], [80, 10, 10]], [[40]], [[40]]],"
    " \"film_grain_characteristics_persistence_flag\": 1}";

static char* read_text(const char* path, size_t* length) {
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

int main(int argc, char** argv) {
    if (argc != 1 && argc != 5 && argc != 6) {
        fprintf(stderr, "usage: %s [IN.yuv WIDTH HEIGHT OUT.yuv [params.json]]\n", argv[0]);
        return 2;
    }
    const int from_file = argc > 1;
    const int width = from_file ? atoi(argv[2]) : 192, height = from_file ? atoi(argv[3]) : 128;

    fg_options options;
    fg_options_init(&options);
    options.flavour = FG_FLAVOUR_RDD5;
    fg_context* ctx = NULL;
    char message[256];
    if (fg_context_create(&options, &ctx, message, sizeof message) != FG_OK) {
        fprintf(stderr, "decoder_hook: %s\n", message);
        return 1;
    }

    size_t params_length = strlen(kDefaultParams);
    char* params = NULL;
    if (argc == 6 && !(params = read_text(argv[5], &params_length))) {
        fprintf(stderr, "decoder_hook: cannot read %s\n", argv[5]);
        return 1;
    }
    /* The SEI arrives with the first picture; persistence keeps it for the others. */
    if (fg_context_push_json(ctx, params ? params : kDefaultParams, params_length, FG_CODEC_HEVC, NULL) != FG_OK) {
        fprintf(stderr, "decoder_hook: parameters: %s\n", fg_last_error(ctx));
        return 1;
    }
    free(params);

    picture in, out;
    if (width <= 0 || height <= 0 || !picture_alloc(&in, width, height) || !picture_alloc(&out, width, height)) {
        fprintf(stderr, "decoder_hook: bad size %dx%d\n", width, height);
        return 1;
    }
    FILE* fin = from_file ? fopen(argv[1], "rb") : NULL;
    FILE* fout = from_file ? fopen(argv[4], "wb") : NULL;
    if (from_file && (!fin || !fout)) {
        fprintf(stderr, "decoder_hook: cannot open %s or %s\n", argv[1], argv[4]);
        return 1;
    }

    int status = 0;
    for (int k = 0; from_file || k < 3; k++) {
        if (from_file) {
            if (fread(in.bytes, 1, in.size, fin) != in.size) break;
        } else {
            generate(&in, k);
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
    if (fin) fclose(fin);
    if (fout && fclose(fout) != 0) status = 1;
    free(in.bytes);
    free(out.bytes);
    fg_context_destroy(ctx);
    return status;
}
