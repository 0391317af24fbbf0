#include "io/input_file.hpp"

#include <fcntl.h>
#include <poll.h>
#include <sys/eventfd.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstring>

#include "filmgrain/error.hpp"

namespace filmgrain {

namespace {
thread_local ReadCancellation* current_cancellation = nullptr;

std::string byte_count(std::size_t n) {
    std::string s = std::to_string(n) + " bytes";
    if (n >= (std::size_t(1) << 20) && n % (std::size_t(1) << 20) == 0)
        s += " (" + std::to_string(n >> 20) + " MiB)";
    return s;
}
}  // namespace

ReadCancellation::ReadCancellation() {
    fd_ = ::eventfd(0, EFD_CLOEXEC | EFD_NONBLOCK);
    if (fd_ < 0) throw Error(ErrorCode::kInternal, std::string("eventfd failed: ") + std::strerror(errno));
}

ReadCancellation::~ReadCancellation() { ::close(fd_); }

void ReadCancellation::cancel() noexcept {
    const uint64_t one = 1;
    // Nonblocking: a full counter (cancelled many times over) is still readable.
    [[maybe_unused]] const ssize_t n = ::write(fd_, &one, sizeof one);
}

bool ReadCancellation::cancelled() const noexcept {
    pollfd p{fd_, POLLIN, 0};
    return ::poll(&p, 1, 0) > 0 && (p.revents & POLLIN);
}

ReadCancellation* ReadCancellation::current() noexcept { return current_cancellation; }

ReadCancellation::Scope::Scope(ReadCancellation& c) noexcept : previous_(current_cancellation) {
    current_cancellation = &c;
}

ReadCancellation::Scope::~Scope() { current_cancellation = previous_; }

InputFile::InputFile(const std::string& path) : path_(path) {
    if (path == "-") {
        fd_ = STDIN_FILENO;
    } else {
        fd_ = ::open(path.c_str(), O_RDONLY | O_CLOEXEC);
        if (fd_ < 0) throw Error(ErrorCode::kIo, "cannot open input '" + path + "': " + std::strerror(errno));
        owns_ = true;
    }
    struct stat st;
    if (::fstat(fd_, &st) == 0) {
        if (S_ISDIR(st.st_mode)) {
            if (owns_) ::close(fd_);
            throw Error(ErrorCode::kIo, "cannot read input '" + path + "': it is a directory");
        }
        regular_ = S_ISREG(st.st_mode);
    }
}

InputFile::~InputFile() {
    if (owns_) ::close(fd_);
}

std::size_t InputFile::read_fd(uint8_t* dst, std::size_t n) {
    ReadCancellation* cancel = ReadCancellation::current();
    for (;;) {
        if (cancel) {
            if (cancel->cancelled()) throw Error(ErrorCode::kIo, "reading '" + path_ + "' was cancelled");
            if (!regular_) {
                // Wait for data or the cancel signal, whichever comes first.
                pollfd p[2] = {{fd_, POLLIN, 0}, {cancel->fd(), POLLIN, 0}};
                const int r = ::poll(p, 2, -1);
                if (r < 0) {
                    if (errno == EINTR) continue;
                    throw Error(ErrorCode::kIo, "read error on '" + path_ + "': " + std::strerror(errno));
                }
                if (p[1].revents & POLLIN) throw Error(ErrorCode::kIo, "reading '" + path_ + "' was cancelled");
                // POLLIN, POLLHUP or POLLERR on the input: read() tells which.
            }
        }
        const ssize_t got = ::read(fd_, dst, n);
        if (got >= 0) return std::size_t(got);
        if (errno == EINTR) continue;
        if (errno == EAGAIN || errno == EWOULDBLOCK) {
            // A nonblocking descriptor inherited as standard input: wait for it.
            pollfd p{fd_, POLLIN, 0};
            ::poll(&p, 1, cancel ? 100 : -1);
            continue;
        }
        throw Error(ErrorCode::kIo, "read error on '" + path_ + "': " + std::strerror(errno));
    }
}

bool InputFile::fill() {
    if (pos_ < end_) return true;
    if (buf_.empty()) buf_.resize(std::size_t(1) << 16);
    pos_ = end_ = 0;
    end_ = read_fd(buf_.data(), buf_.size());
    return end_ > 0;
}

std::size_t InputFile::read(void* dst, std::size_t n) {
    uint8_t* out = static_cast<uint8_t*>(dst);
    std::size_t done = 0;
    // What is buffered first, then straight into dst (large reads are not copied twice).
    if (pos_ < end_) {
        const std::size_t k = std::min(n, end_ - pos_);
        std::memcpy(out, buf_.data() + pos_, k);
        pos_ += k;
        done = k;
    }
    while (done < n) {
        const std::size_t want = n - done;
        if (want < 4096) {
            if (!fill()) break;
            const std::size_t k = std::min(want, end_ - pos_);
            std::memcpy(out + done, buf_.data() + pos_, k);
            pos_ += k;
            done += k;
            continue;
        }
        const std::size_t got = read_fd(out + done, want);
        if (got == 0) break;
        done += got;
    }
    return done;
}

int InputFile::get() {
    if (!fill()) return -1;
    return buf_[pos_++];
}

int InputFile::peek() {
    if (!fill()) return -1;
    return buf_[pos_];
}

std::optional<uint64_t> InputFile::remaining() const {
    if (!regular_) return std::nullopt;
    struct stat st;
    if (::fstat(fd_, &st) != 0) return std::nullopt;
    const off_t at = ::lseek(fd_, 0, SEEK_CUR);
    if (at < 0) return std::nullopt;
    const uint64_t buffered = end_ - pos_;
    const uint64_t position = uint64_t(at) >= buffered ? uint64_t(at) - buffered : 0;
    return uint64_t(st.st_size) > position ? uint64_t(st.st_size) - position : 0;
}

uint64_t InputFile::skip(uint64_t n) {
    const uint64_t buffered = std::min<uint64_t>(n, end_ - pos_);
    pos_ += std::size_t(buffered);
    uint64_t done = buffered;
    if (done == n) return done;
    if (const auto left = remaining()) {
        const uint64_t step = std::min<uint64_t>(n - done, *left);
        if (::lseek(fd_, off_t(step), SEEK_CUR) < 0)
            throw Error(ErrorCode::kIo, "cannot seek in '" + path_ + "': " + std::strerror(errno));
        return done + step;
    }
    uint8_t scratch[65536];
    while (done < n) {
        const std::size_t got = read(scratch, std::size_t(std::min<uint64_t>(sizeof scratch, n - done)));
        if (got == 0) break;
        done += got;
    }
    return done;
}

std::vector<uint8_t> read_whole_file(const std::string& path, std::size_t max_bytes, const std::string& what) {
    InputFile in(path);
    const std::string limit = "the limit for " + what + " is " + byte_count(max_bytes);
    std::vector<uint8_t> out;
    if (const auto left = in.remaining()) {
        if (*left > max_bytes)
            throw Error(ErrorCode::kIo, "'" + path + "' holds " + std::to_string(*left) + " bytes; " + limit);
        out.reserve(std::size_t(*left));
    }
    uint8_t buf[1 << 16];
    for (;;) {
        const std::size_t n = in.read(buf, sizeof buf);
        if (n == 0) break;
        if (n > max_bytes - out.size())
            throw Error(ErrorCode::kIo, "'" + path + "' holds more than " + byte_count(max_bytes) + "; " + limit);
        out.insert(out.end(), buf, buf + n);
    }
    return out;
}

}  // namespace filmgrain
