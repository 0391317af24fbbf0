// `filmgrain render`: physically based grain (the Boolean model) on a still or a video.
#include <chrono>
#include <cstdio>

#include "render_job.hpp"

namespace filmgrain::cli {

void register_render(CLI::App& app) {
    register_subcommand(app, "render",
                        "physically based grain: the Boolean model of Newson, Delon and Galerne (stills through "
                        "OpenImageIO, video as Y4M/YUV)",
                        add_render_options, [](const RenderOptions& o) {
                            RenderJob job(o);
                            RenderTotals tot;
                            const auto t0 = std::chrono::steady_clock::now();
                            job.run_all(tot);
                            const double dt = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
                            if (!o.quiet)
                                std::fprintf(stderr, "render: %s, N used per pixel %.1f (min %d, max %d), %.3f s, %.2f Mpixel/s\n",
                                             physical::algorithm_name(tot.algorithm), tot.pixels ? tot.samples / tot.pixels : 0.0,
                                             tot.max_n ? tot.min_n : 0, tot.max_n, dt, tot.pixels / dt * 1e-6);
                            return 0;
                        });
}

}  // namespace filmgrain::cli
