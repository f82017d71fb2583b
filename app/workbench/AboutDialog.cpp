#include "AboutDialog.h"

#include <CGAL/version.h>
#include <CLI/Version.hpp>
#include <Eigen/Core>
#include <QMessageBox>
#include <QStringList>
#include <QtGlobal>
#include <embree3/rtcore_config.h>
#include <nlohmann/json.hpp>
#include <oneapi/tbb/version.h>
#include <opensubdiv/version.h>
#include <vtkVersion.h>

// CGAL_VERSION is a bare token sequence (5.5.1): stringize it.
#define CONTOUR_STRINGIZE_(x) #x
#define CONTOUR_STRINGIZE(x) CONTOUR_STRINGIZE_(x)

namespace contour {

QString libraryVersionsText() {
    const auto numbers = [](int a, int b, int c) {
        return QStringLiteral("%1.%2.%3").arg(a).arg(b).arg(c);
    };
    QStringList lines;
    lines << QStringLiteral("Qt %1 (built with %2)")
                 .arg(QString::fromLatin1(qVersion()), QStringLiteral(QT_VERSION_STR));
    lines << QStringLiteral("VTK %1").arg(QString::fromLatin1(vtkVersion::GetVTKVersion()));
    lines << QStringLiteral("CGAL %1").arg(QStringLiteral(CONTOUR_STRINGIZE(CGAL_VERSION)));
    lines << QStringLiteral("Eigen %1")
                 .arg(numbers(EIGEN_WORLD_VERSION, EIGEN_MAJOR_VERSION, EIGEN_MINOR_VERSION));
    lines << QStringLiteral("OpenSubdiv %1")
                 .arg(numbers(OPENSUBDIV_VERSION_MAJOR, OPENSUBDIV_VERSION_MINOR,
                              OPENSUBDIV_VERSION_PATCH));
    lines << QStringLiteral("Embree %1").arg(QStringLiteral(RTC_VERSION_STRING));
    lines << QStringLiteral("oneTBB %1 (runs with %2)")
                 .arg(QStringLiteral(TBB_VERSION_STRING),
                      QString::fromLatin1(TBB_runtime_version()));
    lines << QStringLiteral("nlohmann-json %1")
                 .arg(numbers(NLOHMANN_JSON_VERSION_MAJOR, NLOHMANN_JSON_VERSION_MINOR,
                              NLOHMANN_JSON_VERSION_PATCH));
    lines << QStringLiteral("CLI11 %1 (contour-batch)").arg(QStringLiteral(CLI11_VERSION));
    return lines.join(QLatin1Char('\n'));
}

void showAboutDialog(QWidget* parent) {
    QString text = QObject::tr("<h3>Contour Workbench %1</h3>"
                               "<p>Computes, steps through and inspects the occluding contours "
                               "of 3D surfaces: mesh, interpolated and consistent contours "
                               "(Bénard, Hertzmann &amp; Kass 2014), their view graphs and "
                               "visibility.</p><p>Libraries:</p><ul>")
                       .arg(QStringLiteral(CONTOUR_VERSION));
    for (const QString& line : libraryVersionsText().split(QLatin1Char('\n')))
        text += QStringLiteral("<li>%1</li>").arg(line.toHtmlEscaped());
    text += QStringLiteral("</ul>");
    auto* box = new QMessageBox(QMessageBox::Information, QObject::tr("About Contour Workbench"),
                                text, QMessageBox::Ok, parent);
    box->setTextFormat(Qt::RichText);
    box->setAttribute(Qt::WA_DeleteOnClose);
    box->open();
}

} // namespace contour
