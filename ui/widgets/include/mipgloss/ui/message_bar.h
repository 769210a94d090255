// The window's messages: errors a user can cause (a broken mesh, environment or scene file, a
// failed save or export) and what was done. An error shows whole in a dismissable banner (this
// widget, above the view), its first line in the status line for 30 s, and is logged to stderr;
// information shows in the status line for 8 s, its lines joined. The status line, a label in the
// window's status bar, is one line cut short (…) to the room its neighbours leave, whole in its
// tooltip. lastMessage() keeps the last message either way.
//
// What an error in the banner is about (Kind). The rule: a later success of the same kind of
// action (a scene opened, an environment loaded, meshes imported, a library file imported or
// exported) takes the banner down, as what failed has been done since or the user has moved on to
// another file of that kind; a success of another kind says nothing about what failed and leaves
// it. Other errors (saving, exporting an image, OpenGL) stay until dismissed.
#pragma once

#include <QString>
#include <QWidget>

class QLabel;
class QStatusBar;
class QTimer;

namespace mipgloss::ui {

class ElidedLabel;

class MessageBar : public QWidget {
    Q_OBJECT
public:
    enum class Kind { Other, Scene, Environment, Meshes, Library };

    // The banner, hidden until an error comes, and the status line, added to `statusBar`. Named
    // "messageBanner"; its text "messageText", its dismiss button "dismissMessage", the status
    // line "statusMessage".
    MessageBar(QStatusBar* statusBar, QWidget* parent);

    // The last message shown (error or information) and whether it was an error.
    const QString& lastMessage() const { return lastMessage_; }
    bool lastMessageIsError() const { return lastMessageIsError_; }

    // Shows a message of no particular kind (an error's banner stays until dismissed). `log`
    // false: whoever reported the error has logged it already.
    void showMessage(const QString& message, bool error, bool log = true);
    // Shows a message about an action of `kind`, and applies the rule to the banner.
    void showMessageOf(Kind kind, const QString& message, bool error, bool log = true);
    // The rule alone, for a message of `kind` just shown.
    void noteOutcome(Kind kind, bool error);
    // Information that stays in the status line until the next message: an action under way
    // (opening an environment) whose end is a message of its own.
    void showUntilNextMessage(const QString& message);
    // The status line's whole text now (empty once it has timed out).
    const QString& statusText() const { return statusText_; }
    void clearStatus();

signals:
    void messageShown(const QString& message, bool error);

private:
    // The status line's message; gone after `timeoutMs` (0: until the next message).
    void showStatus(const QString& message, int timeoutMs);

    QLabel* text_ = nullptr;
    ElidedLabel* statusLine_ = nullptr;
    QTimer* statusTimer_ = nullptr;
    QString statusText_;
    QString lastMessage_;
    bool lastMessageIsError_ = false;
    Kind bannerKind_ = Kind::Other;
};

}  // namespace mipgloss::ui
