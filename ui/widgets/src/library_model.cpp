#include "mipgloss/ui/library_model.h"
#include "mipgloss/ui/scene_list_model.h"

#include "mipgloss/ibl/phong.h"
#include "mipgloss/scene/library.h"
#include "mipgloss/ui/library_document.h"
#include "mipgloss/ui/material_mime.h"
#include "mipgloss/ui/thumbnail_cache.h"

#include <QMimeData>

#include <cmath>

namespace mipgloss::ui {

namespace {

// "767" for the lobes an artist picks by number, "2.41" for the widest ones, "∞" for a mirror.
QString exponentText(double n) {
    if (std::isinf(n)) return QStringLiteral("∞");
    return QString::number(n, 'f', n >= 10.0 ? 0 : 2);
}

}  // namespace

LibraryModel::LibraryModel(LibraryDocument* document, QObject* parent)
    : QAbstractListModel(parent), document_(document) {
    placeholder_ = QPixmap(ThumbnailCache::kThumbnailSize, ThumbnailCache::kThumbnailSize);
    placeholder_.fill(QColor(118, 118, 118));  // sRGB of the renderer's 18 % grey: where a sphere will be
    // One row per edit: views keep their selection and scroll position through adds and undos.
    connect(document_, &LibraryDocument::entryAboutToBeInserted, this,
            [this](int row) { beginInsertRows({}, row, row); });
    connect(document_, &LibraryDocument::entryInserted, this, [this] { endInsertRows(); });
    connect(document_, &LibraryDocument::entryAboutToBeRemoved, this,
            [this](int row) { beginRemoveRows({}, row, row); });
    connect(document_, &LibraryDocument::entryRemoved, this, [this] { endRemoveRows(); });
    connect(document_, &LibraryDocument::entryAboutToBeMoved, this, [this](int from, int to) {
        // Qt counts the destination before the move: moving down lands above row to + 1.
        beginMoveRows({}, from, from, {}, to > from ? to + 1 : to);
    });
    connect(document_, &LibraryDocument::entryMoved, this, [this] { endMoveRows(); });
    connect(document_, &LibraryDocument::entryChanged, this, [this](int row) { rowChanged(row); });
    connect(document_, &LibraryDocument::aboutToReset, this, [this] { beginResetModel(); });
    connect(document_, &LibraryDocument::reset, this, [this] { endResetModel(); });
}

void LibraryModel::setThumbnails(ThumbnailCache* thumbnails) {
    if (thumbnails_ == thumbnails) return;
    if (thumbnails_) thumbnails_->disconnect(this);
    thumbnails_ = thumbnails;
    if (thumbnails_)
        connect(thumbnails_, &ThumbnailCache::thumbnailChanged, this,
                [this](int row) { rowChanged(row, {Qt::DecorationRole}); });
    if (rowCount() > 0) emit dataChanged(index(0), index(rowCount() - 1), {Qt::DecorationRole});
}

const LibraryMaterial& LibraryModel::entry(const QModelIndex& index) const { return document_->entry(index.row()); }

int LibraryModel::rowCount(const QModelIndex& parent) const { return parent.isValid() ? 0 : document_->count(); }

QVariant LibraryModel::data(const QModelIndex& index, int role) const {
    if (!checkIndex(index, CheckIndexOption::IndexIsValid | CheckIndexOption::ParentIsInvalid)) return {};
    const LibraryMaterial& e = entry(index);
    const Material& m = e.material;
    switch (role) {
        case Qt::DisplayRole:
        case Qt::EditRole: return QString::fromStdString(e.name);
        case Qt::DecorationRole: {
            const QPixmap picture = thumbnails_ ? thumbnails_->thumbnail(m) : QPixmap();
            return picture.isNull() ? placeholder_ : picture;
        }
        case Qt::ToolTipRole: {
            if (m.layered) return layersSummary(m.layers);
            QString text = tr("λ %1 · n %2 · %3")
                               .arg(m.lambda, 0, 'f', 2)
                               .arg(exponentText(lambdaToExponent(m.lambda)))
                               .arg(QString::fromLatin1(lookupModeName(m.mode)));
            if (m.mode == LookupMode::Normal && m.useIrradiance) text += tr(" (irradiance)");
            text += tr(" · tint %1, %2, %3")
                        .arg(m.tint.r, 0, 'f', 3)
                        .arg(m.tint.g, 0, 'f', 3)
                        .arg(m.tint.b, 0, 'f', 3);
            if (m.sharperAtGrazing) text += tr(" · sharper at grazing");
            return text;
        }
        default: return {};
    }
}

bool LibraryModel::setData(const QModelIndex& index, const QVariant& value, int role) {
    if (!checkIndex(index, CheckIndexOption::IndexIsValid | CheckIndexOption::ParentIsInvalid)) return false;
    if (role != Qt::EditRole) return false;
    // The document refuses invalid and taken names; a rename arrives as entryChanged.
    return document_->rename(index.row(), value.toString());
}

Qt::ItemFlags LibraryModel::flags(const QModelIndex& index) const {
    if (!index.isValid()) return Qt::NoItemFlags;
    return Qt::ItemIsSelectable | Qt::ItemIsEnabled | Qt::ItemIsEditable | Qt::ItemIsDragEnabled |
           Qt::ItemNeverHasChildren;
}

QStringList LibraryModel::mimeTypes() const { return {QString::fromLatin1(kMaterialMimeType)}; }

QMimeData* LibraryModel::mimeData(const QModelIndexList& indexes) const {
    for (const QModelIndex& i : indexes)
        if (checkIndex(i, CheckIndexOption::IndexIsValid | CheckIndexOption::ParentIsInvalid))
            return materialMimeData(entry(i));
    return nullptr;
}

void LibraryModel::rowChanged(int row, const QList<int>& roles) {
    if (row < 0 || row >= rowCount()) return;
    const QModelIndex i = index(row);
    emit dataChanged(i, i, roles);
}

}  // namespace mipgloss::ui
