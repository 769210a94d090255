#include "mipgloss/ui/atomic_file.h"

#include <QDir>
#include <QFileInfo>
#include <QSaveFile>

namespace mipgloss::ui {

void writeFileAtomically(const std::filesystem::path& file, const std::function<bool(QIODevice&)>& write) {
    const QString path = QString::fromStdString(file.string());
    const QString folder = QFileInfo(path).absolutePath();
    if (!QDir().mkpath(folder)) throw FileError(file, "cannot create the folder " + folder.toStdString());
    QSaveFile out(path);
    // QSaveFile renames over the target; never fall back to writing it in place.
    out.setDirectWriteFallback(false);
    if (!out.open(QIODevice::WriteOnly)) throw FileError(file, "cannot write: " + out.errorString().toStdString());
    if (!write(out)) {
        out.cancelWriting();
        throw FileError(file, "cannot write: " + (out.errorString().isEmpty()
                                                      ? std::string("the data could not be encoded")
                                                      : out.errorString().toStdString()));
    }
    if (!out.commit()) throw FileError(file, "cannot write: " + out.errorString().toStdString());
}

void writeFileAtomically(const std::filesystem::path& file, const QByteArray& bytes) {
    writeFileAtomically(file, [&bytes](QIODevice& device) { return device.write(bytes) == bytes.size(); });
}

}  // namespace mipgloss::ui
