#include "mipgloss/ui/recent_files.h"

#include <QCoreApplication>
#include <QDir>
#include <QFileInfo>
#include <QSettings>
#include <QStandardPaths>

namespace mipgloss::ui {

namespace {

const QString kKey = QStringLiteral("recentFiles");

void store(const QStringList& files) { userSettings()->setValue(kKey, files); }

}  // namespace

std::unique_ptr<QSettings> userSettings() {
    // A default-constructed QSettings would do the same, but it looks the folder up once per
    // process, so test mode switched on later would not apply.
    const QString organisation = QCoreApplication::organizationName().isEmpty()
                                     ? QCoreApplication::applicationName()
                                     : QCoreApplication::organizationName();
    const QString file = QDir(QStandardPaths::writableLocation(QStandardPaths::GenericConfigLocation))
                             .filePath(organisation + QLatin1Char('/') + QCoreApplication::applicationName() +
                                       QStringLiteral(".conf"));
    return std::make_unique<QSettings>(file, QSettings::IniFormat);
}

QStringList RecentFiles::files() {
    QStringList files = userSettings()->value(kKey).toStringList();
    files.removeAll(QString());
    return files.mid(0, kMaxRecentFiles);
}

void RecentFiles::add(const QString& path) {
    const QString absolute = QFileInfo(path).absoluteFilePath();
    QStringList list = files();
    list.removeAll(absolute);
    list.prepend(absolute);
    store(list.mid(0, kMaxRecentFiles));
}

void RecentFiles::remove(const QString& path) {
    QStringList list = files();
    list.removeAll(QFileInfo(path).absoluteFilePath());
    list.removeAll(path);
    store(list);
}

void RecentFiles::clear() { store({}); }

QStringList RecentFiles::prune() {
    QStringList kept, gone;
    for (const QString& file : files()) (QFileInfo::exists(file) ? kept : gone) << file;
    if (!gone.isEmpty()) store(kept);
    return gone;
}

}  // namespace mipgloss::ui
