/* The filmgrain elements driven from C with gst-check, as an application embeds them:
 *   - a flushing seek in a running pipeline resets the stream (persistence, picture count):
 *     the pictures after it equal those of a fresh start at that point;
 *   - two pipelines with their own elements, run at once in two threads, give what each
 *     gives alone;
 *   - threads=1 and threads=2 give the same bytes;
 *   - bad payloads: on-invalid=passthrough posts a warning naming the field and keeps going,
 *     error posts an error naming it; filmgrainparse on damaged coded units warns and
 *     passes them on;
 *   - a picture without grain (no metadata or parameters, or enabled=false) leaves as the
 *     same GstBuffer and GstMemory it came in; one with grain is copied only when someone
 *     else holds it.
 * Payload files are written with libfilmgrain's C API. The suite also runs against the
 * plugin built with ASan/UBSan (CTest asan_ubsan.gst_element_check). */
#include <gst/app/gstappsink.h>
#include <gst/check/gstcheck.h>
#include <gst/check/gstharness.h>
#include <glib/gstdio.h>
#include <stdio.h>
#include <string.h>

#include "filmgrain/filmgrain.h"

static gchar* test_dir;

/* An FGC SEI payload (H.265 syntax) written with the C API: luma grain of `strength`, or a
 * cancel. */
static gchar* write_sei_file(const char* name, int strength, int cancel) {
    fg_fgc_params p;
    fg_fgc_params_init(&p);
    p.cancel_flag = cancel;
    p.log2_scale_factor = 3;
    p.comp_model_present_flag[0] = 1;
    p.num_intensity_intervals_minus1[0] = 0;
    p.num_model_values_minus1[0] = 2;
    p.intensity_interval_lower_bound[0][0] = 0;
    p.intensity_interval_upper_bound[0][0] = 255;
    p.comp_model_value[0][0][0] = strength;
    p.comp_model_value[0][0][1] = 8;
    p.comp_model_value[0][0][2] = 8;
    uint8_t bytes[512];
    size_t size = 0;
    char message[256];
    fail_unless(fg_fgc_params_to_sei(&p, FG_CODEC_HEVC, bytes, sizeof bytes, &size, message, sizeof message) == FG_OK,
                "%s", message);
    gchar* path = g_build_filename(test_dir, name, NULL);
    fail_unless(g_file_set_contents(path, (const gchar*)bytes, (gssize)size, NULL));
    return path;
}

typedef struct {
    GPtrArray* frames; /* GBytes per picture */
    gchar* error;      /* the first error message, if any */
    GPtrArray* warnings;
} RunResult;

static void run_result_clear(RunResult* r) {
    if (r->frames) g_ptr_array_unref(r->frames);
    if (r->warnings) g_ptr_array_unref(r->warnings);
    g_free(r->error);
    memset(r, 0, sizeof *r);
}

/* Pops the errors and warnings on the bus. With `await_error`, waits (up to 10 s) until an
 * error has arrived: a bin fails its state change when a child posts an error, and the
 * caller's get_state can return before that message has been forwarded to the pipeline's
 * bus (seen under ASan as an intermittent "no error"). */
static void collect_messages(GstBus* bus, RunResult* r, gboolean await_error) {
    GstMessage* m;
    const GstMessageType types = GST_MESSAGE_ERROR | GST_MESSAGE_WARNING;
    while ((m = await_error && !r->error ? gst_bus_timed_pop_filtered(bus, 10 * GST_SECOND, types)
                                         : gst_bus_pop_filtered(bus, types)) != NULL) {
        GError* e = NULL;
        gchar* debug = NULL;
        if (GST_MESSAGE_TYPE(m) == GST_MESSAGE_ERROR) {
            gst_message_parse_error(m, &e, &debug);
            if (!r->error) r->error = g_strdup(e->message);
        } else {
            gst_message_parse_warning(m, &e, &debug);
            g_ptr_array_add(r->warnings, g_strdup(e->message));
        }
        g_clear_error(&e);
        g_free(debug);
        gst_message_unref(m);
    }
}

static GstElement* make_pipeline(const gchar* filter_props) {
    gchar* desc = g_strdup_printf(
        "videotestsrc pattern=ball ! video/x-raw,format=I420,width=96,height=64,framerate=25/1 ! "
        "filmgrain name=fg %s ! appsink name=sink sync=false",
        filter_props);
    GError* error = NULL;
    GstElement* pipeline = gst_parse_launch(desc, &error);
    fail_unless(pipeline != NULL, "%s: %s", desc, error ? error->message : "?");
    g_free(desc);
    return pipeline;
}

/* Pulls pictures until EOS (or `max` pictures). */
static void pull(GstElement* pipeline, RunResult* r, guint max) {
    GstElement* sink = gst_bin_get_by_name(GST_BIN(pipeline), "sink");
    GstBus* bus = gst_element_get_bus(pipeline);
    while (r->frames->len < max) {
        GstSample* s = gst_app_sink_try_pull_sample(GST_APP_SINK(sink), 5 * GST_SECOND);
        if (!s) break;
        GstMapInfo map;
        GstBuffer* b = gst_sample_get_buffer(s);
        fail_unless(gst_buffer_map(b, &map, GST_MAP_READ));
        g_ptr_array_add(r->frames, g_bytes_new(map.data, map.size));
        gst_buffer_unmap(b, &map);
        gst_sample_unref(s);
    }
    collect_messages(bus, r, FALSE);
    gst_object_unref(bus);
    gst_object_unref(sink);
}

/* Pictures 0..kEnd-1 exist: every run seeks to its range (videotestsrc's num-buffers counts
 * buffers pushed, prerolled ones included, not a position). */
enum { kEnd = 16 };

static gboolean seek_to(GstElement* pipeline, int start_frame) {
    return gst_element_seek(pipeline, 1.0, GST_FORMAT_TIME, GST_SEEK_FLAG_FLUSH | GST_SEEK_FLAG_ACCURATE,
                            GST_SEEK_TYPE_SET, gst_util_uint64_scale(start_frame, GST_SECOND, 25), GST_SEEK_TYPE_SET,
                            gst_util_uint64_scale(kEnd, GST_SECOND, 25));
}

static void fail_with_bus_error(GstElement* pipeline, const char* what) {
    GstBus* bus = gst_element_get_bus(pipeline);
    GstMessage* m = gst_bus_pop_filtered(bus, GST_MESSAGE_ERROR);
    gst_object_unref(bus);
    GError* e = NULL;
    if (m) gst_message_parse_error(m, &e, NULL);
    fail("%s: %s", what, e ? e->message : "no error message");
}

/* Runs the pipeline from `start_frame` (a flushing seek before playing) to EOS. */
static RunResult run_from(const gchar* props, int start_frame) {
    RunResult r = {g_ptr_array_new_with_free_func((GDestroyNotify)g_bytes_unref), NULL,
                   g_ptr_array_new_with_free_func(g_free)};
    GstElement* pipeline = make_pipeline(props);
    gst_element_set_state(pipeline, GST_STATE_PAUSED);
    if (gst_element_get_state(pipeline, NULL, NULL, 5 * GST_SECOND) == GST_STATE_CHANGE_FAILURE) {
        /* an error before the first picture (a bad property): the result carries it */
        GstBus* bus = gst_element_get_bus(pipeline);
        collect_messages(bus, &r, TRUE);
        gst_object_unref(bus);
        gst_element_set_state(pipeline, GST_STATE_NULL);
        gst_object_unref(pipeline);
        return r;
    }
    fail_unless(seek_to(pipeline, start_frame));
    gst_element_set_state(pipeline, GST_STATE_PLAYING);
    pull(pipeline, &r, G_MAXUINT);
    gst_element_set_state(pipeline, GST_STATE_NULL);
    gst_object_unref(pipeline);
    return r;
}

static void assert_same_frames(const RunResult* a, guint a_from, const RunResult* b, guint b_from, guint n) {
    fail_unless(a->frames->len >= a_from + n && b->frames->len >= b_from + n, "%u/%u pictures", a->frames->len,
                b->frames->len);
    for (guint i = 0; i < n; i++)
        fail_unless(g_bytes_equal(g_ptr_array_index(a->frames, a_from + i), g_ptr_array_index(b->frames, b_from + i)),
                    "picture %u differs", i);
}

static gchar* sei_props(void) {
    /* an SEI with picture 0 and a cancel with picture 3 (pattern: pictures without a file
     * get none, and the last one stays in force) */
    gchar* grain = write_sei_file("fgc_0.bin", 60, 0);
    gchar* cancel = write_sei_file("fgc_3.bin", 0, 1);
    g_free(grain);
    g_free(cancel);
    gchar* pattern = g_build_filename(test_dir, "fgc_%d.bin", NULL);
    gchar* props = g_strdup_printf("sei=\"%s\"", pattern);
    g_free(pattern);
    return props;
}

GST_START_TEST(test_seek_resets_the_stream) {
    gchar* props = sei_props();
    RunResult fresh = run_from(props, 0);
    fail_unless_equals_int(fresh.frames->len, 16);
    /* pictures 0-2 have grain, 3 on are cancelled: they equal the source */
    RunResult plain = run_from("enabled=false", 0);
    fail_if(g_bytes_equal(g_ptr_array_index(fresh.frames, 1), g_ptr_array_index(plain.frames, 1)));
    fail_unless(g_bytes_equal(g_ptr_array_index(fresh.frames, 5), g_ptr_array_index(plain.frames, 5)));

    /* a running pipeline: 6 pictures (past the cancel), then a flushing seek to picture 8 */
    RunResult seeked = {g_ptr_array_new_with_free_func((GDestroyNotify)g_bytes_unref), NULL,
                        g_ptr_array_new_with_free_func(g_free)};
    GstElement* pipeline = make_pipeline(props);
    gst_element_set_state(pipeline, GST_STATE_PAUSED);
    if (gst_element_get_state(pipeline, NULL, NULL, 5 * GST_SECOND) == GST_STATE_CHANGE_FAILURE)
        fail_with_bus_error(pipeline, "preroll");
    fail_unless(seek_to(pipeline, 0));
    gst_element_set_state(pipeline, GST_STATE_PLAYING);
    pull(pipeline, &seeked, 6);
    fail_unless_equals_int(seeked.frames->len, 6);
    fail_unless(seek_to(pipeline, 8));
    g_ptr_array_set_size(seeked.frames, 0);
    pull(pipeline, &seeked, G_MAXUINT);
    gst_element_set_state(pipeline, GST_STATE_NULL);
    gst_object_unref(pipeline);

    RunResult at8 = run_from(props, 8);
    fail_unless_equals_int(at8.frames->len, 8);
    fail_unless_equals_int(seeked.frames->len, 8);
    assert_same_frames(&seeked, 0, &at8, 0, 8);
    /* and the grain is back after the seek (the cancel no longer in force) */
    fail_if(g_bytes_equal(g_ptr_array_index(seeked.frames, 0), g_ptr_array_index(plain.frames, 8)));
    fail_unless(seeked.error == NULL, "%s", seeked.error);
    run_result_clear(&fresh);
    run_result_clear(&plain);
    run_result_clear(&seeked);
    run_result_clear(&at8);
    g_free(props);
}
GST_END_TEST;

GST_START_TEST(test_thread_count_gives_the_same_bytes) {
    gchar* sei = write_sei_file("strong.fgc.bin", 90, 0);
    gchar* p1 = g_strdup_printf("params=\"%s\" threads=1", sei);
    gchar* p2 = g_strdup_printf("params=\"%s\" threads=2", sei);
    RunResult a = run_from(p1, 0), b = run_from(p2, 0);
    fail_unless(a.error == NULL, "%s", a.error);
    fail_unless_equals_int(a.frames->len, 16);
    assert_same_frames(&a, 0, &b, 0, 16);
    run_result_clear(&a);
    run_result_clear(&b);
    g_free(p1);
    g_free(p2);
    g_free(sei);
}
GST_END_TEST;

typedef struct {
    const gchar* props;
    RunResult result;
} ThreadRun;

static gpointer thread_run(gpointer data) {
    ThreadRun* t = data;
    t->result = run_from(t->props, 0);
    return NULL;
}

GST_START_TEST(test_two_elements_in_two_threads) {
    gchar* weak = write_sei_file("weak.fgc.bin", 20, 0);
    gchar* strong = write_sei_file("strong2.fgc.bin", 100, 0);
    ThreadRun runs[2] = {{g_strdup_printf("params=\"%s\" threads=2", weak), {0}},
                         {g_strdup_printf("params=\"%s\" threads=2 flavour=tr", strong), {0}}};
    RunResult alone[2];
    for (int i = 0; i < 2; i++) {
        alone[i] = run_from(runs[i].props, 0);
        fail_unless(alone[i].error == NULL, "%s", alone[i].error);
    }
    for (int round = 0; round < 3; round++) {
        GThread* threads[2];
        for (int i = 0; i < 2; i++) threads[i] = g_thread_new("run", thread_run, &runs[i]);
        for (int i = 0; i < 2; i++) g_thread_join(threads[i]);
        for (int i = 0; i < 2; i++) {
            assert_same_frames(&runs[i].result, 0, &alone[i], 0, 16);
            run_result_clear(&runs[i].result);
        }
    }
    fail_if(g_bytes_equal(g_ptr_array_index(alone[0].frames, 2), g_ptr_array_index(alone[1].frames, 2)));
    for (int i = 0; i < 2; i++) {
        run_result_clear(&alone[i]);
        g_free((gchar*)runs[i].props);
    }
    g_free(weak);
    g_free(strong);
}
GST_END_TEST;

static gboolean contains(const gchar* text, const gchar* what) { return text && strstr(text, what) != NULL; }

GST_START_TEST(test_bad_payload_warns_or_stops_naming_the_field) {
    /* a payload cut after its first bytes */
    gchar* path = g_build_filename(test_dir, "cut.fgc.bin", NULL);
    const guint8 cut[] = {0x00, 0x12};
    fail_unless(g_file_set_contents(path, (const gchar*)cut, sizeof cut, NULL));
    gchar* pass = g_strdup_printf("params=\"%s\" on-invalid=passthrough", path);
    RunResult r = run_from(pass, 0);
    fail_unless_equals_int(r.frames->len, 16);
    fail_unless(r.warnings->len > 0, "no warning");
    fail_unless(contains(g_ptr_array_index(r.warnings, 0), "truncated") ||
                    contains(g_ptr_array_index(r.warnings, 0), "film_grain"),
                "%s", (gchar*)g_ptr_array_index(r.warnings, 0));
    RunResult plain = run_from("enabled=false", 0);
    assert_same_frames(&r, 0, &plain, 0, 16);
    gchar* err = g_strdup_printf("params=\"%s\" on-invalid=error", path);
    RunResult e = run_from(err, 0);
    fail_unless(e.error != NULL, "no error");
    fail_unless(contains(e.error, "truncated") || contains(e.error, "film_grain"), "%s", e.error);
    fail_unless(e.frames->len == 0, "%u pictures after an error", e.frames->len);
    /* a parameter file that does not exist: an error at start naming it */
    RunResult missing = run_from("params=/nonexistent/p.json", 0);
    fail_unless(contains(missing.error, "/nonexistent/p.json"), "%s", missing.error);
    run_result_clear(&r);
    run_result_clear(&plain);
    run_result_clear(&e);
    run_result_clear(&missing);
    g_free(pass);
    g_free(err);
    g_free(path);
}
GST_END_TEST;

/* filmgrainparse on damaged and hostile coded units: warnings, the units passed on, a meta
 * carrying the FGC payload of an intact SEI. */
GST_START_TEST(test_parse_survives_damaged_units) {
    GstHarness* h = gst_harness_new("filmgrainparse");
    gst_harness_set_src_caps_str(h, "video/x-h265,stream-format=byte-stream,alignment=au");
    /* prefix SEI NAL unit (type 39) with an FGC message (type 19) of 4 bytes, then garbage */
    const guint8 sei[] = {0, 0, 0, 1, 0x4E, 0x01, 19, 4, 0x00, 0x50, 0x00, 0x80, 0x80};
    const guint8 junk[] = {0, 0, 1, 0xFF, 0xFF, 0xFF, 0, 0, 1, 0x4E, 0x01, 19, 200, 0x80, 0, 0, 0};
    const guint8* units[] = {sei, junk};
    const gsize sizes[] = {sizeof sei, sizeof junk};
    for (int i = 0; i < 2; i++) {
        GstBuffer* in = gst_buffer_new_memdup(units[i], sizes[i]);
        fail_unless_equals_int(gst_harness_push(h, in), GST_FLOW_OK);
        GstBuffer* out = gst_harness_pull(h);
        fail_unless(out != NULL);
        if (i == 0) fail_unless(gst_buffer_get_meta(out, g_type_from_name("GstFilmGrainMetaAPI")) != NULL);
        gst_buffer_unref(out);
    }
    /* random bytes */
    GRand* rand = g_rand_new_with_seed(7);
    for (int i = 0; i < 200; i++) {
        guint8 bytes[256];
        const gsize n = (gsize)g_rand_int_range(rand, 1, sizeof bytes);
        for (gsize k = 0; k < n; k++) bytes[k] = (guint8)g_rand_int_range(rand, 0, 256);
        if (n > 4) bytes[0] = bytes[1] = 0, bytes[2] = 1;
        fail_unless_equals_int(gst_harness_push(h, gst_buffer_new_memdup(bytes, n)), GST_FLOW_OK);
        gst_buffer_unref(gst_harness_pull(h));
    }
    g_rand_free(rand);
    gst_harness_teardown(h);
}
GST_END_TEST;

/* What leaves filmgrain for one picture pushed through a harness: the same GstBuffer and
 * GstMemory as went in (pointer equality), and whether the bytes changed. With `hold`, the test
 * keeps its own reference to the input, so the element may not write into it. */
typedef struct {
    gboolean same_buffer, same_memory, input_bytes_kept, output_changed;
} Passage;

enum { kPicW = 64, kPicH = 48 };

static Passage pass_one(const gchar* props, gboolean hold) {
    gchar* desc = g_strdup_printf("filmgrain %s", props);
    GstHarness* h = gst_harness_new_parse(desc);
    g_free(desc);
    gst_harness_set_src_caps_str(h, "video/x-raw,format=I420,width=64,height=48,framerate=25/1");
    const gsize size = kPicW * kPicH * 3 / 2;
    GstBuffer* in = gst_buffer_new_allocate(NULL, size, NULL);
    GstMapInfo map;
    fail_unless(gst_buffer_map(in, &map, GST_MAP_WRITE));
    for (gsize i = 0; i < size; i++) map.data[i] = (guint8)(40 + (i * 7 + i / kPicW * 3) % 160);
    GBytes* before = g_bytes_new(map.data, map.size);
    gst_buffer_unmap(in, &map);
    const GstMemory* memory_in = gst_buffer_peek_memory(in, 0);
    const GstBuffer* buffer_in = in;
    if (hold) gst_buffer_ref(in);
    fail_unless_equals_int(gst_harness_push(h, in), GST_FLOW_OK);
    GstBuffer* out = gst_harness_pull(h);
    fail_unless(out != NULL);
    Passage p;
    p.same_buffer = out == buffer_in;
    p.same_memory = gst_buffer_n_memory(out) == 1 && gst_buffer_peek_memory(out, 0) == memory_in;
    fail_unless(gst_buffer_map(out, &map, GST_MAP_READ));
    p.output_changed = map.size != size || memcmp(map.data, g_bytes_get_data(before, NULL), size) != 0;
    gst_buffer_unmap(out, &map);
    p.input_bytes_kept = TRUE;
    if (hold) {
        fail_unless(gst_buffer_map(in, &map, GST_MAP_READ));
        p.input_bytes_kept = memcmp(map.data, g_bytes_get_data(before, NULL), size) == 0;
        gst_buffer_unmap(in, &map);
        gst_buffer_unref(in);
    }
    gst_buffer_unref(out);
    g_bytes_unref(before);
    gst_harness_teardown(h);
    return p;
}

/* The issue: "A picture without grain is passed through without a copy". */
GST_START_TEST(test_picture_without_grain_is_not_copied) {
    gchar* sei = write_sei_file("nocopy.fgc.bin", 90, 0);
    gchar* with_grain = g_strdup_printf("params=\"%s\"", sei);
    gchar* disabled = g_strdup_printf("params=\"%s\" enabled=false", sei);
    /* no meta and no parameters, and grain switched off: the input buffer itself leaves,
     * though the test holds a reference (a copy would be the only way to write it) */
    const gchar* without[] = {"", disabled};
    for (int i = 0; i < 2; i++) {
        Passage p = pass_one(without[i], TRUE);
        fail_unless(p.same_buffer, "filmgrain %s: another GstBuffer left than came in", without[i]);
        fail_unless(p.same_memory, "filmgrain %s: another GstMemory left than came in", without[i]);
        fail_if(p.output_changed, "filmgrain %s: the picture changed", without[i]);
    }
    /* with grain on a buffer someone else holds: a copy gets the grain, the holder's bytes stay */
    Passage held = pass_one(with_grain, TRUE);
    fail_if(held.same_buffer, "grain was written into the input GstBuffer");
    fail_if(held.same_memory, "grain was written into the input GstMemory");
    fail_unless(held.input_bytes_kept, "the input's bytes changed");
    fail_unless(held.output_changed, "no grain");
    /* with grain on a buffer the element holds alone: written in place, no copy either */
    Passage alone = pass_one(with_grain, FALSE);
    fail_unless(alone.same_memory, "a picture the element held alone was copied");
    fail_unless(alone.output_changed, "no grain");
    g_free(with_grain);
    g_free(disabled);
    g_free(sei);
}
GST_END_TEST;

static Suite* filmgrain_elements_suite(void) {
    Suite* s = suite_create("filmgrain elements");
    TCase* tc = tcase_create("elements");
    tcase_set_timeout(tc, 300);
    suite_add_tcase(s, tc);
    tcase_add_test(tc, test_seek_resets_the_stream);
    tcase_add_test(tc, test_thread_count_gives_the_same_bytes);
    tcase_add_test(tc, test_two_elements_in_two_threads);
    tcase_add_test(tc, test_bad_payload_warns_or_stops_naming_the_field);
    tcase_add_test(tc, test_parse_survives_damaged_units);
    tcase_add_test(tc, test_picture_without_grain_is_not_copied);
    return s;
}

// The files the tests wrote, all directly in test_dir, and test_dir itself.
static void remove_test_dir(void) {
    GDir* d = g_dir_open(test_dir, 0, NULL);
    if (d) {
        const gchar* name;
        while ((name = g_dir_read_name(d)) != NULL) {
            gchar* path = g_build_filename(test_dir, name, NULL);
            g_remove(path);
            g_free(path);
        }
        g_dir_close(d);
    }
    g_rmdir(test_dir);
    g_free(test_dir);
    test_dir = NULL;
}

int main(int argc, char** argv) {
    gst_check_init(&argc, &argv);
    test_dir = g_dir_make_tmp("filmgrain-gst-check-XXXXXX", NULL);
    Suite* s = filmgrain_elements_suite();
    SRunner* sr = srunner_create(s);
    srunner_set_fork_status(sr, CK_NOFORK);
    srunner_run_all(sr, CK_NORMAL);
    const int failed = srunner_ntests_failed(sr);
    srunner_free(sr);
    // FILMGRAIN_KEEP_TEST_FILES=1 keeps them for a look at a failure (as tests/cli does)
    if (g_getenv("FILMGRAIN_KEEP_TEST_FILES"))
        g_printerr("test files kept in %s\n", test_dir);
    else
        remove_test_dir();
    return failed == 0 ? 0 : 1;
}
