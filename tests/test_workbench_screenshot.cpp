// contour-workbench --screenshot, run as a program: on a small sample it
// writes a PNG of the whole window at the size asked for, which shows the
// shaded surface (the 3D view's GL content was grabbed, not black) and more
// than a few colours; a planned method, a missing mesh or an unwritable
// output fail with a message and write nothing; --help documents the option;
// --ground-truth draws the dense ground truth's teal over the consistent
// method's drawing, and says why when the method has no smooth surface.
// Needs a display: run under `xvfb-run -a -s "-screen 0 1600x1200x24"`.
#include <QColor>
#include <QFile>
#include <QFileInfo>
#include <QImage>
#include <QProcess>
#include <QSet>
#include <QTemporaryDir>
#include <QtTest>
#include <algorithm>
#include <cmath>

namespace {

const char* const kProgram = CONTOUR_BINARY_DIR "/app/workbench/contour-workbench";
const char* const kTorus = CONTOUR_SOURCE_DIR "/samples/torus.obj";
const char* const kSpot = CONTOUR_SOURCE_DIR "/samples/spot_control_mesh.obj";

struct Run {
    int exitCode = -1;
    QString out, err;
};

Run run(const QStringList& args) {
    QProcess process;
    process.start(QString::fromLatin1(kProgram), args);
    Run r;
    if (!process.waitForStarted() || !process.waitForFinished(600000)) {
        process.kill();
        process.waitForFinished();
        r.err = QStringLiteral("did not run");
        return r;
    }
    r.out = QString::fromUtf8(process.readAllStandardOutput());
    r.err = QString::fromUtf8(process.readAllStandardError());
    r.exitCode = process.exitStatus() == QProcess::NormalExit ? process.exitCode() : -2;
    return r;
}

// Pixels whose hue is near `reference`'s, saturated enough to be a surface
// colour (lighting scales a colour, it keeps its hue).
long long pixelsOfHue(const QImage& image, const QColor& reference) {
    const float hue = reference.hueF();
    long long n = 0;
    for (int y = 0; y < image.height(); ++y)
        for (int x = 0; x < image.width(); ++x) {
            const QColor c = QColor::fromRgb(image.pixel(x, y));
            float d = std::abs(c.hueF() - hue);
            d = std::min(d, 1.0f - d);
            n += c.hsvSaturationF() > 0.3f && c.valueF() > 0.2f && d < 0.03f;
        }
    return n;
}

} // namespace

class TestWorkbenchScreenshot : public QObject {
    Q_OBJECT

private slots:
    void initTestCase() {
        QVERIFY2(QFile::exists(QString::fromLatin1(kProgram)), kProgram);
        QVERIFY2(QFile::exists(QString::fromLatin1(kTorus)), kTorus);
        QVERIFY(dir_.isValid());
    }

    void helpDocumentsTheOption() {
        const Run r = run({QStringLiteral("--help")});
        QCOMPARE(r.exitCode, 0);
        QVERIFY2(r.out.contains(QStringLiteral("--screenshot <FILE.png>")), qPrintable(r.out));
        QVERIFY(r.out.contains(QStringLiteral("--method <NAME>")));
        QVERIFY(r.out.contains(QStringLiteral("--size <WxH>")));
        QVERIFY(r.out.contains(QStringLiteral("--ground-truth")));
    }

    void drawsTheGroundTruthWhenAsked() {
        const QString png = dir_.filePath(QStringLiteral("spot-ground-truth.png"));
        const QStringList args{QString::fromLatin1(kSpot), QStringLiteral("--method"),
                               QStringLiteral("consistent"), QStringLiteral("--size"),
                               QStringLiteral("1400x850")};
        Run r = run(args + QStringList{QStringLiteral("--ground-truth"),
                                       QStringLiteral("--screenshot"), png});
        QVERIFY2(r.exitCode == 0, qPrintable(r.err));
        QImage with;
        QVERIFY2(with.load(png, "PNG"), qPrintable(png));
        const QString plainPng = dir_.filePath(QStringLiteral("spot.png"));
        r = run(args + QStringList{QStringLiteral("--screenshot"), plainPng});
        QVERIFY2(r.exitCode == 0, qPrintable(r.err));
        QImage without;
        QVERIFY2(without.load(plainPng, "PNG"), qPrintable(plainPng));
        // The ground truth's teal (resources/colormaps/scene-colors.json).
        const QColor teal = QColor::fromRgbF(0.0f, 0.62f, 0.53f);
        const long long tealWith = pixelsOfHue(with.convertToFormat(QImage::Format_RGB32), teal);
        const long long tealWithout =
            pixelsOfHue(without.convertToFormat(QImage::Format_RGB32), teal);
        QVERIFY2(tealWith > 1000 && tealWithout < tealWith / 5,
                 qPrintable(
                     QStringLiteral("%1 teal pixels, %2 without").arg(tealWith).arg(tealWithout)));
        // The mesh method on the cage has no smooth surface.
        const QString never = dir_.filePath(QStringLiteral("never-ground-truth.png"));
        r = run({QString::fromLatin1(kSpot), QStringLiteral("--method"), QStringLiteral("mesh"),
                 QStringLiteral("--ground-truth"), QStringLiteral("--screenshot"), never});
        QCOMPARE(r.exitCode, 1);
        QVERIFY2(r.err.contains(QStringLiteral("surface = none")), qPrintable(r.err));
        QVERIFY(!QFile::exists(never));
    }

    void writesThePictureOfTheWindow() {
        const QString png = dir_.filePath(QStringLiteral("torus.png"));
        const Run r = run({QString::fromLatin1(kTorus), QStringLiteral("--method"),
                           QStringLiteral("mesh"), QStringLiteral("--size"),
                           QStringLiteral("1000x640"), QStringLiteral("--screenshot"), png});
        QVERIFY2(r.exitCode == 0, qPrintable(r.err));
        QImage image;
        QVERIFY2(image.load(png, "PNG"), qPrintable(png));
        QVERIFY(QFileInfo(png).size() > 0);
        QCOMPARE(image.size(), QSize(1000, 640));
        const QImage rgb = image.convertToFormat(QImage::Format_RGB32);
        QSet<QRgb> colours;
        long long dark = 0;
        for (int y = 0; y < rgb.height(); ++y)
            for (int x = 0; x < rgb.width(); ++x) {
                const QRgb c = rgb.pixel(x, y);
                colours.insert(c);
                dark += qRed(c) + qGreen(c) + qBlue(c) < 24;
            }
        QVERIFY2(colours.size() > 200, qPrintable(QString::number(colours.size())));
        QVERIFY(dark < static_cast<long long>(rgb.width()) * rgb.height() / 2);
        // The 3D view's surface: front faces in warm yellow, back faces in
        // blue (SceneColors.h; resources/colormaps/scene-colors.json).
        QVERIFY(pixelsOfHue(rgb, QColor::fromRgbF(1.0f, 0.84f, 0.42f)) > 2000);
    }

    void failuresSayWhyAndWriteNothing() {
        const QString png = dir_.filePath(QStringLiteral("never.png"));
        Run r = run({QString::fromLatin1(kTorus), QStringLiteral("--method"),
                     QStringLiteral("bogus"), QStringLiteral("--screenshot"), png});
        QCOMPARE(r.exitCode, 2);
        QVERIFY2(r.err.contains(QStringLiteral("unknown method")), qPrintable(r.err));
        r = run(
            {dir_.filePath(QStringLiteral("missing.obj")), QStringLiteral("--screenshot"), png});
        QCOMPARE(r.exitCode, 1);
        QVERIFY2(r.err.contains(QStringLiteral("missing.obj")), qPrintable(r.err));
        r = run({QStringLiteral("--screenshot"), png});
        QCOMPARE(r.exitCode, 2);
        QVERIFY2(r.err.contains(QStringLiteral("needs a mesh")), qPrintable(r.err));
        r = run({QString::fromLatin1(kTorus), QStringLiteral("--size"), QStringLiteral("big"),
                 QStringLiteral("--screenshot"), png});
        QCOMPARE(r.exitCode, 2);
        QVERIFY2(r.err.contains(QStringLiteral("--size")), qPrintable(r.err));
        QVERIFY(!QFile::exists(png));
        const QString unwritable = dir_.filePath(QStringLiteral("no-such-folder/shot.png"));
        r = run({QString::fromLatin1(kTorus), QStringLiteral("--method"), QStringLiteral("mesh"),
                 QStringLiteral("--screenshot"), unwritable});
        QCOMPARE(r.exitCode, 1);
        QVERIFY2(r.err.contains(QStringLiteral("shot.png")), qPrintable(r.err));
        QVERIFY(!QFile::exists(unwritable));
    }

private:
    QTemporaryDir dir_;
};

QTEST_GUILESS_MAIN(TestWorkbenchScreenshot)

#include "test_workbench_screenshot.moc"
