// Issue 24, file input/output: the tool's reproducers, each through the tool (and again
// against its ASan/UBSan build, see tests/CMakeLists.txt).
//  - sizes are checked against the picture limit and against the file before anything is
//    allocated, and whole-file reads are bounded;
//  - 10- and 12-bit samples above the bit depth are refused, naming where they are (but not
//    in the decoder output verify checks: tests/verify/decoded_above_bit_depth_test.cpp);
//  - Y4M header numbers are parsed strictly; the Y4M the tool writes is what FFmpeg reads,
//    and it reads what FFmpeg writes (every format, through Debian's ffmpeg binary);
//  - a fatal signal removes the hidden partial output and kills the tool by that signal;
//  - an error at frame 0 does not wait for a slow input;
//  - a failed write of standard output fails the command.
#include <fcntl.h>
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/resource.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <random>
#include <string>
#include <thread>
#include <vector>

#include "tool_under_test.hpp"

using namespace filmgrain::test_support;
namespace fs = std::filesystem;

namespace {

std::string quoted(const fs::path& p) { return "'" + p.string() + "'"; }

std::string read_file(const fs::path& p) {
    std::ifstream f(p, std::ios::binary);
    return std::string((std::istreambuf_iterator<char>(f)), std::istreambuf_iterator<char>());
}

void write_file(const fs::path& p, const std::string& bytes) {
    std::ofstream(p, std::ios::binary) << bytes;
}

bool under_sanitizer() {
    const std::string t = tool_under_test();
    return t.find("asan") != std::string::npos;
}


// `'tool' args` followed by the caller's own redirections (run_tool always ends with 2>&1,
// which would send the messages where stdout goes).
CommandResult run_tool_redirected(const std::string& args, const std::string& redirections) {
    return run_shell("'" + tool_under_test() + "' " + args + " " + redirections);
}

// A FIFO fed by a child process: `data`, then held open (nothing more) until the object
// goes away. A pipe that delivers one frame and then sleeps.
class SlowPipe {
public:
    SlowPipe(const fs::path& path, std::string data) : path_(path), data_(std::move(data)) {
        if (::mkfifo(path.c_str(), 0600) != 0) throw std::runtime_error("mkfifo failed");
        pid_ = ::fork();
        if (pid_ == 0) {
            const int fd = ::open(path_.c_str(), O_WRONLY);
            if (fd < 0) ::_exit(1);
            std::size_t done = 0;
            while (done < data_.size()) {
                const ssize_t n = ::write(fd, data_.data() + done, data_.size() - done);
                if (n <= 0) ::_exit(1);
                done += std::size_t(n);
            }
            ::sleep(60);  // the input stays open; the parent kills this process first
            ::_exit(0);
        }
    }
    ~SlowPipe() {
        if (pid_ > 0) {
            ::kill(pid_, SIGKILL);
            ::waitpid(pid_, nullptr, 0);
        }
    }

private:
    fs::path path_;
    std::string data_;
    pid_t pid_ = -1;
};

// The tool started directly (fork/exec), so that the test can signal it. Output to `log`.
pid_t spawn_tool(const std::vector<std::string>& args, const fs::path& log) {
    const std::string tool = tool_under_test();
    std::vector<std::string> argv_store{tool};
    argv_store.insert(argv_store.end(), args.begin(), args.end());
    std::vector<char*> argv;
    for (auto& a : argv_store) argv.push_back(a.data());
    argv.push_back(nullptr);
    const pid_t pid = ::fork();
    if (pid == 0) {
        const int fd = ::open(log.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0600);
        if (fd >= 0) {
            ::dup2(fd, 1);
            ::dup2(fd, 2);
        }
        for (int sig : {SIGINT, SIGTERM, SIGHUP, SIGQUIT}) ::signal(sig, SIG_DFL);  // not inherited as ignored
        sigset_t none;
        sigemptyset(&none);
        ::sigprocmask(SIG_SETMASK, &none, nullptr);
        const rlimit no_core{0, 0};
        ::setrlimit(RLIMIT_CORE, &no_core);  // SIGQUIT would dump core
        ::execv(tool.c_str(), argv.data());
        ::_exit(127);
    }
    return pid;
}

// waitpid with a deadline; -1 when the process is still running after it (then killed).
int wait_with_deadline(pid_t pid, std::chrono::milliseconds limit) {
    const auto end = std::chrono::steady_clock::now() + limit;
    int status = 0;
    while (std::chrono::steady_clock::now() < end) {
        if (::waitpid(pid, &status, WNOHANG) == pid) return status;
        std::this_thread::sleep_for(std::chrono::milliseconds(10));
    }
    ::kill(pid, SIGKILL);
    ::waitpid(pid, &status, 0);
    return -1;
}

std::vector<std::string> partial_outputs(const fs::path& dir) {
    std::vector<std::string> out;
    for (const auto& e : fs::directory_iterator(dir))
        if (e.path().filename().string().rfind(".filmgrain-partial-", 0) == 0) out.push_back(e.path().string());
    return out;
}

const char* kValidParams = R"({"log2_scale_factor": 5, "comp_model_present_flag": [1, 0, 0],
  "num_intensity_intervals_minus1": [0, 0, 0], "num_model_values_minus1": [2, 0, 0],
  "intensity_interval_lower_bound": [[0], [], []], "intensity_interval_upper_bound": [[255], [], []],
  "comp_model_value": [[[100, 8, 8]], [], []]})";

class HardeningIo : public ::testing::Test {
protected:
    void SetUp() override {
        // a parameterized test's name holds a '/' ("SamplesSurviveBothWays/gray"), which would
        // make a directory inside the one TearDown leaves behind
        std::string name = ::testing::UnitTest::GetInstance()->current_test_info()->name();
        std::replace(name.begin(), name.end(), '/', '-');
        dir = fs::temp_directory_path() / ("filmgrain-hardening-io-" + std::to_string(::getpid()) + "-" + name);
        fs::remove_all(dir);
        fs::create_directories(dir);
        write_file(dir / "p.json", kValidParams);
        std::string bad = kValidParams;
        bad.replace(bad.find("\"log2_scale_factor\": 5"), 22, "\"log2_scale_factor\": 9");
        write_file(dir / "bad.json", bad);
    }
    void TearDown() override { fs::remove_all(dir); }
    std::string params() const { return " -p " + quoted(dir / "p.json"); }
    fs::path dir;
};

}  // namespace

// F3: `apply -i tiny.yuv --size 65536x65536` took 29 s and 6.3 GB before it said the file
// was short; a 24 GiB frame gave a bare std::bad_alloc.
TEST_F(HardeningIo, RawSizeBeyondThePictureLimitIsRefusedBeforeReading) {
    write_file(dir / "tiny.yuv", std::string(1000, '\x80'));
    for (const char* fmt : {"yuv420p", "yuv444p16le"}) {
        const CommandResult r = run_tool("apply -i " + quoted(dir / "tiny.yuv") + " --size 65536x65536 --pix-fmt " +
                                         fmt + params() + " -o " + quoted(dir / "out.yuv"));
        ASSERT_TRUE(r.clean_error()) << r.output;
        EXPECT_NE(r.output.find("picture size 65536x65536 is out of range"), std::string::npos) << r.output;
        EXPECT_NE(r.output.find("at most 268435456 = 2^28 luma samples"), std::string::npos) << r.output;
        EXPECT_FALSE(fs::exists(dir / "out.yuv"));
    }
}

// F3: a size within the limit but larger than the file fails on the file's size, before the
// 1.5 GiB frame is allocated (the run is confined to 1 GiB of address space where it can be:
// not under ASan, which reserves terabytes).
TEST_F(HardeningIo, FrameLargerThanTheFileIsRefusedBeforeAllocating) {
    write_file(dir / "tiny.yuv", std::string(1000, '\x80'));
    const std::string args = "apply -i " + quoted(dir / "tiny.yuv") + " --size 16384x16384 --pix-fmt yuv444p16le" +
                             params() + " -o " + quoted(dir / "out.yuv");
    const CommandResult r = run_tool(args);
    CommandResult limited = r;
    if (!under_sanitizer()) limited = run_shell("ulimit -v 1048576; '" + tool_under_test() + "' " + args + " 2>&1");
    ASSERT_TRUE(r.clean_error()) << r.output;
    EXPECT_NE(r.output.find("'" + (dir / "tiny.yuv").string() +
                            "' holds 1000 bytes, less than one 16384x16384 yuv444p16le frame (1610612736 bytes)"),
              std::string::npos)
        << r.output;
    EXPECT_NE(limited.output.find("holds 1000 bytes, less than one"), std::string::npos) << limited.output;
    EXPECT_EQ(limited.output.find("out of memory"), std::string::npos) << limited.output;
    EXPECT_FALSE(fs::exists(dir / "out.yuv"));
}

// F3: a 42-byte Y4M declaring 65536x65536 did the same.
TEST_F(HardeningIo, Y4mSizeBeyondThePictureLimitIsRefused) {
    const std::string y4m = "YUV4MPEG2 W65536 H65536 F25:1 C420jpeg\nFRAME\n";
    ASSERT_EQ(y4m.size(), 45u);
    write_file(dir / "in.y4m", y4m);
    const CommandResult r = run_tool("apply -i " + quoted(dir / "in.y4m") + params() + " -o " + quoted(dir / "out.y4m"));
    ASSERT_TRUE(r.clean_error()) << r.output;
    EXPECT_NE(r.output.find("picture size 65536x65536 is out of range"), std::string::npos) << r.output;
    EXPECT_FALSE(fs::exists(dir / "out.y4m"));
}

TEST_F(HardeningIo, Y4mFrameLargerThanTheFileIsRefusedBeforeAllocating) {
    write_file(dir / "in.y4m", "YUV4MPEG2 W16384 H16384 F25:1 C444p16\nFRAME\nabc");
    const CommandResult r = run_tool("apply -i " + quoted(dir / "in.y4m") + params() + " -o " + quoted(dir / "out.y4m"));
    ASSERT_TRUE(r.clean_error()) << r.output;
    EXPECT_NE(r.output.find("holds 3 bytes of frame data, less than one 16384x16384 yuv444p16le frame (1610612736 bytes)"),
              std::string::npos)
        << r.output;
}

// 16-bit words above the declared bit depth (a wrong --pix-fmt or Y4M tag, or P010-style data
// in the high bits) were blended as unsigned 16-bit samples without a word; they are refused
// naming the frame, plane, place, value and range, and nothing is written. 16-bit formats
// take every value.
TEST_F(HardeningIo, SamplesAboveTheBitDepthAreRefusedNamingThePlaceAndTheRange) {
    const int w = 64, h = 32;
    const std::size_t frame_words = std::size_t(w) * h * 3 / 2;
    std::vector<uint16_t> words(2 * frame_words);
    std::mt19937 rng(3);
    for (auto& v : words) v = uint16_t(rng() % 1024);
    // frame 1, Cb (after the luma plane), x 5, y 3
    words[frame_words + std::size_t(w) * h + 3 * (w / 2) + 5] = 0x8000;
    const std::string bytes(reinterpret_cast<const char*>(words.data()), words.size() * 2);
    write_file(dir / "in.yuv", bytes);
    write_file(dir / "in.y4m", "YUV4MPEG2 W64 H32 F25:1 C420p10\nFRAME\n" + bytes.substr(0, frame_words * 2) +
                                   "FRAME\n" + bytes.substr(frame_words * 2));
    for (const char* in : {"in.yuv", "in.y4m"}) {
        const CommandResult r = run_tool("apply -i " + quoted(dir / in) + " --size 64x32 --pix-fmt yuv420p10le" +
                                         params() + " -o " + quoted(dir / "out.yuv"));
        ASSERT_TRUE(r.clean_error()) << r.output;
        EXPECT_NE(r.output.find("'" + (dir / in).string() +
                                "' frame 1: Cb sample 32768 at x 5, y 3 is above the 10-bit range 0..1023: is the "
                                "data yuv420p10le?"),
                  std::string::npos)
            << r.output;
        EXPECT_FALSE(fs::exists(dir / "out.yuv")) << in;
    }
    // the same words as 16-bit samples are valid (one frame of 64x32 yuv420p16le is 6144 bytes)
    const CommandResult ok = run_tool("apply -i " + quoted(dir / "in.yuv") + " --size 64x32 --pix-fmt yuv420p16le" +
                                      params() + " -o " + quoted(dir / "out.yuv"));
    EXPECT_TRUE(ok.exited_with(0)) << ok.output;
    EXPECT_EQ(fs::file_size(dir / "out.yuv"), bytes.size());
}

// Y4M header numbers: W4294967312 wrapped to 16 (atoi); every number is now digits only and
// range-checked, and the error names the tag, the value and the allowed range.
TEST_F(HardeningIo, Y4mHeaderNumbersAreParsedStrictly) {
    struct Case {
        const char* tags;
        const char* message;
    };
    const Case cases[] = {
        {"W4294967312 H16 F25:1 C420jpeg", "tag W: value '4294967312' is out of range (allowed 1..65536)"},
        {"W16 H-16 F25:1 C420jpeg", "tag H: value '-16' is not a number (allowed 1..65536)"},
        {"W16x H16 F25:1 C420jpeg", "tag W: value '16x' is not a number (allowed 1..65536)"},
        {"W16 H65537 C420jpeg", "tag H: value '65537' is out of range (allowed 1..65536)"},
        {"W16 H16 F25:0 C420jpeg", "tag F: value '25:0' is out of range (allowed N:D with N and D 1..2147483647"},
        {"W16 H16 F4294967321:1 C420jpeg", "tag F: value '4294967321:1' is out of range"},
        {"W16 H16 F25 C420jpeg", "tag F: value '25' is not a frame rate"},
        {"W16 H16 F25:1 C420p11", "tag C: value '420p11' is not supported (allowed 420jpeg"},
        {"W16 H16 F25:1 Cmono4294967304", "tag C: value 'mono4294967304' is not supported"},
    };
    for (const Case& c : cases) {
        write_file(dir / "in.y4m", std::string("YUV4MPEG2 ") + c.tags + "\nFRAME\n" + std::string(16 * 16 * 3, 'x'));
        const CommandResult r =
            run_tool("apply -i " + quoted(dir / "in.y4m") + params() + " -o " + quoted(dir / "out.y4m"));
        ASSERT_TRUE(r.clean_error()) << c.tags << "\n" << r.output;
        EXPECT_NE(r.output.find(std::string("Y4M header ") + c.message), std::string::npos) << c.tags << "\n" << r.output;
        EXPECT_FALSE(fs::exists(dir / "out.y4m")) << c.tags;
    }
}

// F3: `--sei /dev/zero` and `inspect /dev/zero` read without a bound.
TEST_F(HardeningIo, SeiPayloadFromDevZeroIsBounded) {
    write_file(dir / "in.yuv", std::string(16 * 16 * 3 / 2, '\x80'));
    const CommandResult r = run_tool("apply -i " + quoted(dir / "in.yuv") +
                                     " --size 16x16 --pix-fmt yuv420p --sei /dev/zero -o " + quoted(dir / "out.yuv"));
    ASSERT_TRUE(r.clean_error()) << r.output;
    EXPECT_NE(r.output.find("'/dev/zero'"), std::string::npos) << r.output;
    EXPECT_NE(r.output.find(" bytes"), std::string::npos) << r.output;
}

TEST_F(HardeningIo, InspectOfDevZeroFailsWithoutReadingItAll) {
    const CommandResult r = run_tool("inspect /dev/zero");
    ASSERT_TRUE(r.clean_error()) << r.output;
    EXPECT_NE(r.output.find("cannot tell the codec of '/dev/zero'"), std::string::npos) << r.output;
}

// F5: SIGINT/TERM/HUP/QUIT mid-run left a hidden .filmgrain-partial-<pid>-name beside the
// target. The temporary is removed and the tool dies by the same signal.
TEST_F(HardeningIo, FatalSignalsRemoveThePartialOutput) {
    const int frame = 176 * 144 * 3 / 2;
    for (int sig : {SIGINT, SIGTERM, SIGHUP, SIGQUIT}) {
        SCOPED_TRACE(strsignal(sig));
        const fs::path fifo = dir / ("in-" + std::to_string(sig) + ".yuv");
        SlowPipe input(fifo, std::string(std::size_t(frame) * 2, '\x80'));
        const fs::path out = dir / "out.yuv";
        const pid_t pid = spawn_tool({"apply", "-q", "-i", fifo.string(), "--size", "176x144", "--pix-fmt", "yuv420p",
                                      "-p", (dir / "p.json").string(), "-o", out.string()},
                                     dir / "log.txt");
        ASSERT_GT(pid, 0);
        // Wait for the partial output (it is opened once the input's first bytes arrived).
        const auto end = std::chrono::steady_clock::now() + std::chrono::seconds(10);
        while (partial_outputs(dir).empty() && std::chrono::steady_clock::now() < end)
            std::this_thread::sleep_for(std::chrono::milliseconds(10));
        ASSERT_EQ(partial_outputs(dir).size(), 1u) << read_file(dir / "log.txt");
        ::kill(pid, sig);
        const int status = wait_with_deadline(pid, std::chrono::seconds(5));
        ASSERT_NE(status, -1) << "the tool did not end on the signal";
        EXPECT_TRUE(WIFSIGNALED(status) && WTERMSIG(status) == sig)
            << "status " << status << ": " << read_file(dir / "log.txt");
        EXPECT_TRUE(partial_outputs(dir).empty()) << partial_outputs(dir)[0];
        EXPECT_FALSE(fs::exists(out));
        const std::string log = read_file(dir / "log.txt");
        EXPECT_EQ(log.find("AddressSanitizer"), std::string::npos) << log;
        EXPECT_EQ(log.find("runtime error:"), std::string::npos) << log;
    }
}

// F6: an error known at frame 0 waited for the reader thread to reach the end of a slow
// input (a pipe that delivers one frame, then nothing for a minute). The tool now exits
// with the error while the pipe is still open. The bound is a third of the pipe's minute:
// wide enough for a loaded CI machine or a sanitizer build, and a tool that waits still fails.
TEST_F(HardeningIo, ErrorAtFrameZeroDoesNotWaitForASlowInput) {
    const int frame = 176 * 144 * 3 / 2;
    struct Case {
        const char* what;
        std::string params, output, message;
    };
    const Case cases[] = {
        {"invalid parameters", " -p " + quoted(dir / "bad.json"), quoted(dir / "out.yuv"), "log2_scale_factor = 9"},
        {"write error", params(), "/dev/full", "/dev/full"},
    };
    int n = 0;
    for (const Case& c : cases) {
        SCOPED_TRACE(c.what);
        const fs::path fifo = dir / ("in-" + std::to_string(n++) + ".yuv");
        SlowPipe input(fifo, std::string(std::size_t(frame), '\x80'));
        const auto start = std::chrono::steady_clock::now();
        const CommandResult r = run_tool("apply -q -i " + quoted(fifo) + " --size 176x144 --pix-fmt yuv420p" +
                                         c.params + " -o " + c.output);
        const auto seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        ASSERT_TRUE(r.clean_error()) << r.output;
        EXPECT_NE(r.output.find(c.message), std::string::npos) << r.output;
        EXPECT_LT(seconds, 20.0) << "the tool waited for the input pipe";
        EXPECT_TRUE(partial_outputs(dir).empty());
    }
}

// F7: `inspect ... > /dev/full` exited 0 and the report was lost. Standard output is flushed
// and checked at the end of every command.
TEST_F(HardeningIo, FailedWriteOfStandardOutputFailsTheCommand) {
    // two H.264 access unit delimiters: a stream inspect reports on
    write_file(dir / "aud.h264", std::string("\x00\x00\x00\x01\x09\x10\x00\x00\x00\x01\x09\x10", 12));
    ASSERT_TRUE(run_tool("inspect " + quoted(dir / "aud.h264")).clean_success());
    for (const std::string args : {"inspect " + quoted(dir / "aud.h264"), "inspect --json " + quoted(dir / "aud.h264"),
                                   std::string("--help"), std::string("apply --help")}) {
        const CommandResult r = run_tool_redirected(args, "2>&1 >/dev/full");
        ASSERT_TRUE(r.clean_error()) << args << "\n" << r.output;
        EXPECT_NE(r.output.find("filmgrain: error: cannot write standard output: No space left on device"),
                  std::string::npos)
            << args << "\n" << r.output;
    }
}

// Y4M through FFmpeg (Debian's ffmpeg 5.1; tools/install-deps installs it), for every format
// the tool writes: FFmpeg reads the tool's Y4M into the same samples, and the tool reads the
// Y4M FFmpeg writes into the same samples. High-bit-depth grey was written as Cmonop16 /
// Cmonop10, which FFmpeg rejected ("Invalid data") and the tool read as bit depth 0.
class Y4mThroughFfmpeg : public HardeningIo, public ::testing::WithParamInterface<const char*> {};

TEST_P(Y4mThroughFfmpeg, SamplesSurviveBothWays) {
    ASSERT_EQ(std::system("ffmpeg -version > /dev/null 2>&1"), 0) << "ffmpeg not found (tools/install-deps installs it)";
    const std::string fmt = GetParam();
    const int depth = fmt.find("16le") != std::string::npos   ? 16
                      : fmt.find("12le") != std::string::npos ? 12
                      : fmt.find("10le") != std::string::npos ? 10
                                                              : 8;
    const bool gray = fmt.rfind("gray", 0) == 0;
    const int w = 48, h = 32, frames = 2;
    const int chroma = gray ? 0 : fmt.rfind("yuv420p", 0) == 0 ? w * h / 2 : fmt.rfind("yuv422p", 0) == 0 ? w * h : 2 * w * h;
    const int samples = (w * h + chroma) * frames;
    std::mt19937 rng(depth * 7 + int(fmt.size()));
    std::string raw;
    for (int i = 0; i < samples; i++) {
        const unsigned v = rng() & ((1u << depth) - 1);
        raw.push_back(char(v & 255));
        if (depth > 8) raw.push_back(char(v >> 8));
    }
    write_file(dir / "in.yuv", raw);
    // a parameter set that cancels grain: the pictures pass through untouched
    write_file(dir / "none.json", R"({"film_grain_characteristics_cancel_flag": 1})");
    const std::string none = " -p " + quoted(dir / "none.json");

    // ours -> FFmpeg
    CommandResult r = run_tool("apply -q -i " + quoted(dir / "in.yuv") + " --size 48x32 --pix-fmt " + fmt + none +
                               " -o " + quoted(dir / "ours.y4m"));
    ASSERT_TRUE(r.clean_success()) << r.output;
    const std::string ours = read_file(dir / "ours.y4m");
    const std::string tag = gray ? (depth == 8 ? " Cmono\n" : " Cmono" + std::to_string(depth) + "\n")
                                 : std::string(" C") + fmt.substr(3, 3) +
                                       (depth == 8 ? (fmt == "yuv420p" ? "jpeg" : "") : "p" + std::to_string(depth)) +
                                       "\n";
    EXPECT_NE(ours.substr(0, ours.find('\n') + 1).find(tag), std::string::npos) << ours.substr(0, ours.find('\n'));
    std::string log;
    ASSERT_EQ(std::system(("ffmpeg -v error -nostdin -i " + quoted(dir / "ours.y4m") + " -f rawvideo -pix_fmt " + fmt +
                           " -y " + quoted(dir / "ffmpeg.yuv") + " > " + quoted(dir / "ffmpeg.log") + " 2>&1")
                              .c_str()),
              0)
        << read_file(dir / "ffmpeg.log");
    EXPECT_TRUE(read_file(dir / "ffmpeg.yuv") == raw) << "FFmpeg read other samples from the tool's Y4M";

    // FFmpeg -> ours
    ASSERT_EQ(std::system(("ffmpeg -v error -nostdin -f rawvideo -pix_fmt " + fmt + " -s 48x32 -i " +
                           quoted(dir / "in.yuv") + " -strict -1 -f yuv4mpegpipe -y " + quoted(dir / "theirs.y4m") +
                           " > " + quoted(dir / "ffmpeg.log") + " 2>&1")
                              .c_str()),
              0)
        << read_file(dir / "ffmpeg.log");
    r = run_tool("apply -q -i " + quoted(dir / "theirs.y4m") + none + " -o " + quoted(dir / "back.yuv"));
    ASSERT_TRUE(r.clean_success()) << r.output;
    EXPECT_TRUE(read_file(dir / "back.yuv") == raw) << "the tool read other samples from FFmpeg's Y4M";
}

INSTANTIATE_TEST_SUITE_P(HardeningIo, Y4mThroughFfmpeg,
                         ::testing::Values("gray", "gray10le", "gray12le", "gray16le", "yuv420p", "yuv420p10le",
                                           "yuv420p12le", "yuv420p16le", "yuv422p", "yuv422p10le", "yuv422p12le",
                                           "yuv422p16le", "yuv444p", "yuv444p10le", "yuv444p12le", "yuv444p16le"),
                         [](const ::testing::TestParamInfo<const char*>& i) { return std::string(i.param); });
