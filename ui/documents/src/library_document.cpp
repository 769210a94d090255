#include "mipgloss/ui/library_document.h"

#include "mipgloss/assets/asset.h"

#include "mipgloss/ibl/phong.h"
#include "mipgloss/ui/library_file.h"

#include <QUndoCommand>
#include <QUndoStack>

#include <algorithm>
#include <cmath>
#include <exception>
#include <system_error>
#include <utility>

namespace mipgloss::ui {

// The undo commands' access to the document's steps (LibraryDocument's only friend).
struct LibraryEdits {
    static void insert(LibraryDocument& d, int row, const std::vector<LibraryMaterial>& entries) {
        d.insertEntries(row, entries);
    }
    static void remove(LibraryDocument& d, int row) { d.removeEntry(row); }
    static void replace(LibraryDocument& d, int row, const LibraryMaterial& entry) { d.replaceEntry(row, entry); }
    static void move(LibraryDocument& d, int from, int to) { d.moveEntry(from, to); }
    static void persist(LibraryDocument& d) { d.persist(); }
    static int generation(const LibraryDocument& d) { return d.generation_; }
};

namespace {

QString errorText(const std::exception& e) { return QString::fromStdString(e.what()); }

QString trimmedName(const QString& name) { return name.trimmed(); }

bool isValidName(const std::string& name) { return materialNameProblem(name).empty(); }

// Every library edit: applies a step to the document and writes the file, in both directions.
// A command made for a library that open() has since replaced does nothing and drops out of the
// stack (setObsolete), rather than editing rows of a different library.
class LibraryCommand : public QUndoCommand {
public:
    LibraryCommand(LibraryDocument* document, const QString& text)
        : QUndoCommand(text), document_(document), generation_(LibraryEdits::generation(*document)) {}

    void redo() final { run([this] { apply(); }); }
    void undo() final { run([this] { revert(); }); }

protected:
    virtual void apply() = 0;
    virtual void revert() = 0;
    LibraryDocument& document() const { return *document_; }
    bool sameLibrary(const LibraryCommand& other) const {
        return other.document_ == document_ && other.generation_ == generation_;
    }

private:
    template <typename Step>
    void run(Step step) {
        if (LibraryEdits::generation(*document_) != generation_) {
            setObsolete(true);
            return;
        }
        step();
        LibraryEdits::persist(*document_);
    }

    LibraryDocument* document_;
    int generation_;
};

// Add, duplicate and import: entries inserted at consecutive rows from `row`.
class InsertEntriesCommand : public LibraryCommand {
public:
    InsertEntriesCommand(LibraryDocument* document, const QString& text, int row, std::vector<LibraryMaterial> entries)
        : LibraryCommand(document, text), row_(row), entries_(std::move(entries)) {}

protected:
    void apply() override { LibraryEdits::insert(document(), row_, entries_); }
    void revert() override {
        for (std::size_t i = 0; i < entries_.size(); ++i) LibraryEdits::remove(document(), row_);
    }

private:
    int row_;
    std::vector<LibraryMaterial> entries_;
};

class RemoveEntryCommand : public LibraryCommand {
public:
    RemoveEntryCommand(LibraryDocument* document, int row)
        : LibraryCommand(document, QObject::tr("Delete library material “%1”")
                                       .arg(QString::fromStdString(document->entry(row).name))),
          row_(row), entry_(document->entry(row)) {}

protected:
    void apply() override { LibraryEdits::remove(document(), row_); }
    void revert() override { LibraryEdits::insert(document(), row_, {entry_}); }

private:
    int row_;
    LibraryMaterial entry_;
};

// Rename and new parameters: the entry before and after. Parameter edits of one entry merge, so
// a slider dragged over an entry is one undo step.
class ReplaceEntryCommand : public LibraryCommand {
public:
    enum class Kind { Rename, Parameters };
    ReplaceEntryCommand(LibraryDocument* document, const QString& text, Kind kind, int row, LibraryMaterial after)
        : LibraryCommand(document, text), kind_(kind), row_(row), before_(document->entry(row)),
          after_(std::move(after)) {}

    int id() const override { return kind_ == Kind::Parameters ? kParametersId : -1; }
    bool mergeWith(const QUndoCommand* other) override {
        const auto* next = static_cast<const ReplaceEntryCommand*>(other);  // same id: same class
        if (!sameLibrary(*next) || next->row_ != row_) return false;
        after_ = next->after_;
        setObsolete(after_ == before_);  // dragged back to where it started: no step at all
        return true;
    }

protected:
    void apply() override { LibraryEdits::replace(document(), row_, after_); }
    void revert() override { LibraryEdits::replace(document(), row_, before_); }

private:
    // QUndoCommand ids are per stack; the scene's commands use small numbers.
    static constexpr int kParametersId = 0x4c494250;  // "LIBP"
    Kind kind_;
    int row_;
    LibraryMaterial before_, after_;
};

class MoveEntryCommand : public LibraryCommand {
public:
    MoveEntryCommand(LibraryDocument* document, int from, int to)
        : LibraryCommand(document, QObject::tr("Move library material")), from_(from), to_(to) {}

protected:
    void apply() override { LibraryEdits::move(document(), from_, to_); }
    void revert() override { LibraryEdits::move(document(), to_, from_); }

private:
    int from_, to_;
};

}  // namespace

LibraryDocument::LibraryDocument(QUndoStack* undoStack, QObject* parent)
    : QObject(parent), undoStack_(undoStack ? undoStack : new QUndoStack(this)) {}

bool LibraryDocument::open(const std::filesystem::path& file, const MaterialLibrary& whenMissing) {
    emit aboutToReset();
    ++generation_;
    library_ = {};
    file_ = file;
    detached_ = false;
    lastError_.clear();
    std::error_code ec;
    const bool missing = !std::filesystem::exists(file, ec) && !ec;
    if (missing) library_ = whenMissing;
    if (!missing) {
        try {
            library_ = loadLibrary(file);
        } catch (const std::exception& e) {
            // Refused: an empty library in memory, and the file is left exactly as it is.
            library_ = {};
            detached_ = true;
            lastError_ = errorText(e);
        }
    }
    emit reset();
    emit fileChanged();
    return !detached_;
}

int LibraryDocument::add(const LibraryMaterial& entry) {
    LibraryMaterial added = entry;
    const std::string wanted = trimmedName(QString::fromStdString(entry.name)).toStdString();
    if (!isValidName(wanted) || !isValidMaterial(added.material)) return -1;
    added.name = library_.uniqueName(wanted);
    if (!isValidName(added.name)) return -1;  // a name at the length limit has no room for " 2"
    const int row = count();
    undoStack_->push(new InsertEntriesCommand(
        this, tr("Add library material “%1”").arg(QString::fromStdString(added.name)), row, {added}));
    return row;
}

void LibraryDocument::remove(int row) {
    if (!isValidRow(row)) return;
    undoStack_->push(new RemoveEntryCommand(this, row));
}

bool LibraryDocument::rename(int row, const QString& name) {
    if (!isValidRow(row)) return false;
    const std::string wanted = trimmedName(name).toStdString();
    if (wanted == entry(row).name) return true;
    if (!isValidName(wanted) || library_.contains(wanted)) return false;
    LibraryMaterial renamed = entry(row);
    renamed.name = wanted;
    undoStack_->push(new ReplaceEntryCommand(
        this,
        tr("Rename library material “%1” to “%2”")
            .arg(QString::fromStdString(entry(row).name), trimmedName(name)),
        ReplaceEntryCommand::Kind::Rename, row, std::move(renamed)));
    return true;
}

int LibraryDocument::duplicate(int row) {
    if (!isValidRow(row)) return -1;
    LibraryMaterial copy = entry(row);
    copy.name = library_.uniqueName(copy.name);
    if (!isValidName(copy.name)) return -1;  // a name at the length limit has no room for " 2"
    undoStack_->push(new InsertEntriesCommand(
        this, tr("Duplicate library material “%1”").arg(QString::fromStdString(entry(row).name)), row + 1,
        {copy}));
    return row + 1;
}

bool LibraryDocument::setMaterial(int row, const Material& material) {
    if (!isValidRow(row) || !isValidMaterial(material)) return false;
    if (entry(row).material == material) return true;
    LibraryMaterial changed = entry(row);
    changed.material = material;
    undoStack_->push(new ReplaceEntryCommand(
        this, tr("Edit library material “%1”").arg(QString::fromStdString(changed.name)),
        ReplaceEntryCommand::Kind::Parameters, row, std::move(changed)));
    return true;
}

void LibraryDocument::move(int from, int to) {
    if (!isValidRow(from) || !isValidRow(to) || from == to) return;
    undoStack_->push(new MoveEntryCommand(this, from, to));
}

int LibraryDocument::importFrom(const std::filesystem::path& file) {
    MaterialLibrary incoming;
    try {
        if (isAssetFile(file)) {
            // An asset's materials (glTF, OBJ with MTL), named as in the file, their texture maps
            // referring to its images by absolute path (asset.h).
            const Asset asset = loadAsset(std::filesystem::absolute(file).lexically_normal());
            if (asset.materials.empty()) throw AssetError(file, "has no materials to import");
            for (const AssetMaterial& m : asset.materials) incoming.entries.push_back(libraryEntryOf(m));
        } else {
            incoming = loadLibrary(file);
        }
    } catch (const std::exception& e) {
        lastError_ = errorText(e);
        return -1;
    }
    // Names are made unique against this library and against the entries added before them.
    MaterialLibrary merged = library_;
    std::vector<LibraryMaterial> added;
    for (LibraryMaterial& entry : incoming.entries) {
        const LibraryMaterial* same = merged.find(entry.name);
        if (same && same->material == entry.material) continue;
        entry.name = merged.uniqueName(entry.name);
        if (!isValidName(entry.name)) continue;  // no room left for a number: at the length limit
        merged.entries.push_back(entry);
        added.push_back(std::move(entry));
    }
    if (added.empty()) return 0;
    const int count = static_cast<int>(added.size());
    undoStack_->push(new InsertEntriesCommand(
        this,
        tr("Import %n library material(s) from “%1”", nullptr, count)
            .arg(QString::fromStdString(file.filename().string())),
        this->count(), std::move(added)));
    return count;
}

bool LibraryDocument::exportTo(const std::filesystem::path& file) const {
    try {
        saveLibrary(library_, file);
        return true;
    } catch (const std::exception& e) {
        lastError_ = errorText(e);
        return false;
    }
}

bool LibraryDocument::saveAs(const std::filesystem::path& file) {
    if (!exportTo(file)) return false;
    file_ = file;
    detached_ = false;
    emit fileChanged();
    emit saved();
    return true;
}

bool LibraryDocument::replaceUnreadableFile() { return saveAs(file_); }

void LibraryDocument::insertEntries(int row, const std::vector<LibraryMaterial>& entries) {
    for (std::size_t i = 0; i < entries.size(); ++i) {
        const int at = row + static_cast<int>(i);
        emit entryAboutToBeInserted(at);
        library_.entries.insert(library_.entries.begin() + at, entries[i]);
        emit entryInserted(at);
    }
}

void LibraryDocument::removeEntry(int row) {
    emit entryAboutToBeRemoved(row);
    library_.entries.erase(library_.entries.begin() + row);
    emit entryRemoved(row);
}

void LibraryDocument::replaceEntry(int row, const LibraryMaterial& entry) {
    library_.entries[static_cast<std::size_t>(row)] = entry;
    emit entryChanged(row);
}

void LibraryDocument::moveEntry(int from, int to) {
    emit entryAboutToBeMoved(from, to);
    auto& entries = library_.entries;
    if (from < to)
        std::rotate(entries.begin() + from, entries.begin() + from + 1, entries.begin() + to + 1);
    else
        std::rotate(entries.begin() + to, entries.begin() + from, entries.begin() + from + 1);
    emit entryMoved(from, to);
}

void LibraryDocument::persist() {
    if (detached_ || file_.empty()) return;
    try {
        saveLibrary(library_, file_);
    } catch (const std::exception& e) {
        lastError_ = errorText(e);
        emit saveFailed(lastError_);
        return;
    }
    emit saved();
}

}  // namespace mipgloss::ui
