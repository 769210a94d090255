#include "image_export.h"

#include "mipgloss/io/image_file.h"
#include "mipgloss/ui/atomic_file.h"
#include "mipgloss/ui/viewport.h"

#include <QFileInfo>
#include <QImage>

#include <cmath>
#include <vector>

namespace mipgloss::ui {

QSize devicePixelSize(const QWidget& widget) {
    const qreal ratio = widget.devicePixelRatio();
    return {static_cast<int>(std::lround(widget.width() * ratio)), static_cast<int>(std::lround(widget.height() * ratio))};
}

ExportedImage exportViewImage(Viewport& viewport, const QString& path, QSize size, bool showBackground) {
    QByteArray format = QFileInfo(path).suffix().toUpper().toLatin1();
    if (format.isEmpty()) format = "PNG";
    const bool exr = format == "EXR";
    // Before anything is drawn: a folder that cannot take the file.
    const QFileInfo folder(QFileInfo(path).absolutePath());
    if (!folder.isDir()) throw FileError(path.toStdString(), "its folder does not exist");
    if (!folder.isWritable()) throw FileError(path.toStdString(), "its folder is not writable");
    QString why;
    std::vector<float> hdr;
    const QImage image =
        viewport.renderImage(size.width(), size.height(), /*transparent=*/true, exr ? &hdr : nullptr, &why);
    if (image.isNull()) throw FileError(path.toStdString(), why.toStdString());
    if (exr) {
        writeFloatChannels(path.toStdString(), image.width(), image.height(), {"R", "G", "B", "A"}, hdr);
    } else {
        // Straight alpha (the tone pass un-premultiplies); opaque where the background shows.
        const QImage out = showBackground ? image.convertToFormat(QImage::Format_RGB888)
                                          : image.convertToFormat(QImage::Format_RGBA8888);
        writeFileAtomically(path.toStdString(), [&](QIODevice& device) { return out.save(&device, format.constData()); });
    }
    return {image.size(), exr};
}

}  // namespace mipgloss::ui
