// The one shape of a user-caused problem with a file: what() is "<file>: <reason>", and both
// parts stay available for messages. Each kind of file has its own type (EnvError, MeshError,
// SceneFileError) so callers can catch what they can handle.
#pragma once

#include <filesystem>
#include <stdexcept>
#include <string>

namespace mipgloss {

class FileError : public std::runtime_error {
public:
    FileError(const std::filesystem::path& file, const std::string& reason)
        : std::runtime_error(file.string() + ": " + reason), file_(file), reason_(reason) {}
    const std::filesystem::path& file() const { return file_; }
    const std::string& reason() const { return reason_; }

private:
    std::filesystem::path file_;
    std::string reason_;
};

// The one reason given for a file that is not there, whatever kind of file it is.
inline const std::string kFileNotFound = "file not found";

}  // namespace mipgloss
