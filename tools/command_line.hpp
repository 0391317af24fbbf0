// The `filmgrain` command line, callable in-process: the tool's main() and the Python
// module (src/python) run the same subcommands with the same options and messages.
#pragma once
#include <string>
#include <vector>

namespace filmgrain::cli {

// Runs one command line (argv[0] is the program name) as the tool does: errors are printed
// as "filmgrain: error: ..." and turned into the exit status (2: invalid argument).
int run_command_line(int argc, char** argv);

// Runs `args` (without the program name) and throws what the command throws:
// filmgrain::Error for the tool's own errors, Error(kInvalidArgument) with CLI11's message
// for an option that does not parse, CommandExit for a command that ends with a non-zero
// status of its own (decode --strict). --help is refused (nothing to print into).
struct CommandExit {
    int status;
};
void run_command_or_throw(const std::vector<std::string>& args);

}  // namespace filmgrain::cli
