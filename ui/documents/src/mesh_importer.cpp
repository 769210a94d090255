#include "mipgloss/ui/mesh_importer.h"

#include "mipgloss/scene/mesh.h"
#include "mipgloss/scene/placement.h"
#include "mipgloss/ui/scene_document.h"

#include <QFileInfo>
#include <QLocale>
#include <QUndoStack>

#include <algorithm>
#include <iostream>
#include <memory>
#include <string>
#include <vector>

namespace mipgloss::ui {

// One loaded mesh file (or its error), handed from the loader to finish().
struct MeshImporter::Loaded {
    QString path;
    std::shared_ptr<const Mesh> mesh;
    QString error;
    std::vector<std::string> warnings;
};

namespace {

MeshImporter::Loaded loadOne(const QString& path) {
    MeshImporter::Loaded result;
    result.path = path;
    try {
        MeshReport report;
        Mesh mesh = loadMesh(path.toStdString(), &report);
        if (mesh.name.empty()) mesh.name = QFileInfo(path).completeBaseName().toStdString();
        result.mesh = std::make_shared<const Mesh>(std::move(mesh));
        result.warnings = std::move(report.warnings);
    } catch (const MeshError& e) {
        result.error = QString::fromStdString(e.what());
    } catch (const std::exception& e) {  // e.g. out of memory on a huge file
        result.error = path + QStringLiteral(": ") + QString::fromStdString(e.what());
    }
    return result;
}

}  // namespace

MeshImporter::MeshImporter(SceneDocument* document, QObject* parent)
    : QObject(parent), document_(document), worker_(new BackgroundWorker(this)) {
    connect(worker_, &BackgroundWorker::progress, this, &MeshImporter::progress);
}

MeshImporter::~MeshImporter() {
    // Before members go: the worker's job calls back into them.
    delete worker_;
}

void MeshImporter::import(const QStringList& paths, Placement placement) {
    if (paths.isEmpty()) return;
    std::int64_t bytes = 0;
    for (const QString& path : paths) bytes += QFileInfo(path).size();
    if (bytes <= kBackgroundImportBytes) {
        std::vector<Loaded> results;
        for (const QString& path : paths) results.push_back(loadOne(path));
        finish(results, placement);
        return;
    }
    emit backgroundStarted(static_cast<int>(paths.size()));
    worker_->start(
        [paths](Job& job) {
            // Files are read whole (the readers report no progress of their own): progress counts
            // files, and a cancellation stops before the next one.
            std::vector<Loaded> results;
            for (qsizetype i = 0; i < paths.size(); ++i) {
                const std::string stage = tr("importing %1").arg(QFileInfo(paths[i]).fileName()).toStdString();
                if (!job.progress(stage, static_cast<float>(i) / static_cast<float>(paths.size()))) throw Cancelled{};
                results.push_back(loadOne(paths[i]));
            }
            return results;
        },
        [this, placement](JobOutcome<std::vector<Loaded>>&& outcome, const Job&) {
            // Cancelled imports add nothing (the window that asked is closing).
            if (outcome.value) finish(*outcome.value, placement);
        });
}

void MeshImporter::finish(const std::vector<Loaded>& results, Placement placement) {
    QStringList errors, added, names;
    for (const Loaded& r : results) {
        for (const std::string& w : r.warnings) std::cerr << "mipgloss: " << w << '\n';
        if (r.mesh)
            names << QFileInfo(r.path).fileName();
        else
            errors << r.error;
    }
    // One undo step for the whole import.
    QUndoStack* stack = document_->undoStack();
    if (!names.isEmpty()) stack->beginMacro(tr("Import %1").arg(names.join(QStringLiteral(", "))));
    if (!names.isEmpty() && placement == Placement::ReplaceObjects)
        for (int i = document_->objectCount() - 1; i >= 0; --i) document_->removeObject(i);
    for (const Loaded& r : results) {
        if (!r.mesh) continue;
        SceneObject object;
        object.name = QFileInfo(r.path).completeBaseName().toStdString();
        object.meshSource = QFileInfo(r.path).absoluteFilePath().toStdString();
        object.mesh = r.mesh;
        Material material;
        material.lambda = kImportedLambda;
        material.mode = LookupMode::Reflect;
        object.transform = besideScene(document_->scene(), *r.mesh);
        document_->addObject(std::move(object), material);
        added << tr("%1 (%2 triangles)")
                     .arg(QFileInfo(r.path).fileName())
                     .arg(QLocale().toString(static_cast<qlonglong>(r.mesh->triangleCount())));
    }
    if (!names.isEmpty()) stack->endMacro();
    emit finished(added, errors);
}

}  // namespace mipgloss::ui
