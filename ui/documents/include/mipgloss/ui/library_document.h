// The user's material library as the window edits it: a MaterialLibrary (library.h) and the file
// it lives in (library_file.h). Every edit (add, remove, rename, duplicate, new parameters, move,
// import) is a QUndoCommand pushed onto the undo stack the window gives (the scene document's,
// so Edit → Undo walks library and scene edits in the order they were made), and is written to
// the file at once, atomically; undo and redo write it too. A failed write is reported
// (saveFailed) and the library in memory is kept, so nothing the user did is lost.
//
// A file that exists but cannot be read (corrupt, a newer version, not a library) is refused:
// the document works on an empty library in memory and is "detached", it never writes that
// file, whose bytes stay as they were, until the user chooses: saveAs() another file, or
// replaceUnreadableFile() to overwrite it with the library in memory. A missing file is simply
// an empty library, created by the first edit.
//
// Rows are the library's order. Each change comes as a pair of signals (before, after) so a
// model can tell its views exactly which rows move (library_model.h); open() resets.
#pragma once

#include "mipgloss/scene/library.h"

#include <QObject>
#include <QString>

#include <filesystem>
#include <vector>

class QUndoStack;

namespace mipgloss::ui {

class LibraryDocument : public QObject {
    Q_OBJECT
public:
    // `undoStack` null: the document makes one of its own (tests, tools).
    explicit LibraryDocument(QUndoStack* undoStack, QObject* parent = nullptr);

    const MaterialLibrary& library() const { return library_; }
    int count() const { return static_cast<int>(library_.entries.size()); }
    bool isValidRow(int row) const { return row >= 0 && row < count(); }
    const LibraryMaterial& entry(int row) const { return library_.entries.at(static_cast<std::size_t>(row)); }
    int rowOf(const QString& name) const { return library_.indexOf(name.toStdString()); }
    QUndoStack* undoStack() const { return undoStack_; }

    // The file edits are written to (or, detached, the unreadable one that is left alone).
    const std::filesystem::path& file() const { return file_; }
    bool isDetached() const { return detached_; }
    // Why the last open, save, import or export failed: the file and the reason.
    const QString& lastError() const { return lastError_; }

    // Until open() or saveAs(), the library lives in memory only (nothing is written anywhere).

    // Reads `file` (defaultLibraryPath() for the user's own). Missing: `whenMissing` (the window
    // passes starterLibrary()), attached, in memory until the first edit writes the file.
    // Unreadable: false, lastError() says why, the library is empty and the document detached.
    // Not an edit: the undo stack keeps its commands, and those of the library opened before
    // become no-ops (they drop out of the stack when reached).
    bool open(const std::filesystem::path& file, const MaterialLibrary& whenMissing = {});

    // Edits (undoable, written at once). Rows out of range and refused names change nothing.
    // add: appends `entry` under entry.name made unique (MaterialLibrary::uniqueName); the new
    // row, or -1 when the name is invalid (materialNameProblem).
    int add(const LibraryMaterial& entry);
    void remove(int row);
    // False (and no change) when `name` is invalid or another entry has it; a name equal to the
    // entry's own is a successful no-op. Names are kept as typed, ends trimmed of white space.
    bool rename(int row, const QString& name);
    // A copy right after `row`, named "<name> 2" (or the next free number); the new row or -1.
    int duplicate(int row);
    // New parameters for an entry (λ outside [0, kMaxLambda], or a negative or non-finite tint,
    // are refused: false). Consecutive edits of the same entry merge into one undo step.
    bool setMaterial(int row, const Material& material);
    // Moves the entry at `from` so it ends at row `to`.
    void move(int from, int to);

    // Appends every entry of a library file (or every material of an asset file: glTF, OBJ with
    // MTL, asset.h, named as in it, with their texture maps) as one undo step: a name already here gets a free one
    // (uniqueName), an entry equal to one already here (name and parameters) is skipped, so
    // importing the same file twice adds nothing. The number added, or -1 with lastError() when
    // the file cannot be read; nothing changes then.
    int importFrom(const std::filesystem::path& file);
    // Writes the library to `file` (atomically) without changing which file the document uses.
    bool exportTo(const std::filesystem::path& file) const;
    // Writes the library to `file` and uses it from now on (attaches a detached document).
    bool saveAs(const std::filesystem::path& file);
    // The explicit choice for a detached document: overwrite the unreadable file with the library
    // in memory and use it from now on.
    bool replaceUnreadableFile();

signals:
    void entryAboutToBeInserted(int row);
    void entryInserted(int row);
    void entryAboutToBeRemoved(int row);
    void entryRemoved(int row);
    void entryAboutToBeMoved(int from, int to);
    void entryMoved(int from, int to);
    void entryChanged(int row);  // name or parameters
    void aboutToReset();
    void reset();
    // file() or isDetached() changed.
    void fileChanged();
    // A write of the library failed; the library in memory is kept. `message` names the file.
    void saveFailed(const QString& message);
    // The library was written to file() (after an edit, an undo or redo, saveAs).
    void saved();

private:
    // The undo commands' way in (library_document.cpp).
    friend struct LibraryEdits;

    // The steps commands are made of: change the library and emit, nothing else.
    void insertEntries(int row, const std::vector<LibraryMaterial>& entries);
    void removeEntry(int row);
    void replaceEntry(int row, const LibraryMaterial& entry);
    void moveEntry(int from, int to);
    // Writes the library to file() when attached; reports a failure.
    void persist();

    QUndoStack* undoStack_;
    MaterialLibrary library_;
    std::filesystem::path file_;
    bool detached_ = false;
    mutable QString lastError_;  // exportTo reports through it too
    // Bumped by open(): commands made for an earlier library refuse to run.
    int generation_ = 0;
};

}  // namespace mipgloss::ui
