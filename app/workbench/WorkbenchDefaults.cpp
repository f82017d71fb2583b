#include "WorkbenchDefaults.h"

#include "Resources.h"

#include <QFile>
#include <QJsonArray>
#include <QJsonDocument>
#include <QJsonObject>

namespace contour {

namespace {

const char* const kPath = ":/settings/defaults.json";

[[noreturn]] void fail(const QString& why) {
    qFatal("%s: %s", kPath, qPrintable(why));
}

QJsonValue required(const QJsonObject& object, const char* key) {
    const QJsonValue value = object.value(QLatin1String(key));
    if (value.isUndefined())
        fail(QStringLiteral("no \"%1\"").arg(QLatin1String(key)));
    return value;
}

std::array<double, 3> triple(const QJsonValue& value, const char* key) {
    const QJsonArray a = value.toArray();
    if (a.size() != 3)
        fail(QStringLiteral("\"%1\" is not a triple").arg(QLatin1String(key)));
    return {a[0].toDouble(), a[1].toDouble(), a[2].toDouble()};
}

std::pair<int, int> pair(const QJsonValue& value, const char* key) {
    const QJsonArray a = value.toArray();
    if (a.size() != 2 || a[0].toInt() < 1 || a[1].toInt() < 1)
        fail(QStringLiteral("\"%1\" is not a pair of positive integers").arg(QLatin1String(key)));
    return {a[0].toInt(), a[1].toInt()};
}

} // namespace

bool WorkbenchDefaults::toggle(const std::string& key, bool fallback) const {
    const auto it = display.find(key);
    return it == display.end() ? fallback : it->second;
}

WorkbenchDefaults WorkbenchDefaults::load() {
    registerContourResources();
    QFile file(QString::fromLatin1(kPath));
    if (!file.open(QIODevice::ReadOnly))
        fail(QStringLiteral("cannot read the resource"));
    QJsonParseError error;
    const QJsonDocument document = QJsonDocument::fromJson(file.readAll(), &error);
    if (error.error != QJsonParseError::NoError || !document.isObject())
        fail(error.errorString());
    const QJsonObject root = document.object();

    WorkbenchDefaults d;
    d.method = required(root, "method").toString();
    const QJsonObject window = required(root, "window").toObject();
    const auto [width, height] = pair(required(window, "size"), "size");
    d.windowSize = QSize(width, height);
    d.layout = required(window, "layout").toString();
    const QJsonObject camera = required(root, "analysisCamera").toObject();
    const auto direction = triple(required(camera, "viewDirection"), "viewDirection");
    d.viewDirection = Vec3(direction[0], direction[1], direction[2]);
    if (!(d.viewDirection.norm() > 0.0))
        fail(QStringLiteral("\"viewDirection\" is zero"));
    const auto [vw, vh] = pair(required(camera, "fallbackViewport"), "fallbackViewport");
    d.fallbackViewport = Viewport{vw, vh};
    const QJsonObject display = required(root, "display").toObject();
    d.colourBy = required(display, "colourBy").toString();
    for (auto it = display.begin(); it != display.end(); ++it)
        if (it.value().isBool())
            d.display[it.key().toStdString()] = it.value().toBool();
    d.comparisonTolerancePixels = required(root, "comparisonTolerancePixels").toDouble(-1.0);
    if (!(d.comparisonTolerancePixels >= 0.0))
        fail(QStringLiteral("\"comparisonTolerancePixels\" is negative"));
    return d;
}

} // namespace contour
