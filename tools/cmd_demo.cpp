// The main job: grain on a built-in clip with a built-in parameter set, the result as Y4M
// and a PNG preview (clean | grainy crop, 2x) a person can look at.
#include <cmath>
#include <cstdio>
#include <filesystem>

#include "cli_common.hpp"
#include "filmgrain/session.hpp"
#include "filmgrain/error.hpp"

namespace filmgrain::cli {
namespace {

// A 352x288 clip with a slow gradient, a grey ramp and moving discs: flat areas at several
// intensities, which is where grain is most visible.
void make_builtin_frame(FrameBuffer& f, int k) {
    FrameView v = f.view();
    for (int y = 0; y < v.height; y++) {
        uint8_t* row = v.planes[0].row<uint8_t>(y);
        for (int x = 0; x < v.width; x++) {
            double base = 40 + 150.0 * x / v.width + 20 * std::sin((y + 2 * k) * 0.03);
            if (y > v.height * 3 / 4) base = 16 + 219.0 * (x / 44) / 7.0;  // 8-step grey ramp
            for (int d = 0; d < 3; d++) {
                double cx = 70 + 100 * d + 3 * k, cy = 100 + 20 * d;
                if ((x - cx) * (x - cx) + (y - cy) * (y - cy) < 900) base = 60 + 70 * d;
            }
            row[x] = uint8_t(std::lround(std::clamp(base, 0.0, 255.0)));
        }
    }
    for (int c = 1; c < 3; c++)
        for (int y = 0; y < v.planes[c].height; y++) {
            uint8_t* row = v.planes[c].row<uint8_t>(y);
            for (int x = 0; x < v.planes[c].width; x++)
                row[x] = uint8_t(128 + (c == 1 ? -1 : 1) * int(8.0 * x / v.planes[c].width));
        }
}

FgcParams builtin_params() {
    FgcParams p;
    p.log2_scale_factor = 4;
    p.comp[0].comp_model_present_flag = true;
    p.comp[0].num_model_values_minus1 = 2;
    // stronger, coarser grain in the shadows; finer grain in the highlights
    p.comp[0].intervals = {{0, 80, {160, 6, 6}}, {81, 170, {130, 8, 8}}, {171, 255, {100, 11, 11}}};
    for (int c = 1; c < 3; c++) {
        p.comp[c].comp_model_present_flag = true;
        p.comp[c].num_model_values_minus1 = 2;
        p.comp[c].intervals = {{0, 255, {40, 6, 6}}};
    }
    return p;
}

}  // namespace

int run_demo() {
    std::filesystem::create_directories("out");
    const int w = 352, h = 288, frames = 8;
    PixelFormat fmt{ChromaFormat::k420, 8};
    VideoInfo info;
    info.width = w;
    info.height = h;
    info.format = fmt;
    info.y4m = true;
    VideoWriter clean_out("out/demo-clean.y4m", info, true), grain_out("out/demo-grain.y4m", info, true);
    SessionOptions opt;
    opt.flavour = FgcFlavour::kRdd5;
    Session session(opt);
    FrameBuffer in(w, h, fmt), out(w, h, fmt);
    for (int k = 0; k < frames; k++) {
        make_builtin_frame(in, k);
        session.receive_fgc_params(builtin_params(), FgcCodec::kHevc);
        FrameInfo fi;
        fi.ids = FgcPictureIds{k, 0};
        session.apply(in.view(), out.view(), &fi);
        clean_out.write(in);
        grain_out.write(out);
        if (k == 0) {
            std::string why;
            if (write_preview_png("out/demo-preview.png", in, out, &why))
                std::printf("preview (clean | grainy, 2x): out/demo-preview.png\n");
            else
                std::printf("no PNG preview: %s\n", why.c_str());
        }
    }
    clean_out.commit();
    grain_out.commit();
    std::printf("built-in clip %dx%d yuv420p, %d frames, FGC SEI frequency-filtering model, flavour rdd5\n", w, h,
                frames);
    std::printf("clean: out/demo-clean.y4m\ngrainy: out/demo-grain.y4m\n");
    return 0;
}

void register_demo(CLI::App& app, bool* ran_default) {
    CLI::App* sub = app.add_subcommand("demo", "the main job: grain on the built-in clip, output and PNG preview in ./out/");
    sub->callback([ran_default]() {
        *ran_default = true;
        int rc = run_demo();
        if (rc) throw CLI::RuntimeError(rc);
    });
}

}  // namespace filmgrain::cli
