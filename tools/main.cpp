// The `filmgrain` command. Each subcommand lives in its own file (cmd_*.cpp); the command
// line itself is command_line.cpp, shared with the Python module.
#include <cerrno>
#include <cstdio>
#include <cstring>

#include "command_line.hpp"

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

}  // namespace

int main(int argc, char** argv) { return finish_stdout(filmgrain::cli::run_command_line(argc, argv)); }
