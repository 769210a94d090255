#include "mipgloss/ui/scene_list_model.h"

#include "mipgloss/ui/material_mime.h"
#include "mipgloss/ui/scene_document.h"

#include <QLocale>
#include <QMimeData>

namespace mipgloss::ui {

SceneListModel::SceneListModel(SceneDocument* document, QObject* parent)
    : QAbstractListModel(parent), document_(document) {
    connect(document_, &SceneDocument::objectAboutToBeInserted, this,
            [this](int row) { beginInsertRows({}, row, row); });
    connect(document_, &SceneDocument::objectInserted, this, [this](int) { endInsertRows(); });
    connect(document_, &SceneDocument::objectAboutToBeRemoved, this,
            [this](int row) { beginRemoveRows({}, row, row); });
    connect(document_, &SceneDocument::objectRemoved, this, [this](int) { endRemoveRows(); });
    connect(document_, &SceneDocument::aboutToReset, this, [this] { beginResetModel(); });
    connect(document_, &SceneDocument::sceneReset, this, [this] { endResetModel(); });
    connect(document_, &SceneDocument::objectChanged, this, &SceneListModel::rowChanged);
    connect(document_, &SceneDocument::materialChanged, this, &SceneListModel::rowChanged);
}

int SceneListModel::rowCount(const QModelIndex& parent) const {
    return parent.isValid() ? 0 : document_->objectCount();
}

QVariant SceneListModel::data(const QModelIndex& index, int role) const {
    if (!checkIndex(index, CheckIndexOption::IndexIsValid | CheckIndexOption::ParentIsInvalid))
        return {};
    const SceneObject& object = document_->object(index.row());
    const NamedMaterial* named = document_->namedMaterialOf(index.row());
    switch (role) {
        case Qt::DisplayRole:
        case Qt::EditRole: return QString::fromStdString(object.name);
        case MaterialNameRole: return named ? QString::fromStdString(named->name) : QString();
        case Qt::CheckStateRole: return object.visible ? Qt::Checked : Qt::Unchecked;
        case Qt::ToolTipRole: {
            const Material& m = document_->materialOf(index.row());
            const qlonglong triangles =
                object.mesh ? static_cast<qlonglong>(object.mesh->triangleCount()) : 0;
            QString text = named ? QString::fromStdString(named->name) + QStringLiteral(" · ") : QString();
            if (m.layered) {
                text += layersSummary(m.layers);
            } else {
                text += tr("λ %1 · %2").arg(m.lambda, 0, 'f', 2).arg(lookupModeName(m.mode));
                if (m.mode == LookupMode::Normal && m.useIrradiance) text += tr(" (irradiance)");
            }
            text += tr(" · %1 triangles").arg(QLocale().toString(triangles));
            return text;
        }
        default: return {};
    }
}

bool SceneListModel::setData(const QModelIndex& index, const QVariant& value, int role) {
    if (!checkIndex(index, CheckIndexOption::IndexIsValid | CheckIndexOption::ParentIsInvalid))
        return false;
    // The document emits objectChanged, which becomes dataChanged through rowChanged.
    if (role == Qt::CheckStateRole) {
        document_->setVisible(index.row(),
                              static_cast<Qt::CheckState>(value.toInt()) == Qt::Checked);
        return true;
    }
    if (role == Qt::EditRole) {
        const QString name = value.toString().trimmed();
        if (name.isEmpty()) return false;
        document_->setName(index.row(), name);
        return true;
    }
    return false;
}

Qt::ItemFlags SceneListModel::flags(const QModelIndex& index) const {
    if (!index.isValid()) return Qt::NoItemFlags;
    return Qt::ItemIsSelectable | Qt::ItemIsEnabled | Qt::ItemIsUserCheckable |
           Qt::ItemIsEditable | Qt::ItemNeverHasChildren | Qt::ItemIsDropEnabled;
}

QStringList SceneListModel::mimeTypes() const { return {QString::fromLatin1(kMaterialMimeType)}; }

Qt::DropActions SceneListModel::supportedDropActions() const { return Qt::CopyAction; }

bool SceneListModel::canDropMimeData(const QMimeData* data, Qt::DropAction, int, int,
                                     const QModelIndex& parent) const {
    // Only onto an object: between rows there is nothing to apply it to.
    return parent.isValid() && parent.model() == this && data &&
           data->hasFormat(QString::fromLatin1(kMaterialMimeType));
}

bool SceneListModel::dropMimeData(const QMimeData* data, Qt::DropAction action, int row, int column,
                                  const QModelIndex& parent) {
    if (!canDropMimeData(data, action, row, column, parent)) return false;
    const std::optional<LibraryMaterial> entry = materialFromMimeData(data);
    if (!entry) return false;
    document_->applyLibraryMaterial(parent.row(), *entry);
    return true;
}

void SceneListModel::rowChanged(int row) {
    if (row < 0 || row >= rowCount()) return;
    const QModelIndex i = index(row);
    emit dataChanged(i, i);
}

QString layersSummary(const Layers& l) {
    QString text = l.metallic >= 1.0f ? SceneListModel::tr("metal %1, %2, %3")
                                      : SceneListModel::tr("base %1, %2, %3");
    text = text.arg(l.baseColor.r, 0, 'f', 2).arg(l.baseColor.g, 0, 'f', 2).arg(l.baseColor.b, 0, 'f', 2);
    if (l.metallic > 0.0f && l.metallic < 1.0f) text += SceneListModel::tr(" · metallic %1").arg(l.metallic, 0, 'f', 2);
    text += SceneListModel::tr(" · roughness %1").arg(l.roughness, 0, 'f', 2);
    if (l.coat > 0.0f)
        text += SceneListModel::tr(" · coat %1 (roughness %2)").arg(l.coat, 0, 'f', 2).arg(l.coatRoughness, 0, 'f', 2);
    return text;
}

}  // namespace mipgloss::ui
