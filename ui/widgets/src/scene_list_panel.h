// The Scene dock's panel: the scene's objects, one a row (scene_list_model.h, drawn by
// scene_list_delegate.h), with buttons and a context menu for the actions the window gives it
// (Duplicate, Remove, Frame all). Library materials dropped onto a row are applied to its object.
// The list's selection and the document's are one: each follows the other.
#pragma once

#include <QList>
#include <QWidget>

class QAction;
class QListView;

namespace mipgloss::ui {

class SceneDocument;
class SceneListModel;

class SceneListPanel : public QWidget {
public:
    SceneListPanel(SceneDocument* document, const QList<QAction*>& actions, QWidget* parent);

    QListView* list() const { return list_; }

private:
    void showSelection(int index);

    SceneDocument* document_;
    QListView* list_ = nullptr;
    SceneListModel* model_ = nullptr;
};

}  // namespace mipgloss::ui
