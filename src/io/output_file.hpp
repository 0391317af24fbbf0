// Where an output file is written so that it appears only complete (a failed run leaves
// nothing at the path), shared by every writer of the project: frames, parameter files and
// images.
#pragma once
#include <cstdio>
#include <string>

namespace filmgrain {

// True when `path` names something other than a regular file or directory: a device such as
// /dev/null, a FIFO or a socket.
bool is_stream_target(const std::string& path);

// An output at `path`, written at write_path(): a temporary beside it (its name ends with the
// target's file name, so the extension by which OpenImageIO picks a format is kept), renamed
// over `path` by commit(); destroyed without commit() it removes the temporary. "-" (standard
// output) and pipes or devices (is_stream_target) are written directly: renaming over them
// would replace the device or pipe with a plain file (and the pipe's reader would get
// nothing), and there is no file to leave half-written.
//
// While a temporary exists it is also registered for removal on SIGINT, SIGTERM, SIGHUP and
// SIGQUIT: the first OutputFile installs handlers for those signals (unless they are
// ignored, as under nohup) that remove every registered temporary and then let the process
// die by the same signal.
class OutputFile {
public:
    explicit OutputFile(std::string path);
    ~OutputFile();
    OutputFile(const OutputFile&) = delete;
    OutputFile& operator=(const OutputFile&) = delete;

    const std::string& path() const { return path_; }
    const std::string& write_path() const { return write_path_; }
    bool is_stdout() const { return path_ == "-"; }
    // A stdio stream on write_path() (standard output for "-"), opened on the first call, for
    // writers that do not open write_path() themselves. Throws filmgrain::Error naming the
    // path when it cannot be opened.
    std::FILE* stream();
    // The written file into place (throws filmgrain::Error naming the path). Once the writing
    // is finished; a stream() is flushed and closed here first, and a failed write through it
    // (an error flag, a failed flush or close) fails the commit.
    void commit();

private:
    std::string path_, write_path_;
    std::FILE* stream_ = nullptr;
    bool direct_ = false, committed_ = false;
    int signal_slot_ = -1;  // its entry in the list the signal handler removes
};

}  // namespace filmgrain
