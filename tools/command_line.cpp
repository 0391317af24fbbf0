#include "command_line.hpp"

#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <exception>
#include <memory>
#include <new>

#include "cli_common.hpp"
#include "core/simd_targets.hpp"
#include "filmgrain/error.hpp"
#include "filmgrain/filmgrain.h"

namespace filmgrain::cli {
namespace {

std::unique_ptr<CLI::App> make_app(bool* ran_default) {
    auto app = std::make_unique<CLI::App>(
        "filmgrain: film grain synthesis bit-exact with the FGC SEI (RDD 5, HM/VTM) and AV1 references.\n"
        "Without a subcommand it runs the demo: grain on a built-in clip, output and PNG preview in ./out/");
    app->require_subcommand(0, 1);
    // The vector target is part of the version: benchmark reports and bug reports need to say
    // which optimized kernels ran (FILMGRAIN_SIMD_TARGET may have forced one).
    app->set_version_flag("--version", [] {
        std::string available;
        for (const auto& t : simd::available_targets()) available += (available.empty() ? "" : " ") + t.name;
        return "filmgrain " + std::to_string(FG_VERSION_MAJOR) + "." + std::to_string(FG_VERSION_MINOR) + "." +
               std::to_string(FG_VERSION_PATCH) + "\nvector target: " + simd::dispatched_target() +
               " (available: " + available + ")";
    });
    register_apply(*app);
    register_render(*app);
    register_stats(*app);
    register_tradeoff(*app);
    register_analyze(*app);
    register_preset(*app);
    register_params(*app);
    register_demo(*app, ran_default);
    register_inspect(*app);
    register_decode(*app);
    register_verify(*app);
    return app;
}

}  // namespace

int run_command_line(int argc, char** argv) {
    // FILMGRAIN_SIMD_TARGET=AVX2|SSE4|EMU128|...: run the optimized kernels for that vector
    // target only (verification and benchmarks; the output is the same for every target).
    if (const char* target = std::getenv("FILMGRAIN_SIMD_TARGET"); target && *target) {
        if (!simd::force_target(std::string(target))) {
            std::string names;
            for (const auto& t : simd::available_targets()) names += " " + t.name;
            std::fprintf(stderr, "filmgrain: error: FILMGRAIN_SIMD_TARGET=%s is not available (available:%s)\n",
                         target, names.c_str());
            return 2;
        }
    }
    bool ran_default = false;
    const std::unique_ptr<CLI::App> app = make_app(&ran_default);
    try {
        app->parse(argc, argv);
        if (app->get_subcommands().empty()) return run_demo();
    } catch (const CLI::ParseError& e) {
        return app->exit(e);
    } catch (const Error& e) {
        std::fprintf(stderr, "filmgrain: error: %s\n", e.what());
        return e.code() == ErrorCode::kInvalidArgument ? 2 : 1;
    } catch (const std::bad_alloc&) {
        std::fprintf(stderr, "filmgrain: error: out of memory\n");
        return 1;
    } catch (const std::exception& e) {
        std::fprintf(stderr, "filmgrain: error: %s\n", e.what());
        return 1;
    }
    return 0;
}

void run_command_or_throw(const std::vector<std::string>& args) {
    if (args.empty()) throw Error(ErrorCode::kInvalidArgument, "no command given");
    for (const std::string& a : args)
        if (a == "--help" || a == "-h" || a == "--help-all")
            throw Error(ErrorCode::kInvalidArgument, "--help: read the command line's help (filmgrain " + args[0] +
                                                         " --help) or the docstrings");
    bool ran_default = false;
    const std::unique_ptr<CLI::App> app = make_app(&ran_default);
    try {
        parse_arguments(*app, args);
    } catch (const CLI::RuntimeError& e) {
        if (e.get_exit_code() != 0) throw CommandExit{e.get_exit_code()};
    }
}

}  // namespace filmgrain::cli
