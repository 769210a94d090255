#include "mipgloss/ui/scene_list_model.h"

#include "mipgloss/ui/scene_document.h"

#include <QLocale>

namespace mipgloss::ui {

SceneListModel::SceneListModel(SceneDocument* document, QObject* parent)
    : QAbstractListModel(parent), document_(document) {
    // Any change of the object list resets the model: rows are cheap and the list is short, and
    // a reset is the only notification that is right for every add/remove/duplicate/replace.
    connect(document_, &SceneDocument::objectsChanged, this, [this] {
        beginResetModel();
        endResetModel();
    });
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
    switch (role) {
        case Qt::DisplayRole:
        case Qt::EditRole: return QString::fromStdString(object.name);
        case Qt::CheckStateRole: return object.visible ? Qt::Checked : Qt::Unchecked;
        case Qt::ToolTipRole: {
            const Material& m = document_->materialOf(index.row());
            const qlonglong triangles =
                object.mesh ? static_cast<qlonglong>(object.mesh->triangleCount()) : 0;
            QString text = tr("λ %1 · %2").arg(m.lambda, 0, 'f', 2).arg(lookupModeName(m.mode));
            if (m.mode == LookupMode::Normal && m.useIrradiance) text += tr(" (irradiance)");
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
           Qt::ItemIsEditable | Qt::ItemNeverHasChildren;
}

void SceneListModel::rowChanged(int row) {
    if (row < 0 || row >= rowCount()) return;
    const QModelIndex i = index(row);
    emit dataChanged(i, i);
}

}  // namespace mipgloss::ui
