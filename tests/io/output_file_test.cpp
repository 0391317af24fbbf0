// OutputFile: a regular output appears only on commit (through a temporary beside it, removed
// when the writer gives up); standard output, pipes and devices are written directly.
#include <gtest/gtest.h>
#include <sys/stat.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>

#include "filmgrain/error.hpp"
#include "io/output_file.hpp"

using namespace filmgrain;
namespace fs = std::filesystem;

namespace {

fs::path fresh_dir(const std::string& name) {
    const fs::path d = fs::temp_directory_path() / ("filmgrain-output-" + std::to_string(::getpid()) + "-" + name);
    fs::remove_all(d);
    fs::create_directories(d);
    return d;
}

TEST(OutputFile, RegularFileAppearsOnlyOnCommit) {
    const fs::path dir = fresh_dir("commit");
    const fs::path target = dir / "out.png";
    {
        OutputFile out(target.string());
        EXPECT_NE(out.write_path(), target.string());
        // the temporary sits beside the target and keeps its extension (OpenImageIO's format)
        EXPECT_EQ(fs::path(out.write_path()).parent_path(), dir);
        EXPECT_EQ(fs::path(out.write_path()).extension(), ".png");
        std::ofstream(out.write_path()) << "data";
        EXPECT_FALSE(fs::exists(target));
        out.commit();
    }
    ASSERT_TRUE(fs::exists(target));
    EXPECT_EQ(fs::file_size(target), 4u);
    EXPECT_EQ(std::distance(fs::directory_iterator(dir), fs::directory_iterator()), 1);
    fs::remove_all(dir);
}

TEST(OutputFile, WithoutCommitNothingIsLeft) {
    const fs::path dir = fresh_dir("abandon");
    {
        OutputFile out((dir / "out.yuv").string());
        std::ofstream(out.write_path()) << "half";
    }
    EXPECT_EQ(std::distance(fs::directory_iterator(dir), fs::directory_iterator()), 0);
    fs::remove_all(dir);
}

TEST(OutputFile, StdoutPipesAndDevicesAreWrittenDirectly) {
    EXPECT_TRUE(OutputFile("-").is_stdout());
    EXPECT_EQ(OutputFile("-").write_path(), "-");
    const fs::path dir = fresh_dir("direct");
    const fs::path fifo = dir / "pipe.yuv";
    ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
    EXPECT_TRUE(is_stream_target(fifo.string()));
    {
        OutputFile out(fifo.string());
        EXPECT_EQ(out.write_path(), fifo.string());
        out.commit();
    }
    EXPECT_TRUE(fs::is_fifo(fifo));
    EXPECT_FALSE(is_stream_target((dir / "missing.yuv").string()));
    EXPECT_FALSE(is_stream_target(dir.string()));
    fs::remove_all(dir);
}

// stream(): the writers that write through stdio get the stream from OutputFile, and commit()
// is where a failed write through it shows (a full device here), leaving nothing behind.
TEST(OutputFile, StreamIsFlushedClosedAndCheckedByCommit) {
    const fs::path dir = fresh_dir("stream");
    const fs::path target = dir / "params.json";
    {
        OutputFile out(target.string());
        std::FILE* f = out.stream();
        EXPECT_EQ(out.stream(), f);  // opened once
        std::fputs("{}\n", f);
        out.commit();
    }
    ASSERT_TRUE(fs::exists(target));
    EXPECT_EQ(fs::file_size(target), 3u);
    {
        OutputFile out((dir / "half.json").string());
        std::fputs("{", out.stream());
    }  // destroyed unflushed and uncommitted: closed, then removed
    EXPECT_EQ(std::distance(fs::directory_iterator(dir), fs::directory_iterator()), 1);
    if (fs::exists("/dev/full")) {
        OutputFile out("/dev/full");
        std::fputs("more than a full device takes", out.stream());
        try {
            out.commit();
            ADD_FAILURE() << "a write to /dev/full committed";
        } catch (const Error& e) {
            EXPECT_NE(std::string(e.what()).find("/dev/full"), std::string::npos) << e.what();
        }
    }
    EXPECT_THROW(OutputFile((dir / "no-such-dir" / "x.json").string()).stream(), Error);
    fs::remove_all(dir);
}

}  // namespace
