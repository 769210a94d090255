#include "scene_list_panel.h"

#include "mipgloss/ui/scene_document.h"
#include "mipgloss/ui/scene_list_delegate.h"
#include "mipgloss/ui/scene_list_model.h"

#include <QAction>
#include <QHBoxLayout>
#include <QListView>
#include <QToolButton>
#include <QVBoxLayout>

namespace mipgloss::ui {

SceneListPanel::SceneListPanel(SceneDocument* document, const QList<QAction*>& actions, QWidget* parent)
    : QWidget(parent), document_(document) {
    auto* layout = new QVBoxLayout(this);
    list_ = new QListView(this);
    model_ = new SceneListModel(document_, this);
    list_->setObjectName(QStringLiteral("sceneList"));
    list_->setModel(model_);
    list_->setItemDelegate(new SceneListDelegate(list_));
    list_->setSelectionMode(QAbstractItemView::SingleSelection);
    list_->setContextMenuPolicy(Qt::ActionsContextMenu);
    // Library materials dropped onto a row (SceneListModel::dropMimeData).
    list_->setDragDropMode(QAbstractItemView::DropOnly);
    list_->setDefaultDropAction(Qt::CopyAction);
    list_->setDropIndicatorShown(true);
    layout->addWidget(list_, 1);

    // Selection, both ways. The model moves rows rather than resetting, and the document hands a
    // removed object's selection on before removing it, so the list's selection never changes
    // behind the document's back; each direction sets the other only when it differs, so the
    // round trip ends there.
    connect(list_->selectionModel(), &QItemSelectionModel::selectionChanged, this, [this] {
        const QModelIndexList rows = list_->selectionModel()->selectedRows();
        document_->setSelected(rows.isEmpty() ? -1 : rows.first().row());
    });
    connect(document_, &SceneDocument::selectionChanged, this, &SceneListPanel::showSelection);

    list_->addActions(actions);
    auto* buttons = new QHBoxLayout;
    for (QAction* action : actions) {
        auto* button = new QToolButton(this);
        button->setDefaultAction(action);
        buttons->addWidget(button);
    }
    buttons->addStretch(1);
    layout->addLayout(buttons);
    showSelection(document_->selected());
}

void SceneListPanel::showSelection(int index) {
    QItemSelectionModel* selection = list_->selectionModel();
    if (document_->isValidIndex(index))
        selection->setCurrentIndex(model_->index(index), QItemSelectionModel::ClearAndSelect);
    else
        selection->clear();
}

}  // namespace mipgloss::ui
