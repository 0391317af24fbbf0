// Reading an input file through its descriptor: "-" is standard input; a regular file tells
// how many bytes are left (so that a size can be checked against the file before anything
// is allocated for it); and a read that waits on a pipe or device can be cancelled from
// another thread (ReadCancellation), so that a failed run does not wait for a slow input.
#pragma once
#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace filmgrain {

// A cancel signal for blocking reads. Reads made on a thread while a Scope of a
// ReadCancellation is alive on it wait on the input and on this signal at once (poll); after
// cancel() (from any thread) they throw Error(kIo) instead of waiting.
class ReadCancellation {
public:
    ReadCancellation();
    ~ReadCancellation();
    ReadCancellation(const ReadCancellation&) = delete;
    ReadCancellation& operator=(const ReadCancellation&) = delete;

    void cancel() noexcept;
    bool cancelled() const noexcept;
    int fd() const { return fd_; }

    // The cancellation of the calling thread's reads (nullptr: none).
    static ReadCancellation* current() noexcept;
    class Scope {
    public:
        explicit Scope(ReadCancellation& c) noexcept;
        ~Scope();
        Scope(const Scope&) = delete;
        Scope& operator=(const Scope&) = delete;

    private:
        ReadCancellation* previous_;
    };

private:
    int fd_ = -1;  // an eventfd, readable once cancelled
};

class InputFile {
public:
    // Opens `path` for reading ("-": standard input, not closed). Throws Error(kIo) naming it.
    explicit InputFile(const std::string& path);
    ~InputFile();
    InputFile(const InputFile&) = delete;
    InputFile& operator=(const InputFile&) = delete;

    const std::string& path() const { return path_; }
    bool is_regular() const { return regular_; }

    // Up to n bytes into dst; fewer only at the end of the input. Throws Error(kIo) on a
    // read error or when the thread's ReadCancellation is cancelled.
    std::size_t read(void* dst, std::size_t n);
    // The next byte, or -1 at the end of the input (buffered).
    int get();
    int peek();
    // A regular file: the bytes from the current position to its end (as it is now).
    // Anything else (pipe, device, terminal): nullopt.
    std::optional<uint64_t> remaining() const;
    // Passes over n bytes (seeks in a regular file, reads elsewhere); returns how many there
    // were (fewer only at the end of the input).
    uint64_t skip(uint64_t n);

private:
    std::size_t read_fd(uint8_t* dst, std::size_t n);  // one read(2), waiting cancellably
    bool fill();
    int fd_ = -1;
    bool owns_ = false, regular_ = false;
    std::string path_;
    std::vector<uint8_t> buf_;
    std::size_t pos_ = 0, end_ = 0;
};

// The bound of read_whole_file(path): 64 MiB. Parameter files, SEI / AFGS1 payloads and grain
// tables are far smaller; a device such as /dev/zero or a huge file fails fast instead of
// filling memory.
inline constexpr std::size_t kDefaultMaxFileBytes = std::size_t(64) << 20;

// The whole of `path` ("-": standard input), at most max_bytes of it: a regular file larger
// than that fails before it is read, anything else once more than max_bytes arrive. The
// error (Error(kIo)) names the file, `what` it is meant to be and the limit.
std::vector<uint8_t> read_whole_file(const std::string& path, std::size_t max_bytes, const std::string& what);

}  // namespace filmgrain
