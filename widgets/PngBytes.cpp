#include "PngBytes.h"

#include <QBuffer>
#include <QByteArray>
#include <QImage>

namespace contour {

std::string pngBytes(const QImage& image) {
    if (image.isNull())
        return {};
    QByteArray bytes;
    QBuffer buffer(&bytes);
    buffer.open(QIODevice::WriteOnly);
    if (!image.save(&buffer, "PNG"))
        return {};
    return bytes.toStdString();
}

} // namespace contour
