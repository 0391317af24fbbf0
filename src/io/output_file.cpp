#include "io/output_file.hpp"

#include <signal.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <mutex>

#include "filmgrain/error.hpp"

namespace filmgrain {

namespace {
// Temporaries to remove on a fatal signal: a fixed table the handler can walk without
// locks or allocation. A path is freed on unregistering unless the handler has started
// (it then never returns: the process dies), so the handler never reads freed memory.
constexpr int kMaxPartialOutputs = 64;
std::atomic<char*> partial_outputs[kMaxPartialOutputs];
std::atomic<bool> handler_started{false};
constexpr int kCleanupSignals[] = {SIGINT, SIGTERM, SIGHUP, SIGQUIT};

extern "C" void remove_partial_outputs_and_die(int sig) {
    handler_started.store(true);
    for (auto& slot : partial_outputs)
        if (const char* p = slot.load()) ::unlink(p);
    // Die by the same signal: the default action, delivered when this handler returns and
    // the signal is unblocked.
    ::signal(sig, SIG_DFL);
    ::raise(sig);
}

void install_cleanup_handlers() {
    for (int sig : kCleanupSignals) {
        struct sigaction old {};
        if (::sigaction(sig, nullptr, &old) != 0 || old.sa_handler != SIG_DFL) continue;  // ignored or taken
        struct sigaction sa {};
        sa.sa_handler = remove_partial_outputs_and_die;
        sigemptyset(&sa.sa_mask);
        for (int other : kCleanupSignals) sigaddset(&sa.sa_mask, other);  // one cleanup at a time
        sa.sa_flags = SA_RESTART;
        ::sigaction(sig, &sa, nullptr);
    }
}

int register_partial_output(const std::string& path) {
    static std::once_flag installed;
    std::call_once(installed, install_cleanup_handlers);
    char* copy = ::strdup(path.c_str());
    if (!copy) return -1;
    for (int i = 0; i < kMaxPartialOutputs; i++) {
        char* expected = nullptr;
        if (partial_outputs[i].compare_exchange_strong(expected, copy)) return i;
    }
    std::free(copy);  // more than kMaxPartialOutputs at once: this one is not removed on a signal
    return -1;
}

void unregister_partial_output(int slot) {
    if (slot < 0) return;
    char* p = partial_outputs[slot].exchange(nullptr);
    if (!handler_started.load()) std::free(p);
}
}  // namespace

bool is_stream_target(const std::string& path) {
    std::error_code ec;
    const std::filesystem::file_status st = std::filesystem::status(path, ec);
    return !ec && std::filesystem::exists(st) && !std::filesystem::is_regular_file(st) &&
           !std::filesystem::is_directory(st);
}

OutputFile::OutputFile(std::string path) : path_(std::move(path)) {
    direct_ = is_stdout() || is_stream_target(path_);
    if (direct_) {
        write_path_ = path_;
        return;
    }
    const std::filesystem::path p(path_);
    write_path_ = (p.parent_path() / (".filmgrain-partial-" + std::to_string(::getpid()) + "-" + p.filename().string()))
                      .string();
    signal_slot_ = register_partial_output(write_path_);
}

OutputFile::~OutputFile() {
    if (stream_ && stream_ != stdout) std::fclose(stream_);  // before its file is removed
    if (!direct_ && !committed_) std::remove(write_path_.c_str());
    unregister_partial_output(signal_slot_);
}

std::FILE* OutputFile::stream() {
    if (stream_) return stream_;
    stream_ = is_stdout() ? stdout : std::fopen(write_path_.c_str(), "wb");
    if (!stream_)
        throw Error(ErrorCode::kIo, "cannot open '" + path_ + "' for writing: " + std::strerror(errno));
    return stream_;
}

void OutputFile::commit() {
    if (stream_) {
        bool ok = std::fflush(stream_) == 0 && !std::ferror(stream_);
        if (stream_ != stdout) ok = std::fclose(stream_) == 0 && ok;
        stream_ = nullptr;
        if (!ok) throw Error(ErrorCode::kIo, "write error on '" + path_ + "'");  // the destructor removes it
    }
    if (!direct_ && std::rename(write_path_.c_str(), path_.c_str()) != 0) {
        const int err = errno;
        std::remove(write_path_.c_str());
        throw Error(ErrorCode::kIo, "cannot rename output into '" + path_ + "': " + std::strerror(err));
    }
    committed_ = true;
    unregister_partial_output(signal_slot_);  // after the rename: a signal before it still removes the temporary
    signal_slot_ = -1;
}

}  // namespace filmgrain
