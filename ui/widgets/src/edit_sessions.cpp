#include "edit_sessions.h"

#include <QAbstractSlider>
#include <QEvent>
#include <QWidget>

namespace mipgloss::ui {

void EditSessions::track(QWidget* widget) {
    widget->installEventFilter(this);
    connect(widget, &QObject::destroyed, this, [this, widget] { end(widget); });
    if (auto* slider = qobject_cast<QAbstractSlider*>(widget)) {
        connect(slider, &QAbstractSlider::sliderPressed, this, [this, slider] { end(slider); });
        connect(slider, &QAbstractSlider::sliderReleased, this, [this, slider] { end(slider); });
    }
}

SceneDocument::MergeKey EditSessions::key(const QObject* widget) {
    auto [it, inserted] = keys_.try_emplace(widget, 0);
    if (inserted) it->second = SceneDocument::newMergeKey();
    return it->second;
}

bool EditSessions::eventFilter(QObject* watched, QEvent* event) {
    if (event->type() == QEvent::FocusIn || event->type() == QEvent::FocusOut) end(watched);
    return false;
}

}  // namespace mipgloss::ui
