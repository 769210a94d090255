#include "mipgloss/ui/scene_list_delegate.h"

#include "mipgloss/ui/scene_list_model.h"

#include <QApplication>
#include <QPainter>

namespace mipgloss::ui {

namespace {
constexpr int kMaterialGap = 12;  // pixels between the object's name and its material's
}

void SceneListDelegate::paint(QPainter* painter, const QStyleOptionViewItem& option,
                              const QModelIndex& index) const {
    QStyledItemDelegate::paint(painter, option, index);
    const QString material = index.data(SceneListModel::MaterialNameRole).toString();
    if (material.isEmpty()) return;
    QStyleOptionViewItem opt = option;
    initStyleOption(&opt, index);
    const QWidget* widget = option.widget;
    const QStyle* style = widget ? widget->style() : QApplication::style();
    const QRect textRect = style->subElementRect(QStyle::SE_ItemViewItemText, &opt, widget);
    const int nameWidth = opt.fontMetrics.horizontalAdvance(opt.text);
    QRect materialRect = textRect.adjusted(nameWidth + kMaterialGap, 0, 0, 0);
    if (materialRect.width() <= opt.fontMetrics.averageCharWidth()) return;
    const bool selected = opt.state & QStyle::State_Selected;
    painter->save();
    QColor colour =
        opt.palette.color(QPalette::Disabled, selected ? QPalette::HighlightedText : QPalette::Text);
    if (selected) colour.setAlphaF(0.7f);
    painter->setPen(colour);
    painter->setFont(opt.font);
    painter->drawText(materialRect, Qt::AlignLeft | Qt::AlignVCenter,
                      opt.fontMetrics.elidedText(material, Qt::ElideRight, materialRect.width()));
    painter->restore();
}

}  // namespace mipgloss::ui
