// The material library as a flat list for views: one row per entry, in the library's order.
//   display/edit  the name (editable: renames the entry through the document, an undoable edit;
//                 an invalid or taken name is refused)
//   decoration    the entry's thumbnail (thumbnail_cache.h), a neutral placeholder until drawn
//   tooltip       "λ 3.00 · n 767 · reflect · tint 1.000, 0.800, 0.300"
// Rows follow the document's edits one by one (insert, remove, move, change); only open() of
// another library resets. Entries drag out as kMaterialMimeType (material_mime.h).
#pragma once

#include <QAbstractListModel>
#include <QPixmap>

namespace mipgloss {
struct LibraryMaterial;
}

namespace mipgloss::ui {

class LibraryDocument;
class ThumbnailCache;

class LibraryModel : public QAbstractListModel {
    Q_OBJECT
public:
    explicit LibraryModel(LibraryDocument* document, QObject* parent = nullptr);

    LibraryDocument* document() const { return document_; }
    // Where DecorationRole comes from; null (the default): the placeholder for every row.
    void setThumbnails(ThumbnailCache* thumbnails);
    ThumbnailCache* thumbnails() const { return thumbnails_; }

    // The library entry of a row of this model.
    const LibraryMaterial& entry(const QModelIndex& index) const;

    int rowCount(const QModelIndex& parent = {}) const override;
    QVariant data(const QModelIndex& index, int role = Qt::DisplayRole) const override;
    bool setData(const QModelIndex& index, const QVariant& value, int role = Qt::EditRole) override;
    Qt::ItemFlags flags(const QModelIndex& index) const override;

    QStringList mimeTypes() const override;
    // The first of `indexes` (a library material is applied one at a time).
    QMimeData* mimeData(const QModelIndexList& indexes) const override;
    Qt::DropActions supportedDragActions() const override { return Qt::CopyAction; }

private:
    void rowChanged(int row, const QList<int>& roles = {});

    LibraryDocument* document_;
    ThumbnailCache* thumbnails_ = nullptr;
    QPixmap placeholder_;
};

}  // namespace mipgloss::ui
