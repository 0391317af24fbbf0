// A main() for the libFuzzer harnesses of this folder without libFuzzer, so that the
// suite runs them under the ordinary compiler's ASan/UBSan build (tests/CMakeLists.txt):
//
//   fuzz_replay_<target> [--mutations N] [--seed S] DIR_OR_FILE...
//
// Every input is run as it is, then N deterministic mutations of it (bit flips, bytes set to
// random or boundary values, truncation, erased, inserted and repeated runs, a run spliced
// in from another input). The mutations depend only on the inputs and --seed, so a failure
// is reproduced by the same command; a crash, a sanitizer report or a harness's abort names
// the input and the mutation on stderr. It is not coverage-guided (the clang build,
// fuzz/CMakeLists.txt, is for that); what it gives the suite is that the harnesses' own
// checks (only filmgrain::Error escapes, write/parse round trips, documented ranges) hold
// around every real input, on every build.
#include <unistd.h>

#include <algorithm>
#include <charconv>
#include <csignal>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <string_view>
#include <system_error>
#include <vector>

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size);
// ASan/UBSan call this before they end the process (weak: absent without the sanitizers)
extern "C" void __sanitizer_set_death_callback(void (*callback)(void)) __attribute__((weak));

namespace {

// Which run is in flight, formatted before the run so that the handlers below only write it.
char g_current_run[1024];

void report_current_run() {
    const ssize_t n = write(STDERR_FILENO, g_current_run, std::strlen(g_current_run));
    (void)n;
}

extern "C" void on_fatal_signal(int sig) {
    report_current_run();
    std::signal(sig, SIG_DFL);
    std::raise(sig);
}

using Bytes = std::vector<uint8_t>;

// SplitMix64: small, and the same sequence on every platform.
struct Random {
    uint64_t state;
    uint64_t next() {
        uint64_t z = (state += 0x9E3779B97F4A7C15ull);
        z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
        z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
        return z ^ (z >> 31);
    }
    std::size_t below(std::size_t n) { return n ? static_cast<std::size_t>(next() % n) : 0; }
};

uint64_t fnv1a(const Bytes& b) {
    uint64_t h = 0xCBF29CE484222325ull;
    for (uint8_t c : b) h = (h ^ c) * 0x100000001B3ull;
    return h;
}

void mutate_once(Bytes& b, const Bytes& other, Random& r) {
    static constexpr uint8_t kBoundaries[] = {0x00, 0x01, 0x7F, 0x80, 0xFF, 0x40, 0x3F, 0xFE};
    const std::size_t n = b.size();
    switch (r.below(8)) {
        case 0:
            if (n) b[r.below(n)] ^= static_cast<uint8_t>(1u << r.below(8));
            break;
        case 1:
            if (n) b[r.below(n)] = static_cast<uint8_t>(r.next());
            break;
        case 2:
            if (n) b[r.below(n)] = kBoundaries[r.below(sizeof(kBoundaries))];
            break;
        case 3:  // truncated, as a cut file or a lost packet
            b.resize(r.below(n + 1));
            break;
        case 4: {
            if (!n) break;
            const std::size_t at = r.below(n), len = std::min(n - at, 1 + r.below(16));
            b.erase(b.begin() + static_cast<std::ptrdiff_t>(at), b.begin() + static_cast<std::ptrdiff_t>(at + len));
            break;
        }
        case 5: {
            const std::size_t at = r.below(n + 1), len = 1 + r.below(16);
            Bytes ins(len);
            for (auto& c : ins) c = static_cast<uint8_t>(r.next());
            b.insert(b.begin() + static_cast<std::ptrdiff_t>(at), ins.begin(), ins.end());
            break;
        }
        case 6: {  // a run repeated in place: duplicated units, lengths that no longer match
            if (!n) break;
            const std::size_t at = r.below(n), len = std::min(n - at, 1 + r.below(64));
            const Bytes run(b.begin() + static_cast<std::ptrdiff_t>(at), b.begin() + static_cast<std::ptrdiff_t>(at + len));
            b.insert(b.begin() + static_cast<std::ptrdiff_t>(at), run.begin(), run.end());
            break;
        }
        default: {  // a run of another input over this one: valid syntax in the wrong place
            if (other.empty() || !n) break;
            const std::size_t from = r.below(other.size()), len = std::min(other.size() - from, 1 + r.below(64));
            const std::size_t at = r.below(n);
            const std::size_t fit = std::min(len, n - at);
            std::copy_n(other.begin() + static_cast<std::ptrdiff_t>(from), fit, b.begin() + static_cast<std::ptrdiff_t>(at));
            break;
        }
    }
}

bool read_file(const std::filesystem::path& p, Bytes& out) {
    std::ifstream f(p, std::ios::binary);
    if (!f) return false;
    out.assign(std::istreambuf_iterator<char>(f), std::istreambuf_iterator<char>());
    return true;
}

int usage(const char* self) {
    std::fprintf(stderr, "usage: %s [--mutations N] [--seed S] DIR_OR_FILE...\n", self);
    return 2;
}

}  // namespace

int main(int argc, char** argv) {
    long mutations = 100;
    uint64_t seed = 1;
    std::vector<std::filesystem::path> files;
    for (int i = 1; i < argc; i++) {
        const std::string a = argv[i];
        if ((a == "--mutations" || a == "--seed") && i + 1 < argc) {
            // from_chars, not strtoull (which takes "-1" as 2^64 - 1): no wrap, and a negative count is refused
            const std::string_view v = argv[++i];
            const auto parsed = a == "--mutations" ? std::from_chars(v.data(), v.data() + v.size(), mutations)
                                                   : std::from_chars(v.data(), v.data() + v.size(), seed);
            if (parsed.ec != std::errc() || parsed.ptr != v.data() + v.size() || mutations < 0) return usage(argv[0]);
        } else if (a.rfind("--", 0) == 0) {
            return usage(argv[0]);
        } else if (std::filesystem::is_directory(a)) {
            for (const auto& e : std::filesystem::directory_iterator(a))
                if (e.is_regular_file()) files.push_back(e.path());
        } else {
            files.emplace_back(a);
        }
    }
    // directory order is the file system's: sorted, so that input i is the same everywhere
    std::sort(files.begin(), files.end());
    if (files.empty()) {
        std::fprintf(stderr, "%s: no inputs (make them with fuzz/make-seed-corpus)\n", argv[0]);
        return 2;
    }
    std::vector<Bytes> inputs(files.size());
    for (std::size_t i = 0; i < files.size(); i++)
        if (!read_file(files[i], inputs[i])) {
            std::fprintf(stderr, "%s: cannot read %s\n", argv[0], files[i].c_str());
            return 2;
        }
    if (__sanitizer_set_death_callback) __sanitizer_set_death_callback(report_current_run);
    for (int sig : {SIGABRT, SIGSEGV, SIGBUS, SIGFPE, SIGILL}) std::signal(sig, on_fatal_signal);
    long runs = 0;
    for (std::size_t i = 0; i < inputs.size(); i++) {
        std::snprintf(g_current_run, sizeof(g_current_run), "replay: failed on %s as it is\n", files[i].c_str());
        LLVMFuzzerTestOneInput(inputs[i].data(), inputs[i].size());
        runs++;
        Random r{seed ^ fnv1a(inputs[i]) ^ (0xD1B54A32D192ED03ull * (i + 1))};
        const Bytes& other = inputs[(i + 1) % inputs.size()];
        for (long m = 0; m < mutations; m++) {
            Bytes b = inputs[i];
            const std::size_t edits = 1 + r.below(4);
            for (std::size_t e = 0; e < edits; e++) mutate_once(b, other, r);
            std::snprintf(g_current_run, sizeof(g_current_run),
                          "replay: failed on mutation %ld of %s (%zu bytes; --seed %llu)\n", m, files[i].c_str(),
                          b.size(), static_cast<unsigned long long>(seed));
            LLVMFuzzerTestOneInput(b.data(), b.size());
            runs++;
        }
    }
    std::printf("%s: %zu inputs, %ld runs, every harness check held\n", argv[0], inputs.size(), runs);
    return 0;
}
