// The one way mipgloss writes a file the user keeps (scenes, libraries, autosaves, pictures and
// AOVs from `render`, DDS cubes, exported images): the content goes to a fresh temporary file
// beside the target, is flushed to disk, and only then renamed over the target, so the target is
// always the old file or the new one, whatever happens in between (an error, a full disk, the
// process killed). ui/files' writeFileAtomically (Qt devices) is this, and so is the bake's
// folder swap (bake.cpp), which names its staging folder with temporaryBeside.
#pragma once

#include <filesystem>
#include <functional>
#include <string_view>

namespace mipgloss {

// Writes `file` by calling `write` with an open, empty file descriptor, which `write` fills (with
// write(2), a FILE* from fdopen(dup(fd)), a QFile opened on it) and throws on failure, naming
// `file`; it must not close `fd`. The file has no name until it is whole (O_TMPFILE, as Qt's
// QSaveFile does), so a process killed while writing leaves nothing behind; where the file system
// cannot do that, a temporary name beside the target, removed on failure. Creates the folder when
// missing. On any failure the target is left as it was and the error passed on; a failure of
// the flush or rename throws FileError naming `file`.
void writeAtomically(const std::filesystem::path& file, const std::function<void(int fd)>& write);

// The same for writers that need a path (OpenImageIO): `write` fills the temporary path it is
// given beside the target. A process killed while writing leaves that temporary behind (never
// read: readers open the target's own name).
void writeAtomicallyByPath(const std::filesystem::path& file,
                           const std::function<void(const std::filesystem::path& temporary)>& write);

// A path beside `target` that does not exist yet: target + "." + tag + "-" + a random number.
std::filesystem::path temporaryBeside(const std::filesystem::path& target, std::string_view tag = "partial");

}  // namespace mipgloss
