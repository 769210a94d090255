// Writing a file the user keeps (scenes, libraries, autosaves, exported images) from Qt: the one
// atomic write (mipgloss/io/atomic_write.h: a temporary beside the target, flushed, then renamed
// over it, so the target is always the old file or the new one) with a QIODevice to write into.
#pragma once

#include "mipgloss/io/file_error.h"

#include <QByteArray>

#include <filesystem>
#include <functional>

class QIODevice;

namespace mipgloss::ui {

// Writes `bytes` to `file` atomically, creating its folder when missing. Throws FileError naming
// the file and the reason.
void writeFileAtomically(const std::filesystem::path& file, const QByteArray& bytes);
// The same with a writer that streams into the device (e.g. QImage::save(QIODevice*, "PNG")),
// returning false on failure.
void writeFileAtomically(const std::filesystem::path& file, const std::function<bool(QIODevice&)>& write);

}  // namespace mipgloss::ui
