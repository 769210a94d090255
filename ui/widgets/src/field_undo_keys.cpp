#include "field_undo_keys.h"

#include <QDoubleSpinBox>
#include <QKeyEvent>
#include <QLineEdit>

namespace mipgloss::ui {

namespace {

// True while a field shows text it has not handed on: a spin box whose text is not its value's, a
// line edit edited since it was last set.
bool beingTyped(const QWidget* field) {
    if (const auto* spin = qobject_cast<const QDoubleSpinBox*>(field)) {
        const bool special = !spin->specialValueText().isEmpty() && spin->value() == spin->minimum();
        const QString shown =
            special ? spin->specialValueText() : spin->prefix() + spin->textFromValue(spin->value()) + spin->suffix();
        return spin->text() != shown;
    }
    if (const auto* edit = qobject_cast<const QLineEdit*>(field)) return edit->isModified();
    return false;
}

}  // namespace

FieldUndoKeys::FieldUndoKeys(std::function<bool(const QWidget*)> inPanels, QObject* parent)
    : QObject(parent), inPanels_(std::move(inPanels)) {}

bool FieldUndoKeys::eventFilter(QObject* watched, QEvent* event) {
    if (event->type() != QEvent::ShortcutOverride) return false;
    const auto* key = static_cast<QKeyEvent*>(event);
    if (!key->matches(QKeySequence::Undo) && !key->matches(QKeySequence::Redo)) return false;
    const auto* field = qobject_cast<QWidget*>(watched);
    if (!field || !(qobject_cast<const QAbstractSpinBox*>(field) || qobject_cast<const QLineEdit*>(field)) ||
        !inPanels_(field) || beingTyped(field))
        return false;
    event->ignore();  // not the field's: the shortcut goes to the window's action
    return true;
}

}  // namespace mipgloss::ui
