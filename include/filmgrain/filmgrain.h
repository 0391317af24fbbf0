/* filmgrain C API: film grain synthesis for a decoder, one opaque context per stream.
 *
 * Plain C (C99), stable ABI: the context is opaque; structs the caller fills carry their
 * own size (struct_size) so that later versions can append fields; enum values travel as
 * plain ints (fields and parameters), so an out-of-range value is an error, not UB.
 * No function aborts or lets an exception escape: every one returns an fg_status, and
 * fg_last_error(ctx) gives the message of the last failure on that context (naming the
 * field, its value and the allowed range where one is at fault).
 *
 * Flow per stream:
 *   fg_options o; fg_options_init(&o);  o.flavour = FG_FLAVOUR_RDD5; ...
 *   fg_context* ctx; fg_context_create(&o, &ctx, NULL, 0);
 *   for each decoded access unit:  fg_context_push_fgc_sei(...)  / fg_context_push_av1_params(...)
 *   for each output picture:       fg_context_apply(ctx, &src, &dst_or_NULL, &info)
 *   fg_context_destroy(ctx);
 *
 * Contexts share nothing: different contexts may be used from different threads at the
 * same time; one context must not be used by two threads at once. */
#ifndef FILMGRAIN_FILMGRAIN_H
#define FILMGRAIN_FILMGRAIN_H

#include <stddef.h>
#include <stdint.h>

#include "filmgrain/export.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Version of this header. The library's own is fg_version(); the ABI (SONAME) changes only
 * with the major number. */
#define FG_VERSION_MAJOR 2
#define FG_VERSION_MINOR 0
#define FG_VERSION_PATCH 0
#define FG_VERSION ((FG_VERSION_MAJOR << 16) | (FG_VERSION_MINOR << 8) | FG_VERSION_PATCH)

FG_API unsigned fg_version(void);            /* FG_VERSION of the library */
FG_API const char* fg_version_string(void);  /* "2.0.0" */

typedef enum fg_status {
    FG_OK = 0,
    FG_ERROR_INVALID_ARGUMENT = 1,   /* caller error: NULL pointer, sizes, formats, options */
    FG_ERROR_INVALID_PARAMS = 2,     /* a parameter set breaks the model's constraints */
    FG_ERROR_MALFORMED_PAYLOAD = 3,  /* a metadata payload or JSON text cannot be parsed */
    FG_ERROR_UNSUPPORTED = 4,        /* valid but not implemented (by this flavour / build) */
    FG_ERROR_IO = 5,
    FG_ERROR_OUT_OF_MEMORY = 6,
    FG_ERROR_INTERNAL = 7
} fg_status;

FG_API const char* fg_status_name(int status); /* fg_status -> "FG_ERROR_INVALID_PARAMS", ... */

/* Which bit-exact behaviour of the FGC SEI frequency-filtering model to reproduce. */
typedef enum fg_flavour {
    FG_FLAVOUR_RDD5 = 0, /* SMPTE RDD 5 (HM-2020): seed from POC + (idr_pic_id << 5) */
    FG_FLAVOUR_VTM = 1,  /* HM/VTM reference software: POC-only seed, block size by coded size */
    FG_FLAVOUR_VFGS = 2, /* InterDigital VersatileFilmGrain (TR 23002-9 7.5) */
    FG_FLAVOUR_TR = 3,   /* rdd5 plus what TR 23002-9 clause 7 allows beyond the references:
                            auto-regressive model, multiplicative blending, film grain bit depth */
    FG_FLAVOUR_FFMPEG = 4 /* what FFmpeg >= 6.1 outputs (rdd5 with FFmpeg's departures); pass the
                             decoder's uncropped picture and crop after, as FFmpeg does */
} fg_flavour;

/* How an FGC SEI persists over pictures that carry none. */
typedef enum fg_persistence {
    FG_PERSISTENCE_REFERENCE = 0, /* as HM: the last SEI is reused whatever its flag */
    FG_PERSISTENCE_SEMANTIC = 1   /* as the SEI semantics: persistence_flag = 0 (H.264:
                                     repetition_period = 0) covers its own picture only */
} fg_persistence;

typedef enum fg_codec { FG_CODEC_AVC = 0, FG_CODEC_HEVC = 1, FG_CODEC_VVC = 2 } fg_codec;

typedef enum fg_chroma_format {
    FG_CHROMA_400 = 0,
    FG_CHROMA_420 = 1,
    FG_CHROMA_422 = 2,
    FG_CHROMA_444 = 3
} fg_chroma_format;

typedef struct fg_options {
    uint32_t struct_size;     /* sizeof(fg_options); set by fg_options_init */
    int flavour;              /* fg_flavour; FGC SEI only (AV1 grain has one behaviour) */
    int persistence;          /* fg_persistence; rdd5 and vtm */
    int passthrough_invalid;  /* 1: an invalid parameter set leaves pictures untouched (as the
                                 reference decoders output them) and fg_context_apply returns
                                 FG_OK with info->grain_applied = 0 and the reason in
                                 fg_last_error; 0: fg_context_apply fails */
    int threads;              /* 0..256 workers per context, the calling thread included; 0 = all
                                 hardware threads. Pictures are split into stripes (rdd5, vtm,
                                 AV1, AFGS1); the output is identical for every count. vfgs runs
                                 on the calling thread (its random state runs through the
                                 picture in order). Threads start at the first picture with
                                 grain and wait idle between pictures. */
    int coded_width;          /* vtm: the SPS coded luma size, which picks HM's block size; */
    int coded_height;         /*      0 = the picture size rounded up to a multiple of 16 */
    int vfgs_has_seed;        /* vfgs: 1 = start the LFSR from vfgs_seed (the reference's -r) */
    uint32_t vfgs_seed;
    int vfgs_gain_percent;    /* vfgs: global grain strength in percent, default 100 */
    /* Added in 2.0; a caller with the 1.0 layout passes its smaller struct_size and gets the
       defaults for these. */
    int block_size;           /* FGC: 0 = the flavour's own; 8, 16 or 32 forces one (vfgs: 16) */
    int single_line_blocks;   /* vtm, tr: TR 23002-9 7.3.2.3 single-line blocks of 8, 16 or 32
                                 samples; 0 = square blocks */
    int pattern_interpolation; /* vfgs: 1 = TR 23002-9 7.5.4 pattern interpolation (0: the
                                  reference) */
    int vfgs_output_bit_depth; /* vfgs: 0 = the input's depth; 8 rounds 10-bit output to 8 bits
                                  (dst then has this bit_depth), the reference's --outdepth */
    int clip_to_restricted_range; /* AV1, AFGS1: -1 (default) keeps each set's flag; 0 or 1
                                     replaces it (libaom grain tables cannot carry it) */
} fg_options;

/* Defaults: rdd5, reference persistence, errors on invalid parameters, threads 0. */
FG_API void fg_options_init(fg_options* options);

typedef struct fg_context fg_context;

/* options may be NULL (defaults). On failure *out is NULL and, when message is not NULL,
 * the reason is written there (NUL-terminated, truncated to message_size). */
FG_API fg_status fg_context_create(const fg_options* options, fg_context** out, char* message, size_t message_size);
FG_API void fg_context_destroy(fg_context* ctx); /* NULL is allowed */

/* The message of the last failure (or passthrough notice) on ctx; "" when the last call
 * succeeded without notice. Valid until the next call on ctx. ctx NULL gives a fixed text. */
FG_API const char* fg_last_error(const fg_context* ctx);

/* Picture identifiers of the FGC seed derivation. */
typedef struct fg_picture_ids {
    int32_t poc;         /* PicOrderCnt (H.264: TopFieldOrderCnt of a frame); any int32 */
    int32_t idr_pic_id;  /* H.264: idr_pic_id of the latest IDR picture; 0 elsewhere */
} fg_picture_ids;
/* The FGC seed takes (POC + (idr_pic_id << 5) + colour offset) mod 256 (RDD 5; vtm without
 * the idr_pic_id term), computed modulo 2^32: every int32 value is valid. */

/* ---- metadata, handed over as it arrives ------------------------------------------- */

/* An FGC SEI message body (payloadType 19: no NAL header, no emulation prevention bytes).
 * picture: the picture it arrived with. Decoders that output in another order than they
 * decode pass the ids, and the SEI is taken by the fg_context_apply call with the same ids;
 * NULL means "the next picture applied". Several SEIs for one picture: the last pushed is
 * used. Up to 64 SEIs may wait. The payload is parsed at
 * once (FG_ERROR_MALFORMED_PAYLOAD); its values are checked against the picture format at
 * apply time (FG_ERROR_INVALID_PARAMS naming the element, its value and the allowed range,
 * e.g. comp_model_value[c][i][j] against what the SEI semantics let it carry at the film
 * grain bit depth, 0..2^bitDepth - 1 for scale factors and cut-offs; or passthrough). */
FG_API fg_status fg_context_push_fgc_sei(fg_context* ctx, const uint8_t* payload, size_t size, int codec,
                                         const fg_picture_ids* picture);

/* AV1 film_grain_params() (AV1 5.9.30) of a frame header, raw bitstream values including
 * the +128 / +256 biases. Only the first num_*_points entries and the AR coefficients the
 * lag uses are read. */
typedef struct fg_av1_params {
    uint32_t struct_size; /* sizeof(fg_av1_params); set by fg_av1_params_init */
    int apply_grain;
    int grain_seed;
    int update_grain;
    int film_grain_params_ref_idx;
    int num_y_points;
    int point_y_value[14];
    int point_y_scaling[14];
    int chroma_scaling_from_luma;
    int num_cb_points;
    int point_cb_value[10];
    int point_cb_scaling[10];
    int num_cr_points;
    int point_cr_value[10];
    int point_cr_scaling[10];
    int grain_scaling_minus_8;
    int ar_coeff_lag;
    int ar_coeffs_y_plus_128[24];
    int ar_coeffs_cb_plus_128[25];
    int ar_coeffs_cr_plus_128[25];
    int ar_coeff_shift_minus_6;
    int grain_scale_shift;
    int cb_mult, cb_luma_mult, cb_offset;
    int cr_mult, cr_luma_mult, cr_offset;
    int overlap_flag;
    int clip_to_restricted_range;
    int matrix_coefficients; /* color_config(); 0 (identity) changes the restricted chroma range */
} fg_av1_params;

/* No grain, AR coefficients 128 (zero), mult/offset at their neutral values, matrix 2. */
FG_API void fg_av1_params_init(fg_av1_params* params);

/* The film grain parameters of a frame header; they apply from the next fg_context_apply
 * until replaced. update_grain = 0 loads the parameters stored in reference slot
 * film_grain_params_ref_idx and keeps this header's grain_seed (AV1 7.20 load_grain_params);
 * the resolved parameters are then stored in every slot whose bit is set in
 * refresh_frame_flags (AV1 7.20 reference frame update). */
FG_API fg_status fg_context_push_av1_params(fg_context* ctx, const fg_av1_params* params,
                                            unsigned refresh_frame_flags);

/* ---- typed parameter sets (2.0) ---------------------------------------------------- */

/* The FGC SEI as its syntax elements (film_grain_characteristics(): H.274 8.5, H.265 D.2.20,
 * H.264 D.1.21), for decoders that parse the SEI themselves (FFmpeg's
 * AVFilmGrainH274Params carries the same). Per component c, intervals
 * 0..num_intensity_intervals_minus1[c] and model values 0..num_model_values_minus1[c] are
 * read. Values are checked as the SEI's are: at push time the syntax ranges (naming the
 * element), at apply time against the picture and the flavour. */
typedef struct fg_fgc_params {
    uint32_t struct_size; /* sizeof(fg_fgc_params); set by fg_fgc_params_init */
    int cancel_flag;      /* film_grain_characteristics_cancel_flag */
    int model_id;         /* film_grain_model_id: 0 frequency filtering, 1 auto-regression */
    int separate_colour_description_present_flag;
    int bit_depth_luma_minus8, bit_depth_chroma_minus8;
    int full_range_flag, colour_primaries, transfer_characteristics, matrix_coeffs;
    int blending_mode_id;  /* 0 additive, 1 multiplicative */
    int log2_scale_factor;
    int comp_model_present_flag[3];
    int num_intensity_intervals_minus1[3];
    int num_model_values_minus1[3];
    uint8_t intensity_interval_lower_bound[3][256];
    uint8_t intensity_interval_upper_bound[3][256];
    int32_t comp_model_value[3][256][6];
    int persistence_flag;  /* H.265 / H.266 film_grain_characteristics_persistence_flag */
    int repetition_period; /* H.264 film_grain_characteristics_repetition_period */
} fg_fgc_params;

/* Not cancelled, model 0, additive, no component, persistence 1, repetition period 1,
 * colour description 2 (unspecified). */
FG_API void fg_fgc_params_init(fg_fgc_params* params);

/* Converters between the typed set and the SEI payload bytes of `codec` (FG_CODEC_*).
 * from_sei: FG_ERROR_MALFORMED_PAYLOAD naming the syntax element. to_sei: *size is the
 * payload's length; FG_ERROR_INVALID_ARGUMENT when capacity is smaller (then *size is the
 * capacity needed). message may be NULL. */
FG_API fg_status fg_fgc_params_from_sei(const uint8_t* payload, size_t size, int codec, fg_fgc_params* out,
                                        char* message, size_t message_size);
FG_API fg_status fg_fgc_params_to_sei(const fg_fgc_params* params, int codec, uint8_t* out, size_t capacity,
                                      size_t* size, char* message, size_t message_size);

/* As fg_context_push_fgc_sei, with the set already parsed. */
FG_API fg_status fg_context_push_fgc_params(fg_context* ctx, const fg_fgc_params* params, int codec,
                                            const fg_picture_ids* picture);

/* AV1 film grain with the biases removed and chroma indexed [0] = Cb, [1] = Cr, as dav1d's
 * Dav1dFilmGrainData: a resolved set (no update_grain / reference slot; a decoder that keeps
 * the slots itself hands over what a frame uses). */
typedef struct fg_av1_grain {
    uint32_t struct_size; /* sizeof(fg_av1_grain); set by fg_av1_grain_init */
    int apply_grain;
    unsigned seed;                /* grain_seed, 0..65535 */
    int num_y_points;             /* 0..14 */
    uint8_t y_points[14][2];      /* point_y_value, point_y_scaling */
    int chroma_scaling_from_luma;
    int num_uv_points[2];         /* 0..10 */
    uint8_t uv_points[2][10][2];  /* point_cb/cr_value, point_cb/cr_scaling */
    int scaling_shift;            /* grain_scaling_minus_8 + 8: 8..11 */
    int ar_coeff_lag;             /* 0..3 */
    int ar_coeffs_y[24];          /* ar_coeffs_y_plus_128 - 128: -128..127 */
    int ar_coeffs_uv[2][25];      /* ar_coeffs_cb/cr_plus_128 - 128 */
    int ar_coeff_shift;           /* ar_coeff_shift_minus_6 + 6: 6..9 */
    int grain_scale_shift;        /* 0..3 */
    int uv_mult[2];               /* cb/cr_mult - 128: -128..127 */
    int uv_luma_mult[2];          /* cb/cr_luma_mult - 128: -128..127 */
    int uv_offset[2];             /* cb/cr_offset - 256: -256..255 */
    int overlap_flag;
    int clip_to_restricted_range;
    int matrix_coefficients;      /* color_config(); 0 (identity) changes the restricted chroma range */
} fg_av1_grain;

/* No grain, neutral multipliers and offsets (0), shifts 8 and 6, matrix 2. */
FG_API void fg_av1_grain_init(fg_av1_grain* grain);

/* Converters between the bitstream form (fg_av1_params, with update_grain = 1: a set that
 * loads from a reference slot has no values of its own) and the de-biased one. Values
 * outside what the bitstream fields carry: FG_ERROR_INVALID_PARAMS naming the field. */
FG_API fg_status fg_av1_grain_from_params(const fg_av1_params* params, fg_av1_grain* out, char* message,
                                          size_t message_size);
FG_API fg_status fg_av1_grain_to_params(const fg_av1_grain* grain, fg_av1_params* out, char* message,
                                        size_t message_size);

/* A resolved AV1 set for the pictures applied from now on (until replaced); the reference
 * slots are not touched. */
FG_API fg_status fg_context_push_av1_grain(fg_context* ctx, const fg_av1_grain* grain);

/* show_existing_frame = 1: the next picture applied takes the parameters stored in
 * slot frame_to_show_map_idx (0..7). */
FG_API fg_status fg_context_show_existing_av1_frame(fg_context* ctx, int frame_to_show_map_idx);

/* An AOM film grain synthesis 1 (AFGS1) ITU-T T.35 metadata payload, as a decoder finds it
 * in an AV1 metadata OBU (metadata_type 4) or an H.26x T.35 SEI: either starting with the
 * T.35 header (country code 0xB5, provider code 0x5890, provider oriented code 0x01) or at
 * av1_film_grain_param_sets() itself; the first byte tells which.
 * The payload is parsed at once and updates the context's 8 stored parameter sets, which
 * persist across payloads until fg_context_reset (a set with update_grain_flag = 0 takes a
 * stored set with a new seed). The payload is for the next fg_context_apply only; that
 * picture takes the set chosen by AFGS1 select_film_grain_param_set():
 *   - sets whose subsampling fits the picture's chroma_format (a luma-only set fits any)
 *     and, when the set signals one, whose bit depth equals the picture's bit_depth;
 *   - among them the first whose resolution equals the picture's width x height (in the
 *     set's apply_units_resolution_log2 units), else the largest not exceeding it (a 0x0
 *     resolution fits any size);
 *   - colour descriptions (CICP) the set signals are not compared (the context does not
 *     know the picture's); the set's matrix_coefficients is used when signalled, else 2.
 * That picture gets no grain (FG_OK, grain_applied = 0, the reason in fg_last_error) when
 * no set fits, when afgs1_enable_flag = 0 or when the set has apply_grain_flag = 0; a
 * picture with no payload pushed for it gets none either. info->seed replaces the set's
 * grain_seed as for fg_context_push_av1_params. Several payloads before one picture: each
 * updates the stored sets, the last one chooses. A truncated or malformed payload returns
 * FG_ERROR_MALFORMED_PAYLOAD naming the syntax element, its value and the allowed range;
 * the stored sets and any payload already waiting are then unchanged. */
FG_API fg_status fg_context_push_afgs1_t35(fg_context* ctx, const uint8_t* payload, size_t size);

/* (fg_context_push_json of 1.0 is gone: JSON is the tool's form, not a decoder's. A decoder
 * hands over SEI bytes, T.35 payloads or the typed sets above; `filmgrain params convert`
 * turns a JSON file into SEI or AFGS1 payload bytes.) */

/* A new coded video sequence, or a seek: forgets waiting SEIs, the parameters in force
 * and the AV1 reference slots; picture counting restarts at 0. */
FG_API fg_status fg_context_reset(fg_context* ctx);

/* ---- frames ------------------------------------------------------------------------- */

/* A picture in planar memory. Samples are uint8_t at bit depth 8 and host-order uint16_t
 * above. strides are in bytes and may be negative (planes[p] then points at the top row of
 * a bottom-up buffer). Chroma planes are ceil(width / 2) wide for 4:2:0 and 4:2:2 and
 * ceil(height / 2) high for 4:2:0. planes[1..2] are ignored for FG_CHROMA_400. Samples
 * must lie below 1 << bit_depth; the library does not scan for larger ones (a pass per
 * frame), which get unspecified grain but are never used to read outside its tables.
 * Layout rules, checked before any sample is read (FG_ERROR_INVALID_ARGUMENT naming the
 * field, e.g. "src.strides[1]" or "dst.planes[0]", and its value):
 *   - |strides[p]| is at least a row of the plane (width x bytes per sample) and at most
 *     what keeps the plane's rows within PTRDIFF_MAX bytes; any value for a one-row plane;
 *   - bit_depth > 8: planes[p] and strides[p] are even. 16-bit samples at odd addresses
 *     are not supported (they would be misaligned uint16_t reads): such planes are
 *     refused, not copied or read bytewise. Every allocator's buffers satisfy this. */
typedef struct fg_frame {
    void* planes[3];
    ptrdiff_t strides[3];
    int width;
    int height;
    int bit_depth;     /* 8..16 (AV1: 8, 10, 12) */
    int chroma_format; /* fg_chroma_format */
} fg_frame;

/* Per-picture information, in and out. */
typedef struct fg_frame_info {
    uint32_t struct_size;   /* sizeof(fg_frame_info) */
    fg_picture_ids ids;     /* in: this picture's ids (FGC seed derivation, SEI matching) */
    int has_seed;           /* in: 1 = use `seed` instead of the derived seed: */
    uint32_t seed;          /*   rdd5/vtm: the picture offset the seed is derived from (in place
                                 of POC + (idr_pic_id << 5), resp. POC); AV1: grain_seed (16
                                 bits); vfgs refuses it (the reference never reseeds) */
    int grain_applied;      /* out: 1 when grain was added to at least one plane */
} fg_frame_info;

FG_API void fg_frame_info_init(fg_frame_info* info);

/* Adds grain to src, writing dst; dst NULL (or equal to src) means in place. dst must
 * have src's size, bit depth and format. info NULL: ids count 0, 1, 2, ... from the
 * context's creation (or last reset), idr_pic_id 0. Without metadata in force the picture
 * is copied unchanged. */
FG_API fg_status fg_context_apply(fg_context* ctx, const fg_frame* src, const fg_frame* dst, fg_frame_info* info);

/* ---- stream scanning (2.0) ----------------------------------------------------------- */

/* Film grain metadata in a coded elementary stream, for players and tools that do not parse
 * the stream themselves: FGC SEI payloads (payloadType 19), ITU-T T.35 payloads (SEI
 * payloadType 4 or AV1 metadata OBUs: AFGS1 among them) and AV1 frame-header film grain, per
 * access unit (H.26x) or temporal unit (AV1), with the picture ids fg_context_apply takes.
 * Damage in one unit is a warning on that unit; scanning goes on with the next one. */
typedef enum fg_stream_codec {
    FG_STREAM_H264 = 0, /* Annex-B byte stream */
    FG_STREAM_H265 = 1,
    FG_STREAM_H266 = 2,
    FG_STREAM_AV1 = 3   /* IVF, low-overhead OBUs (Section 5) or Annex-B length-delimited */
} fg_stream_codec;

typedef struct fg_stream_scan fg_stream_scan;

/* One unit. Units are indexed in output order: by POC within each coded video sequence
 * (H.26x), in decode order for AV1. */
typedef struct fg_stream_unit {
    int decode_index;   /* its place in decode order */
    uint64_t offset;    /* its first byte in the stream */
    int has_poc;        /* H.26x: poc is known */
    int32_t poc;        /* PicOrderCntVal, for fg_picture_ids.poc */
    int32_t idr_pic_id; /* H.264 IDR pictures, else 0 */
    int sequence;       /* coded video sequence count (for fg_context_reset between them) */
    int output;         /* 0: a picture decoders drop (RASL after a CRA that starts decoding) */
    int fgc_count;      /* FGC SEI payloads: fg_stream_scan_fgc_payload */
    int t35_count;      /* T.35 payloads: fg_stream_scan_t35_payload */
    int has_av1_grain;  /* AV1 with film_grain_params_present: fg_stream_scan_av1_grain */
    int warning_count;  /* fg_stream_scan_warning */
} fg_stream_unit;

/* Scans `size` bytes of a whole elementary stream. On failure *out is NULL and `message` (if
 * not NULL) says why. The scan keeps copies of the payloads; `data` may be freed after. */
FG_API fg_status fg_stream_scan_create(const uint8_t* data, size_t size, int codec, fg_stream_scan** out,
                                       char* message, size_t message_size);
FG_API void fg_stream_scan_destroy(fg_stream_scan* scan); /* NULL is allowed */
FG_API int fg_stream_scan_unit_count(const fg_stream_scan* scan);
FG_API fg_status fg_stream_scan_unit(const fg_stream_scan* scan, int unit, fg_stream_unit* out);
/* Payload j of unit `unit`: the payloadType 19 body, for fg_context_push_fgc_sei ... */
FG_API fg_status fg_stream_scan_fgc_payload(const fg_stream_scan* scan, int unit, int j, const uint8_t** data,
                                            size_t* size);
/* ... the T.35 bytes from itu_t_t35_country_code on, for fg_context_push_afgs1_t35 ... */
FG_API fg_status fg_stream_scan_t35_payload(const fg_stream_scan* scan, int unit, int j, const uint8_t** data,
                                            size_t* size);
/* ... the unit's AFGS1 payload resolved against the parameter sets the payloads before it
 * stored, in decode order (AFGS1 stores sets in decode order; units are given in output
 * order), and written with every set's parameters present (update_grain_flag = 1): push it
 * with fg_context_push_afgs1_t35 as the units are applied in output order. The raw T.35 bytes
 * of a payload with update_grain_flag = 0, pushed in output order, would take the set stored
 * by another picture than decoding does. *data = NULL and *size = 0 when the unit has no
 * AFGS1 payload, or only a damaged one (one of the unit's warnings then names the element).
 * Several payloads in one unit: each updates the stored sets, the last one is given. */
FG_API fg_status fg_stream_scan_afgs1_payload(const fg_stream_scan* scan, int unit, const uint8_t** data,
                                              size_t* size);
/* ... the film grain of the frame an AV1 unit shows (update_grain = 0 resolved from its
 * reference slot; apply_grain = 0 for none), for fg_context_push_av1_grain. */
FG_API fg_status fg_stream_scan_av1_grain(const fg_stream_scan* scan, int unit, fg_av1_grain* out);
/* Warning j of a unit (unit -1: of the stream as a whole); NULL when there is none. Valid
 * until the scan is destroyed. */
FG_API const char* fg_stream_scan_warning(const fg_stream_scan* scan, int unit, int j);
FG_API int fg_stream_scan_stream_warning_count(const fg_stream_scan* scan);
/* Why the last failed call on `scan` failed, naming the argument and its allowed range ("" after
 * a success). */
FG_API const char* fg_stream_scan_last_error(const fg_stream_scan* scan);

#ifdef __cplusplus
}
#endif

#endif
