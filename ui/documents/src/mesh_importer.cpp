#include "mipgloss/ui/mesh_importer.h"

#include "mipgloss/assets/asset.h"
#include "mipgloss/assets/textures.h"
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

// One loaded file (or its error), handed from the loader to finish(): a plain mesh is an asset
// of one part without a material (asset.h).
struct MeshImporter::Loaded {
    QString path;
    std::shared_ptr<const Asset> asset;
    QString error;
    std::vector<std::string> warnings;
};

namespace {

// Reads the file and decodes the textures its materials read into `textures` (the document's,
// textures.h) from the images the read kept (Asset::images), here: on the worker thread for a
// large import, so the window only uploads them.
MeshImporter::Loaded loadOne(const QString& path, TextureCache& textures) {
    MeshImporter::Loaded result;
    result.path = path;
    try {
        const std::string file = QFileInfo(path).absoluteFilePath().toStdString();
        Asset asset = loadAsset(file);
        for (AssetPart& part : asset.parts)
            if (part.name.empty()) part.name = QFileInfo(path).completeBaseName().toStdString();
        result.warnings = std::move(asset.warnings);
        std::vector<TextureRef> maps;
        for (const AssetMaterial& m : asset.materials)
            for (const TextureRef& t : m.material.layers.maps.textures()) maps.push_back(t);
        for (std::string& w : textures.load(maps, asset.images)) result.warnings.push_back(std::move(w));
        result.asset = std::make_shared<const Asset>(std::move(asset));
    } catch (const FileError& e) {
        result.error = QString::fromStdString(e.what());
    } catch (const std::exception& e) {  // e.g. out of memory on a huge file
        result.error = path + QStringLiteral(": ") + QString::fromStdString(e.what());
    }
    return result;
}

std::size_t triangles(const Asset& asset) {
    std::size_t n = 0;
    for (const AssetPart& part : asset.parts) n += part.mesh->triangleCount();
    return n;
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
        for (const QString& path : paths) results.push_back(loadOne(path, *document_->textures()));
        finish(results, placement);
        return;
    }
    emit backgroundStarted(static_cast<int>(paths.size()));
    worker_->start(
        [paths, textures = document_->textures()](Job& job) {
            // Files are read whole (the readers report no progress of their own): progress counts
            // files, and a cancellation stops before the next one.
            std::vector<Loaded> results;
            for (qsizetype i = 0; i < paths.size(); ++i) {
                const std::string stage = tr("importing %1").arg(QFileInfo(paths[i]).fileName()).toStdString();
                if (!job.progress(stage, static_cast<float>(i) / static_cast<float>(paths.size()))) throw Cancelled{};
                results.push_back(loadOne(paths[i], *textures));
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
    QStringList warnings;
    for (const Loaded& r : results) {
        for (const std::string& w : r.warnings) {
            std::cerr << "mipgloss: " << w << '\n';
            warnings << QString::fromStdString(w);
        }
        if (r.asset)
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
        if (!r.asset) continue;
        const Asset& asset = *r.asset;
        // The asset's parts stay where its file put them relative to each other: one placement
        // for all, from the box of all parts.
        Mesh box;
        box.bounds = assetBounds(asset);
        const Transform where = besideScene(document_->scene(), box);
        Material plain;
        plain.lambda = kImportedLambda;
        plain.mode = LookupMode::Reflect;
        // Each asset material once, shared by the parts that use it, under its name in the file.
        std::vector<MaterialId> ids(asset.materials.size(), kNoMaterial);
        for (std::size_t k = 0; k < asset.parts.size(); ++k) {
            const AssetPart& part = asset.parts[k];
            SceneObject object;
            object.name = asset.wholeFile ? QFileInfo(r.path).completeBaseName().toStdString() : part.name;
            object.meshSource = QFileInfo(r.path).absoluteFilePath().toStdString();
            object.meshPart = asset.wholeFile ? -1 : static_cast<int>(k);
            object.mesh = part.mesh;
            object.transform = where;
            if (part.material < 0) {
                document_->addObject(std::move(object), plain);
                continue;
            }
            MaterialId& id = ids[static_cast<std::size_t>(part.material)];
            if (id != kNoMaterial) {
                object.material = id;
                document_->addObject(std::move(object));
            } else {
                const AssetMaterial& m = asset.materials[static_cast<std::size_t>(part.material)];
                const int index = document_->addObject(std::move(object), m.name, m.material);
                id = document_->object(index).material;
            }
        }
        document_->addFileCameras(QFileInfo(r.path).absoluteFilePath().toStdString(), asset.cameras);
        added << tr("%1 (%2 triangles%3)")
                     .arg(QFileInfo(r.path).fileName())
                     .arg(QLocale().toString(static_cast<qlonglong>(triangles(asset))))
                     .arg(asset.materials.empty()      ? QString()
                          : asset.materials.size() == 1 ? tr(", 1 material")
                                                        : tr(", %1 materials").arg(asset.materials.size()));
    }
    if (!names.isEmpty()) stack->endMacro();
    warnings_ = warnings;
    emit finished(added, errors);
}

}  // namespace mipgloss::ui
