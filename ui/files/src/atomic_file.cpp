#include "mipgloss/ui/atomic_file.h"

#include "mipgloss/io/atomic_write.h"

#include <QFile>

namespace mipgloss::ui {

void writeFileAtomically(const std::filesystem::path& file, const std::function<bool(QIODevice&)>& write) {
    mipgloss::writeAtomically(file, [&](int fd) {
        QFile out;  // on the atomic write's descriptor, which it leaves open (DontCloseHandle)
        if (!out.open(fd, QIODevice::WriteOnly, QFileDevice::DontCloseHandle))
            throw FileError(file, "cannot write: " + out.errorString().toStdString());
        const bool written = write(out) && out.flush();
        if (!written || out.error() != QFileDevice::NoError)
            throw FileError(file, "cannot write: " + (out.error() == QFileDevice::NoError
                                                          ? std::string("the data could not be encoded")
                                                          : out.errorString().toStdString()));
        out.close();
        if (out.error() != QFileDevice::NoError)
            throw FileError(file, "cannot write: " + out.errorString().toStdString());
    });
}

void writeFileAtomically(const std::filesystem::path& file, const QByteArray& bytes) {
    writeFileAtomically(file, [&bytes](QIODevice& device) { return device.write(bytes) == bytes.size(); });
}

}  // namespace mipgloss::ui
