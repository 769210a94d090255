// The scene's objects as a flat list for views: one row per object, in the document's order.
//   display/edit  the name (editable: renames the object)
//   check state   visibility (editable)
//   tooltip       "λ 3.50 · reflect · 2,256 triangles"
// Resets on SceneDocument::objectsChanged and updates one row on objectChanged/materialChanged.
#pragma once

#include <QAbstractListModel>

namespace mipgloss::ui {

class SceneDocument;

class SceneListModel : public QAbstractListModel {
    Q_OBJECT
public:
    explicit SceneListModel(SceneDocument* document, QObject* parent = nullptr);

    SceneDocument* document() const { return document_; }

    int rowCount(const QModelIndex& parent = {}) const override;
    QVariant data(const QModelIndex& index, int role = Qt::DisplayRole) const override;
    bool setData(const QModelIndex& index, const QVariant& value, int role = Qt::EditRole) override;
    Qt::ItemFlags flags(const QModelIndex& index) const override;

private:
    void rowChanged(int row);

    SceneDocument* document_;
};

}  // namespace mipgloss::ui
