// The one atomic write (mipgloss/io/atomic_write.h): the target is the old file or the new one,
// never a part, and nothing is left beside it.
#include "mipgloss/io/atomic_write.h"
#include "mipgloss/io/file_error.h"
#include "mipgloss/io/image_file.h"
#include "mipgloss/io/import.h"

#include "test_support.h"

#include <gtest/gtest.h>

#include <unistd.h>

#include <cstdio>
#include <fstream>
#include <iterator>
#include <stdexcept>
#include <string>
#include <vector>

using namespace mipgloss;
namespace fs = std::filesystem;

namespace {

std::string contents(const fs::path& file) {
    std::ifstream in(file, std::ios::binary);
    return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

void writeAll(int fd, const std::string& text) {
    ASSERT_EQ(::write(fd, text.data(), text.size()), static_cast<ssize_t>(text.size()));
}

void put(const fs::path& file, const std::string& text) {
    std::ofstream(file, std::ios::binary) << text;
}

std::size_t entries(const fs::path& folder) {
    return static_cast<std::size_t>(std::distance(fs::directory_iterator(folder), fs::directory_iterator()));
}

}  // namespace

TEST(AtomicWrite, ReplacesTheFileAndCreatesItsFolder) {
    test::TempDir dir;
    const fs::path file = dir / "a" / "b" / "out.txt";
    writeAtomically(file, [](int fd) { writeAll(fd, "first"); });
    EXPECT_EQ(contents(file), "first");
    writeAtomically(file, [](int fd) { writeAll(fd, "second"); });
    EXPECT_EQ(contents(file), "second");
    writeAtomicallyByPath(file, [](const fs::path& temporary) { put(temporary, "third"); });
    EXPECT_EQ(contents(file), "third");
    EXPECT_EQ(entries(file.parent_path()), 1u);  // no temporary left beside it
}

TEST(AtomicWrite, AFailedWriteLeavesTheOldFileAndNoTemporary) {
    test::TempDir dir;
    const fs::path file = dir / "out.txt";
    put(file, "old");
    EXPECT_THROW(writeAtomically(file,
                                 [&](int fd) {
                                     writeAll(fd, "half of the new");
                                     throw FileError(file, "the disk is full");
                                 }),
                 FileError);
    EXPECT_EQ(contents(file), "old");
    EXPECT_EQ(entries(dir.path()), 1u);
    EXPECT_THROW(writeAtomicallyByPath(file,
                                       [&](const fs::path& temporary) {
                                           put(temporary, "half of the new");
                                           throw FileError(file, "the disk is full");
                                       }),
                 FileError);
    EXPECT_EQ(contents(file), "old");
    EXPECT_EQ(entries(dir.path()), 1u);
    // A path writer that writes nothing is a failure too, not an empty file.
    EXPECT_THROW(writeAtomicallyByPath(file, [](const fs::path&) {}), FileError);
    EXPECT_EQ(contents(file), "old");
    EXPECT_EQ(entries(dir.path()), 1u);
}

// The descriptor's file has no name while it is written: a process killed then leaves nothing.
TEST(AtomicWrite, TheFileHasNoNameUntilItIsWhole) {
    test::TempDir dir;
    const fs::path file = dir / "out.txt";
    writeAtomically(file, [&](int fd) {
        writeAll(fd, "being written");
        EXPECT_EQ(entries(dir.path()), 0u);
    });
    EXPECT_EQ(contents(file), "being written");
}

TEST(AtomicWrite, TemporaryNamesAreFreshAndBesideTheTarget) {
    test::TempDir dir;
    const fs::path target = dir / "x.exr";
    const fs::path a = temporaryBeside(target);
    EXPECT_EQ(a.parent_path(), dir.path());
    EXPECT_EQ(a.filename().string().rfind("x.exr.partial-", 0), 0u) << a;
    put(a, "taken");
    for (int i = 0; i < 50; ++i) EXPECT_NE(temporaryBeside(target), a);
}

// `mipgloss render --out x.exr` and `--aov` write through writeFloatChannels: the EXR is
// replaced whole, and a write that cannot be put in place (here the target is a folder with a
// file in it) leaves what was there and nothing beside it.
TEST(AtomicWrite, FloatChannelsReplaceAnExrWholeOrNotAtAll) {
    test::TempDir dir;
    const fs::path file = dir / "picture.exr";
    writeFloatChannels(file, 2, 1, {"R", "G", "B"}, {1, 2, 3, 4, 5, 6});
    const std::string first = contents(file);
    EXPECT_FALSE(first.empty());
    writeFloatChannels(file, 1, 1, {"R", "G", "B"}, {7, 8, 9});
    EXPECT_NE(contents(file), first);
    EXPECT_EQ(entries(dir.path()), 1u);

    const fs::path folder = dir / "taken.exr";
    fs::create_directories(folder);
    put(folder / "keep.txt", "mine");
    try {
        writeFloatChannels(folder, 1, 1, {"R", "G", "B"}, {7, 8, 9});
        ADD_FAILURE() << "wrote over a folder";
    } catch (const FileError& e) {
        EXPECT_EQ(e.file(), folder);
        EXPECT_NE(e.reason().find("cannot write"), std::string::npos) << e.what();
    }
    EXPECT_EQ(contents(folder / "keep.txt"), "mine");
    EXPECT_EQ(entries(dir.path()), 2u);  // picture.exr and the folder, no temporary
}
