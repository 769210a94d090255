// How the scene list draws a row of SceneListModel (scene_list_model.h): the object's name, then
// its material's.
#pragma once

#include <QStyledItemDelegate>

namespace mipgloss::ui {

// Draws a row as usual and the material's name after the object's, in the disabled text colour,
// cut short (…) to the room left; the row's width stays the name's, so a long material name never
// makes the list scroll sideways.
class SceneListDelegate : public QStyledItemDelegate {
    Q_OBJECT
public:
    using QStyledItemDelegate::QStyledItemDelegate;
    void paint(QPainter* painter, const QStyleOptionViewItem& option, const QModelIndex& index) const override;
};

}  // namespace mipgloss::ui
