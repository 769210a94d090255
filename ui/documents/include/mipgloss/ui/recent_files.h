// The recently opened and saved scene files (File → Open Recent), newest first, at most
// kMaxRecentFiles, kept in the user's settings (QSettings, key "recentFiles"). The settings file is
// located through QStandardPaths every time, so tests under QStandardPaths::setTestModeEnabled
// never touch the user's own.
#pragma once

#include <QString>
#include <QStringList>

#include <memory>

class QSettings;

namespace mipgloss::ui {

inline constexpr int kMaxRecentFiles = 8;

// The application's settings: <GenericConfigLocation>/<organisation>/<application>.conf, where a
// default QSettings keeps them too.
std::unique_ptr<QSettings> userSettings();

class RecentFiles {
public:
    static QStringList files();
    // Puts `path` (made absolute) first, dropping an older entry for it and any beyond the limit.
    static void add(const QString& path);
    static void remove(const QString& path);
    static void clear();
    // Drops the entries whose files no longer exist and returns them.
    static QStringList prune();
};

}  // namespace mipgloss::ui
