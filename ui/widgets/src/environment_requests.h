// The environments the document asks for, as the user hears of them. Opening a file or folder
// (File → Open environment, drops, the command line) is one undo step on the document, and the
// status line says "Opening environment sky.exr…" until it is drawn ("Loaded sky.exr", perhaps
// before its chain is built) or the document no longer asks for it (undone, another scene opened).
//
// Any environment that cannot be read (opened, undone to, or named by a scene) is an error of the
// environment kind (message_bar.h: Kind) and never changes what is drawn: the document's
// environment settings are put back to the environment drawn, without an undo step (the step that
// asked for the file is withdrawn, SceneDocument::withdrawFailedEnvironment).
#pragma once

#include <QObject>
#include <QString>

#include <string>

namespace mipgloss::ui {

class EnvironmentManager;
class MessageBar;
class SceneDocument;

class EnvironmentRequests : public QObject {
public:
    EnvironmentRequests(SceneDocument* document, EnvironmentManager* environments, MessageBar* messages,
                        QObject* parent);

    // Sets the document's environment source to `path` (a file, a face of a six-face set or a
    // directory). False (with a message) if it does not exist; a file that exists but cannot be
    // read fails later, through EnvironmentManager::failed.
    bool open(const QString& path);

private:
    // Ends "Opening environment …" once that environment is drawn or no longer asked for.
    void noteOpened();
    void onFailed(const QString& message);

    SceneDocument* document_;
    EnvironmentManager* environments_;
    MessageBar* messages_;
    // The file or folder open() asked for, until it is loaded or fails.
    std::string opening_;
};

}  // namespace mipgloss::ui
