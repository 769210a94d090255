// The one way mipgloss writes a file the user keeps (scenes, libraries, autosaves, exported
// images): QSaveFile writes a temporary file beside the target and renames it over the target
// only when everything was written and flushed, so the target is always the old file or the new
// one, whatever happens in between (an error, a full disk, the process killed).
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
