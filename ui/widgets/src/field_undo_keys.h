// The window's Undo and Redo keys in the panels' fields. A focused line edit or spin box takes
// Ctrl+Z and Ctrl+Shift+Z for its own text (it accepts the ShortcutOverride), so Edit → Undo never
// fired while one had the focus. In the Material and Environment panels a field's text history is
// only values the document already has (and undoes), so there the keys are the document's: the
// override is refused and the window's action fires. Typing not yet entered is undone as text
// first, as a user expects of a field being typed in. Fields elsewhere keep their text undo: the
// library's search text is in no document, and its Ctrl+Z should bring back what was typed.
#pragma once

#include <QObject>

#include <functional>

class QWidget;

namespace mipgloss::ui {

class FieldUndoKeys : public QObject {
public:
    // `inPanels`: whether a field is one whose keys are the document's.
    FieldUndoKeys(std::function<bool(const QWidget*)> inPanels, QObject* parent);

    bool eventFilter(QObject* watched, QEvent* event) override;

private:
    std::function<bool(const QWidget*)> inPanels_;
};

}  // namespace mipgloss::ui
