// The scene's objects as a flat list for views: one row per object, in the document's order.
//   display/edit      the name (editable: renames the object)
//   MaterialNameRole  the name of the material the object uses (SceneListDelegate, in the widgets
//                     room, draws it after the name, in a quieter colour)
//   check state       visibility (editable)
//   tooltip           "Gold · λ 3.50 · reflect · 2,256 triangles"
// Rows follow the document's paired signals (scene_document.h): an added or duplicated object is
// one inserted row, a removed one one removed row, and only resetScene resets the model, so a
// view's selection and current row survive edits elsewhere in the list.
//
// Drops: a library material (material_mime.h) dropped onto a row is applied to that object
// (SceneDocument::applyLibraryMaterial, one undo step).
#pragma once

#include "mipgloss/scene/scene.h"

#include <QAbstractListModel>
#include <QString>

namespace mipgloss::ui {

class SceneDocument;

class SceneListModel : public QAbstractListModel {
    Q_OBJECT
public:
    enum Role { MaterialNameRole = Qt::UserRole + 1 };

    explicit SceneListModel(SceneDocument* document, QObject* parent = nullptr);

    SceneDocument* document() const { return document_; }

    int rowCount(const QModelIndex& parent = {}) const override;
    QVariant data(const QModelIndex& index, int role = Qt::DisplayRole) const override;
    bool setData(const QModelIndex& index, const QVariant& value, int role = Qt::EditRole) override;
    Qt::ItemFlags flags(const QModelIndex& index) const override;

    QStringList mimeTypes() const override;
    Qt::DropActions supportedDropActions() const override;
    bool canDropMimeData(const QMimeData* data, Qt::DropAction action, int row, int column,
                         const QModelIndex& parent) const override;
    bool dropMimeData(const QMimeData* data, Qt::DropAction action, int row, int column,
                      const QModelIndex& parent) override;

private:
    void rowChanged(int row);

    SceneDocument* document_;
};

// A layered material in a tooltip's words: "metal" or "base r, g, b", roughness, and the coat when
// it has one (the scene list's and the library's tooltips).
QString layersSummary(const Layers& layers);

}  // namespace mipgloss::ui
