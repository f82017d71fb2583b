#include "Resources.h"

#include <QFile>
#include <mutex>

// Outside any namespace, as Q_INIT_RESOURCE requires.
static void initContourResources() {
    Q_INIT_RESOURCE(contour_workbench);
}

namespace contour {

void registerContourResources() {
    static std::once_flag once;
    std::call_once(once, initContourResources);
}

QIcon resourceIcon(const QString& name) {
    registerContourResources();
    const QString path = QStringLiteral(":/icons/%1.svg").arg(name);
    if (!QFile::exists(path))
        return {};
    return QIcon(path);
}

} // namespace contour
