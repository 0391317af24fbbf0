// The `filmgrain` command. Each subcommand lives in its own file (cmd_*.cpp).
#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <exception>
#include <new>

#include "cli_common.hpp"
#include "core/simd_targets.hpp"
#include "filmgrain/error.hpp"

namespace {

// Whatever a command printed to standard output is flushed and checked here, at the end of
// every command: a report written into a full disk or a closed pipe is an error, not exit 0.
// An earlier error keeps its own exit code and message.
int finish_stdout(int rc) {
    errno = 0;
    const bool failed = std::fflush(stdout) != 0 || std::ferror(stdout);
    const int err = errno;
    if (!failed) return rc;
    if (rc == 0) {
        std::fprintf(stderr, "filmgrain: error: cannot write standard output%s%s\n", err ? ": " : "",
                     err ? std::strerror(err) : "");
        return 1;
    }
    return rc;
}

int run(int argc, char** argv) {
    // FILMGRAIN_SIMD_TARGET=AVX2|SSE4|EMU128|...: run the optimized kernels for that vector
    // target only (verification and benchmarks; the output is the same for every target).
    if (const char* target = std::getenv("FILMGRAIN_SIMD_TARGET"); target && *target) {
        if (!filmgrain::simd::force_target(std::string(target))) {
            std::string names;
            for (const auto& t : filmgrain::simd::available_targets()) names += " " + t.name;
            std::fprintf(stderr, "filmgrain: error: FILMGRAIN_SIMD_TARGET=%s is not available (available:%s)\n",
                         target, names.c_str());
            return 2;
        }
    }
    CLI::App app{"filmgrain: film grain synthesis bit-exact with the FGC SEI (RDD 5, HM/VTM) and AV1 references.\n"
                 "Without a subcommand it runs the demo: grain on a built-in clip, output and PNG preview in ./out/"};
    app.require_subcommand(0, 1);
    bool ran_default = false;
    filmgrain::cli::register_apply(app);
    filmgrain::cli::register_render(app);
    filmgrain::cli::register_stats(app);
    filmgrain::cli::register_tradeoff(app);
    filmgrain::cli::register_analyze(app);
    filmgrain::cli::register_preset(app);
    filmgrain::cli::register_params(app);
    filmgrain::cli::register_demo(app, &ran_default);
    filmgrain::cli::register_inspect(app);
    filmgrain::cli::register_decode(app);
    try {
        app.parse(argc, argv);
        if (app.get_subcommands().empty()) return filmgrain::cli::run_demo();
    } catch (const CLI::ParseError& e) {
        return app.exit(e);
    } catch (const filmgrain::Error& e) {
        std::fprintf(stderr, "filmgrain: error: %s\n", e.what());
        return e.code() == filmgrain::ErrorCode::kInvalidArgument ? 2 : 1;
    } catch (const std::bad_alloc&) {
        std::fprintf(stderr, "filmgrain: error: out of memory\n");
        return 1;
    } catch (const std::exception& e) {
        std::fprintf(stderr, "filmgrain: error: %s\n", e.what());
        return 1;
    }
    return 0;
}

}  // namespace

int main(int argc, char** argv) { return finish_stdout(run(argc, argv)); }
