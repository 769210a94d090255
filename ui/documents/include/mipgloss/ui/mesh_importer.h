// Imports mesh and asset files (asset.h: glTF, OBJ with MTL; their parts and named materials with
// texture maps, decoded here too) into a SceneDocument. Files adding up to more than kBackgroundImportBytes are
// loaded on a worker thread (background_worker.h; the UI never waits on a large file), smaller ones
// at once; finished() follows either way. Each mesh becomes an object named after the file stem, referring to the
// file by its absolute path, with a material of its own (named after it) of λ = kImportedLambda
// looked up by the reflection vector: a plainly glossy start, well inside the filtered levels of
// any chain of 16² or more. One import (one call, however many files) is one undo step.
//
// Each is placed beside the scene (mipgloss/scene/placement.h: besideScene).
#pragma once

#include "mipgloss/scene/scene.h"
#include "mipgloss/ui/background_worker.h"

#include <QObject>
#include <QString>
#include <QStringList>

#include <cstdint>

namespace mipgloss::ui {

class SceneDocument;

class MeshImporter : public QObject {
    Q_OBJECT
public:
    // Imports whose files add up to more than this run on a worker thread.
    static constexpr std::int64_t kBackgroundImportBytes = 4 * 1024 * 1024;
    // The λ an imported object starts with (reflect mode).
    static constexpr float kImportedLambda = 3.0f;

    explicit MeshImporter(SceneDocument* document, QObject* parent = nullptr);
    ~MeshImporter() override;  // cancels a background import: nothing of it is added

    // Where the new objects go: Beside the scene (placement.h), or ReplaceObjects: the scene's
    // objects are removed in the same undo step and the meshes placed alone (the window's
    // untouched demo scene); a failed import then removes nothing.
    enum class Placement { Beside, ReplaceObjects };
    void import(const QStringList& paths, Placement placement = Placement::Beside);
    // True while a background import runs.
    bool busy() const { return worker_->busy(); }
    // The last import's warnings (an asset's texture that is missing or does not decode, parts
    // left out, ...), each naming its file; set before finished() is emitted.
    const QStringList& warnings() const { return warnings_; }

    // One loaded mesh file (or its error), handed from the loader to the document.
    struct Loaded;

signals:
    // A background import started (the window shows a busy indicator).
    void backgroundStarted(int files);
    // A background import's progress: the file being read and the fraction of files read.
    void progress(const QString& stage, double fraction);
    // After import(): what was added ("bunny.obj (2,256 triangles)", in order) and the errors, one
    // per failed file, each naming it.
    void finished(const QStringList& added, const QStringList& errors);

private:
    void finish(const std::vector<Loaded>& results, Placement placement);

    SceneDocument* document_;
    BackgroundWorker* worker_;
    QStringList warnings_;
};

}  // namespace mipgloss::ui
