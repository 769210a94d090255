// Autosaves of the open scene, so a crash never costs more than the last interval's work.
//
// Each window session writes one file, <AppDataLocation>/autosave/<session>.json (QStandardPaths:
// ~/.local/share/mipgloss/mipgloss/autosave on Linux), atomically (atomic_file.h), as a scene file
// (scene_file.h) with two differences: every mesh and environment file is referred to by its
// absolute path (the autosave folder is nowhere near the user's files), and an extra "autosave"
// object, which scene readers ignore, remembers the scene file the work belongs to:
//     "autosave": {"sceneFile": "/home/me/shots/gold.json" | "", "written": "2024-05-01T12:00:00"}
// While the session lives it holds <session>.lock (QLockFile). The window removes the file when
// the user's work is safe or knowingly dropped (a save, New or Open, a clean exit); a file left
// behind whose lock is free belongs to a session that ended without that: a crash. The next start
// offers it for restoring (leftovers()).
#pragma once

#include "mipgloss/scene/scene.h"

#include <QDateTime>
#include <QString>

#include <memory>
#include <vector>

class QLockFile;

namespace mipgloss::ui {

class Autosave {
public:
    Autosave();   // a new session; writes nothing yet
    ~Autosave();  // releases the lock; a written file stays (see above)
    Autosave(const Autosave&) = delete;
    Autosave& operator=(const Autosave&) = delete;

    // The folder all sessions write to.
    static QString folder();
    // This session's file (it exists only after write()).
    const QString& file() const { return file_; }

    // Writes `scene` (and `sceneFile`, the file it belongs to, "" if none). Throws FileError.
    void write(const Scene& scene, const QString& sceneFile);
    // Removes this session's file, if written.
    void discard();

    // An autosave a session left behind.
    struct Leftover {
        QString file;       // the autosave
        QString sceneFile;  // the scene file it belongs to, "" for a scene never saved
        QDateTime written;  // when it was written (the file's time when the JSON does not say)
    };
    // Those whose session ended (their lock is free), newest first; never a live session's.
    static std::vector<Leftover> leftovers();
    // Removes a leftover and its lock.
    static void remove(const Leftover& leftover);

private:
    QString file_;
    std::unique_ptr<QLockFile> lock_;
};

}  // namespace mipgloss::ui
