// The `filmgrain` command the CLI tests run, and a run that tells a crash from an error exit.
//
// FILMGRAIN_TOOL_UNDER_TEST overrides the build's tool: CTest runs the Hardening* suites
// a second time against the ASan/UBSan build of the tool (tests/CMakeLists.txt), so every
// reproducer of a crash or undefined behaviour fails there if it comes back.
#pragma once
#include <sys/wait.h>

#include <array>
#include <cstdio>
#include <cstdlib>
#include <string>

namespace filmgrain::test_support {

inline std::string tool_under_test() {
    if (const char* e = std::getenv("FILMGRAIN_TOOL_UNDER_TEST"); e && *e) return e;
#ifdef FILMGRAIN_TOOL_PATH
    return FILMGRAIN_TOOL_PATH;
#else
    return "filmgrain";
#endif
}

// How a command ended: its exit code, or the signal that killed it.
struct CommandResult {
    int exit_code = -1;  // -1 when killed by a signal
    int signal = 0;
    std::string output;  // stdout and stderr together
    bool exited_with(int code) const { return signal == 0 && exit_code == code; }
    // An orderly error exit: non-zero, not a signal, and not a sanitizer's report.
    bool clean_error() const {
        return signal == 0 && exit_code > 0 && output.find("runtime error:") == std::string::npos &&
               output.find("AddressSanitizer") == std::string::npos &&
               output.find("LeakSanitizer") == std::string::npos;
    }
    bool clean_success() const { return exited_with(0) && clean_error_free(); }
    bool clean_error_free() const {
        return output.find("runtime error:") == std::string::npos &&
               output.find("AddressSanitizer") == std::string::npos &&
               output.find("LeakSanitizer") == std::string::npos;
    }
};

// Runs a shell command line (its stderr is the caller's to redirect); a child killed by a
// signal is told apart from an error exit.
inline CommandResult run_shell(const std::string& cmd) {
    CommandResult r;
    std::FILE* p = popen(cmd.c_str(), "r");
    if (!p) return r;
    std::array<char, 4096> buf;
    std::size_t n;
    while ((n = std::fread(buf.data(), 1, buf.size(), p)) > 0) r.output.append(buf.data(), n);
    const int status = pclose(p);
    if (WIFEXITED(status)) {
        r.exit_code = WEXITSTATUS(status);
        // the shell reports a child killed by signal N as 128 + N
        if (r.exit_code > 128 && r.exit_code < 128 + 65) {
            r.signal = r.exit_code - 128;
            r.exit_code = -1;
        }
    } else if (WIFSIGNALED(status)) {
        r.signal = WTERMSIG(status);
    }
    return r;
}

// Runs `args` after the tool under test through the shell (quote them yourself).
inline CommandResult run_tool(const std::string& args) {
    return run_shell("'" + tool_under_test() + "' " + args + " 2>&1");
}

}  // namespace filmgrain::test_support
