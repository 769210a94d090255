// One undo step per interaction with a widget. A panel asks key(widget) for the MergeKey of each
// edit it sends the document (scene_document.h); edits with the same key merge into one step. A
// widget's session, and with it its key, ends when it gains or loses the keyboard focus, and for
// a slider also when it is pressed or released. So a slider drag is one step, a run of arrow
// steps or typed values in one spin box while it keeps the focus is one step, and the next drag
// or the next visit to the box starts another.
#pragma once

#include "mipgloss/ui/scene_document.h"

#include <QObject>

#include <unordered_map>

class QWidget;

namespace mipgloss::ui {

class EditSessions : public QObject {
public:
    using QObject::QObject;

    // Ends `widget`'s sessions at the moments above. Call once per widget.
    void track(QWidget* widget);
    // The key of `widget`'s current session, starting one when there is none.
    SceneDocument::MergeKey key(const QObject* widget);
    void end(const QObject* widget) { keys_.erase(widget); }

protected:
    bool eventFilter(QObject* watched, QEvent* event) override;

private:
    std::unordered_map<const QObject*, SceneDocument::MergeKey> keys_;
};

}  // namespace mipgloss::ui
