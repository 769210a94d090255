#include "mipgloss/io/atomic_write.h"

#include "mipgloss/io/file_error.h"

#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <random>
#include <string>
#include <system_error>

namespace fs = std::filesystem;

namespace mipgloss {

namespace {

// Flushes the file's data to the disk, so a crash after the rename cannot leave the new name
// holding a file whose blocks never arrived. Returns the errno, 0 on success.
int syncToDisk(const fs::path& file) {
    const int fd = ::open(file.c_str(), O_RDONLY | O_CLOEXEC);
    if (fd < 0) return errno;
    const int status = ::fsync(fd) == 0 ? 0 : errno;
    ::close(fd);
    return status;
}

void removeQuietly(const fs::path& file) {
    std::error_code ignored;
    fs::remove(file, ignored);
}

}  // namespace

fs::path temporaryBeside(const fs::path& target, std::string_view tag) {
    std::random_device rd;
    for (int attempt = 0; attempt < 100; ++attempt) {
        fs::path p = target;
        p += "." + std::string(tag) + "-" + std::to_string(rd() % 1000000);
        std::error_code ec;
        if (!fs::exists(p, ec) && !ec) return p;
    }
    throw FileError(target, "cannot find a free temporary name beside it");
}

namespace {

void makeFolderOf(const fs::path& file) {
    const fs::path folder = file.parent_path();
    std::error_code ec;
    if (folder.empty() || fs::is_directory(folder, ec)) return;
    fs::create_directories(folder, ec);
    if (ec) throw FileError(file, "cannot create the folder " + folder.string() + ": " + ec.message());
}

std::string errnoText(int error) { return std::generic_category().message(error); }

}  // namespace

void writeAtomically(const fs::path& file, const std::function<void(int fd)>& write) {
    makeFolderOf(file);
    const fs::path folder = file.parent_path().empty() ? fs::path(".") : file.parent_path();
    // An unnamed file in the target's folder (same file system, so it can be linked there).
    int fd = ::open(folder.c_str(), O_TMPFILE | O_WRONLY | O_CLOEXEC, 0666);
    fs::path named;  // the temporary's name, once it has one
    if (fd < 0) {
        if (errno != EOPNOTSUPP && errno != EISDIR && errno != EINVAL && errno != ENOENT)
            throw FileError(file, "cannot write: " + errnoText(errno));
        named = temporaryBeside(file);
        fd = ::open(named.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0666);
        if (fd < 0) throw FileError(file, "cannot write: " + errnoText(errno));
    }
    try {
        write(fd);
        if (::fdatasync(fd) != 0) throw FileError(file, "cannot write: " + errnoText(errno));
        if (named.empty()) {
            const fs::path temporary = temporaryBeside(file);
            const std::string self = "/proc/self/fd/" + std::to_string(fd);
            if (::linkat(AT_FDCWD, self.c_str(), AT_FDCWD, temporary.c_str(), AT_SYMLINK_FOLLOW) != 0)
                throw FileError(file, "cannot write: " + errnoText(errno));
            named = temporary;
        }
        // Renamed before the descriptor is closed: the name exists for as short a time as it can.
        std::error_code ec;
        fs::rename(named, file, ec);
        if (ec) throw FileError(file, "cannot write: " + ec.message());
        named.clear();
        const int closed = ::close(fd);
        fd = -1;
        if (closed != 0) throw FileError(file, "cannot write: " + errnoText(errno));
    } catch (...) {
        if (fd >= 0) ::close(fd);
        if (!named.empty()) removeQuietly(named);
        throw;
    }
}

void writeAtomicallyByPath(const fs::path& file, const std::function<void(const fs::path& temporary)>& write) {
    makeFolderOf(file);
    const fs::path temporary = temporaryBeside(file);
    try {
        write(temporary);
        std::error_code ec;
        if (!fs::is_regular_file(temporary, ec)) throw FileError(file, "cannot write: nothing was written");
        if (const int error = syncToDisk(temporary)) throw FileError(file, "cannot write: " + errnoText(error));
        fs::rename(temporary, file, ec);
        if (ec) throw FileError(file, "cannot write: " + ec.message());
    } catch (...) {
        removeQuietly(temporary);
        throw;
    }
}

}  // namespace mipgloss
