#include "conformance_case.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <thread>

#include <algorithm>
#include <array>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "core/md5.hpp"
#include "io/xz_file.hpp"

namespace fs = std::filesystem;

namespace filmgrain::test_support {

std::string conformance_dir() { return (fs::path(FILMGRAIN_SOURCE_DIR) / "conformance").string(); }

std::vector<std::string> list_cases(const std::string& prefix) {
    std::vector<std::string> out;
    if (!fs::exists(conformance_dir())) return out;
    for (const auto& e : fs::directory_iterator(conformance_dir())) {
        const std::string n = e.path().filename().string();
        if (e.is_directory() && n.rfind(prefix, 0) == 0 && fs::exists(e.path() / "case.json")) out.push_back(n);
    }
    std::sort(out.begin(), out.end());
    return out;
}

ConformanceCase load_case_description(const std::string& name) {
    ConformanceCase c;
    c.name = name;
    c.dir = (fs::path(conformance_dir()) / name).string();
    std::ifstream jf(fs::path(c.dir) / "case.json");
    c.json = nlohmann::json::parse(jf);
    c.width = c.json.at("width");
    c.height = c.json.at("height");
    c.frames = c.json.at("frames");
    c.format = parse_pix_fmt(c.json.at("pix_fmt").get<std::string>());
    c.output_format = parse_pix_fmt(c.json.value("output_pix_fmt", c.json.at("pix_fmt").get<std::string>()));
    return c;
}

ConformanceCase load_case(const std::string& name) {
    ConformanceCase c = load_case_description(name);
    c.input = read_xz_file((fs::path(c.dir) / "input.yuv.xz").string());
    if (fs::exists(fs::path(c.dir) / "expected.yuv.xz")) c.expected = read_xz_file((fs::path(c.dir) / "expected.yuv.xz").string());
    return c;
}

FrameBuffer ConformanceCase::input_frame(int k) const {
    FrameBuffer f(width, height, format);
    std::memcpy(f.bytes(), input.data() + frame_bytes() * std::size_t(k), frame_bytes());
    return f;
}

std::string describe_mismatch(const ConformanceCase& c, int frame, const uint8_t* got, std::size_t bytes) {
    const std::string md5 = md5_hex(got, bytes);
    if (md5 == c.expected_md5(frame)) return "";
    std::ostringstream s;
    s << c.name << " frame " << frame << ": md5 " << md5 << " != expected " << c.expected_md5(frame);
    if (c.expected.size() != c.output_frame_bytes() * std::size_t(c.frames)) {
        s << " (no expected.yuv.xz in this case to locate the first differing sample)";
        return s.str();
    }
    const uint8_t* want = c.expected.data() + c.output_frame_bytes() * std::size_t(frame);
    const PixelFormat f = c.output_format;
    const int bps = f.bit_depth > 8 ? 2 : 1;
    std::size_t off = 0;
    for (int p = 0; p < num_planes(f.chroma); p++) {
        const int pw = plane_width(f.chroma, p, c.width), ph = plane_height(f.chroma, p, c.height);
        for (int y = 0; y < ph; y++)
            for (int x = 0; x < pw; x++, off += bps) {
                const int a = bps == 2 ? got[off] | got[off + 1] << 8 : got[off];
                const int b = bps == 2 ? want[off] | want[off + 1] << 8 : want[off];
                if (a != b) {
                    s << "; first difference at plane " << p << " x " << x << " y " << y << ": got " << a
                      << ", expected " << b;
                    return s.str();
                }
            }
    }
    return s.str();
}

int run_command(const std::string& cmd, std::string* log) {
    std::FILE* p = popen((cmd + " 2>&1").c_str(), "r");
    if (!p) return -1;
    std::array<char, 4096> buf;
    std::size_t n;
    while ((n = std::fread(buf.data(), 1, buf.size(), p)) > 0)
        if (log) log->append(buf.data(), n);
    int status = pclose(p);
    return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

std::string read_through_fifo(const std::string& fifo, const std::string& cmd, int* status, bool* still_fifo,
                              std::string* log) {
    *status = -1;
    *still_fifo = false;
    if (::mkfifo(fifo.c_str(), 0600) != 0) return "";
    // the read end, and a write end of our own held until the command is done
    const int rfd = ::open(fifo.c_str(), O_RDONLY | O_NONBLOCK);
    if (rfd < 0) return "";
    ::fcntl(rfd, F_SETFL, ::fcntl(rfd, F_GETFL) & ~O_NONBLOCK);
    const int hold = ::open(fifo.c_str(), O_WRONLY);
    std::string got;
    std::thread reader([&] {
        char buf[65536];
        for (ssize_t r; (r = ::read(rfd, buf, sizeof buf)) > 0;) got.append(buf, std::size_t(r));
    });
    *status = run_command(cmd, log);
    if (hold >= 0) ::close(hold);
    reader.join();
    ::close(rfd);
    struct stat st {};
    *still_fifo = ::lstat(fifo.c_str(), &st) == 0 && S_ISFIFO(st.st_mode);
    std::filesystem::remove(fifo);
    return got;
}

}  // namespace filmgrain::test_support
