// bench_workbench: the workbench's two interactive figures, measured on the
// real main window. A benchmark: it prints figures and asserts nothing.
//
//   xvfb-run -a -s "-screen 0 1920x1200x24" bench_workbench
//       [--meshes-dir DIR] [--orbit-mesh NAME] [--orbit-method M] [--frames N]
//       [--step-mesh NAME] [--move-mesh NAME] [--move-method M] [--moves N]
//       [--parts orbit,step,move] [--width W] [--height H] [--out figures.csv]
//
// Part 1, orbit frame rate: the orbit model (default controlmesh with the
// consistent method: about 117k faces at its last phase, every 3D overlay
// and the view graph available) is run to the end; every overlay is switched
// on; then the 3D view is orbited N times by 360/N degrees, each frame
// scheduled and the event loop run until it is drawn (VTK renders in
// paintGL, then Qt composes the window), as during an interactive orbit;
// frames per second = N / wall time, next to the process's CPU time per
// frame (all threads, llvmpipe's included: the figure to compare on a busy
// machine). Measured four ways: the full drawing; the lighter drawing a drag
// switches on (SceneView3D::setMotionDrawing: 1 px lines, square points, no
// translucent tint) without and with the decimated copy of the mesh
// (SceneView3D::setLevelOfDetail, waited for before timing); and a real drag:
// mouse press, N moves and release sent to the view, the interactor's
// trackball turning the camera by 360/N degrees per move, so motion drawing
// and the decimated copy are switched on as a user gets them. The render
// count of the view is checked to have grown by N (a frame that was not
// drawn is not counted).
//
// Part 2, step latency: the step model (default bob_quad: its consistent
// output is about 48.5k faces) is reset to the input and stepped one phase
// at a time; per phase, the wall time from MainWindow::stepPhase() until the
// window is idle again and both views have repainted with the new snapshot,
// next to the phase's own Snapshot::phaseSeconds (the rest is the window:
// post-condition checks, snapshot-to-VTK conversion, rendering).
//
// Part 3, camera-move latency: the move model (default spot_control_mesh with
// the powell-sabin method) is run to the end; then the 3D view is orbited N
// times by 360/N degrees and each time taken as the analysis camera
// (MainWindow::setAnalysisCameraFromView, what View > Camera from view
// does): the wall time from there until the window is idle and both views
// have repainted with the new view's snapshot, next to the sum of the
// phases' Snapshot::phaseSeconds (the view-independent phases come from the
// preprocessing cache and cost only the lookup).
//
// Under Xvfb, rendering is Mesa's llvmpipe on the CPU: a desktop GPU is
// faster. The figures say which renderer ran.
#include "BenchSupport.h"
#include "ImageView2D.h"
#include "MainWindow.h"
#include "SceneView3D.h"
#include "SurfaceFormat.h"
#include "pipeline/CounterNames.h"
#include "pipeline/Runner.h"
#include "pipeline/Snapshot.h"

#include <CLI/CLI.hpp>
#include <QApplication>
#include <QElapsedTimer>
#include <QMouseEvent>
#include <QOpenGLContext>
#include <QOpenGLFunctions>
#include <QWindow>
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <optional>
#include <string>
#include <sys/resource.h>
#include <vector>
#include <vtkRenderWindow.h>
#include <vtkRenderer.h>
#include <vtkRendererCollection.h>

using namespace contour;
using namespace contour::bench;

namespace {

// The GL renderer string of the 3D view's context (llvmpipe under Xvfb).
std::string rendererName(SceneView3D* view) {
    view->makeCurrent();
    const QOpenGLContext* context = QOpenGLContext::currentContext();
    std::string name = "unknown";
    if (context) {
        const auto* s = context->functions()->glGetString(GL_RENDERER);
        if (s)
            name = reinterpret_cast<const char*>(s);
    }
    view->doneCurrent();
    return name;
}

// Schedules a render of `view` and runs the event loop until it is drawn,
// as an interactive orbit does (the frame then also goes through Qt's
// composition of the window). False after 10 s without a frame.
bool renderNextFrame(SceneView3D* view) {
    const int before = view->renderCount();
    view->update();
    QElapsedTimer timer;
    timer.start();
    while (view->renderCount() == before && timer.elapsed() < 10000)
        QApplication::processEvents(QEventLoop::AllEvents, 5);
    return view->renderCount() > before;
}

// CPU seconds of the whole process so far (every thread, user + system).
double processCpuSeconds() {
    rusage usage{};
    getrusage(RUSAGE_SELF, &usage);
    const auto seconds = [](const timeval& t) {
        return static_cast<double>(t.tv_sec) + 1e-6 * static_cast<double>(t.tv_usec);
    };
    return seconds(usage.ru_utime) + seconds(usage.ru_stime);
}

// Sends a left-button mouse event at `position` (view coordinates) to the
// view, as a user's drag delivers it.
void sendMouse(SceneView3D* view, QEvent::Type type, QPointF position) {
    const Qt::MouseButtons buttons =
        type == QEvent::MouseButtonRelease ? Qt::NoButton : Qt::LeftButton;
    const Qt::MouseButton button = type == QEvent::MouseMove ? Qt::NoButton : Qt::LeftButton;
    QMouseEvent event(type, position, view->mapToGlobal(position), button, buttons, Qt::NoModifier);
    QApplication::sendEvent(view, &event);
}

// Opens `path`, switches to `method` and waits for the run to end.
bool openAndRun(MainWindow& window, const std::filesystem::path& path, const QString& method) {
    if (!window.openMesh(QString::fromStdString(path.string())) || !window.waitForIdle(3600000))
        return false;
    if (window.methodName() != method &&
        (!window.setMethod(method) || !window.waitForIdle(3600000)))
        return false;
    return window.lastError().isEmpty() && window.runner() && window.runner()->atEnd();
}

} // namespace

int main(int argc, char** argv) {
    CLI::App app{"The workbench: orbit frame rate of the 3D view with overlays on a "
                 "large mesh, and the time from a phase step to updated views."};
    std::string meshesDir = CONTOUR_SHARED_DIR "/meshes";
    std::string orbitMesh = "controlmesh";
    std::string orbitMethod = "consistent";
    std::string stepMesh = "bob_quad";
    std::string moveMesh = "spot_control_mesh";
    std::string moveMethod = "powell-sabin";
    int moves = 12;
    std::vector<std::string> parts{"orbit", "step", "move"};
    int frames = 120;
    int width = 1600;
    int height = 1000;
    std::string outPath;
    bool diagnose = false;
    app.add_option("--meshes-dir", meshesDir, "Folder of the meshes")->capture_default_str();
    app.add_option("--orbit-mesh", orbitMesh, "Model orbited (file name without extension)")
        ->capture_default_str();
    app.add_option("--orbit-method", orbitMethod, "Method run on the orbited model")
        ->capture_default_str();
    app.add_option("--frames", frames, "Frames of the orbit (one full turn)")
        ->check(CLI::Range(4, 100000))
        ->capture_default_str();
    app.add_option("--step-mesh", stepMesh, "Model stepped phase by phase (consistent method)")
        ->capture_default_str();
    app.add_option("--move-mesh", moveMesh, "Model whose analysis camera is moved")
        ->capture_default_str();
    app.add_option("--move-method", moveMethod, "Method run on the moved model")
        ->capture_default_str();
    app.add_option("--moves", moves, "Camera moves (one full turn)")
        ->check(CLI::Range(2, 1000))
        ->capture_default_str();
    app.add_option("--parts", parts, "Parts to run: orbit, step, move")
        ->delimiter(',')
        ->capture_default_str();
    app.add_option("--width", width, "Main window width")->capture_default_str();
    app.add_option("--height", height, "Main window height")->capture_default_str();
    app.add_option("--out", outPath, "Write the figures to this CSV file");
    app.add_flag("--diagnose", diagnose,
                 "Also time the drag with the overlays off, and frames in which VTK draws "
                 "nothing (what is left: the blit and Qt's composition of the window)");
    // CLI11 sees the arguments before Qt removes its own.
    CLI11_PARSE(app, argc, argv);

    setDefaultSurfaceFormat();
    QApplication qapp(argc, argv);
    std::ofstream csv;
    if (!outPath.empty()) {
        csv.open(outPath);
        if (!csv) {
            std::fprintf(stderr, "bench_workbench: cannot write %s\n", outPath.c_str());
            return 1;
        }
        csv << "part,mesh,method,phase,faces,frames,seconds,fps,phase seconds\n";
    }

    MainWindow window;
    window.setInteractive(false);
    window.resize(width, height);
    window.show();
    QElapsedTimer exposure;
    exposure.start();
    while ((!window.windowHandle() || !window.windowHandle()->isExposed()) &&
           exposure.elapsed() < 10000)
        QApplication::processEvents(QEventLoop::AllEvents, 10);
    std::printf("bench_workbench: load average %s, window %dx%d\n", loadAverage().c_str(), width,
                height);

    const auto wanted = [&](const char* part) {
        return std::find(parts.begin(), parts.end(), part) != parts.end();
    };
    // Part 1: orbit.
    if (!wanted("orbit")) {
    } else if (const auto path = findMeshFile(meshesDir, orbitMesh)) {
        const QElapsedTimer runTimer = [] {
            QElapsedTimer t;
            t.start();
            return t;
        }();
        if (!openAndRun(window, *path, QString::fromStdString(orbitMethod))) {
            std::printf("orbit: %s with %s did not run to the end: %s\n", orbitMesh.c_str(),
                        orbitMethod.c_str(), qPrintable(window.lastError()));
        } else {
            SceneView3D* view = window.sceneView();
            int overlaysOn = 0;
            for (int i = 0; i < kSceneOverlayCount; ++i) {
                const auto overlay = static_cast<SceneOverlay>(i);
                view->setOverlayEnabled(overlay, true);
                overlaysOn += view->isOverlayShown(overlay) ? 1 : 0;
            }
            const Snapshot s = window.currentSnapshot();
            const std::size_t faces = s.mesh ? s.mesh->faceCount() : 0;
            std::printf("orbit: %s, %s method (%.1f s to run), %zu faces, %d of %d overlays shown "
                        "and the view graph %s; view %dx%d px, renderer %s\n",
                        orbitMesh.c_str(), orbitMethod.c_str(),
                        static_cast<double>(runTimer.elapsed()) * 1e-3, faces, overlaysOn,
                        kSceneOverlayCount, view->hasViewGraph() ? "drawn" : "absent",
                        view->width(), view->height(), rendererName(view).c_str());
            // The decimated copy is built off the UI thread once the snapshot
            // has been shown: wait for it, so that every timed frame can use it.
            if (faces >= static_cast<std::size_t>(SceneView3D::kLevelOfDetailMinFaces)) {
                QElapsedTimer wait;
                wait.start();
                while (!view->levelOfDetailReady() && wait.elapsed() < 120000)
                    QApplication::processEvents(QEventLoop::AllEvents, 10);
                std::printf("orbit: decimated copy for motion %s: %lld faces, built in %.2f s "
                            "on its worker thread\n",
                            view->levelOfDetailReady() ? "ready" : "NOT READY after 120 s",
                            view->levelOfDetailFaceCount(), view->levelOfDetailSeconds());
            }
            enum class Mode { Full, Motion, MotionLod, Drag, DragNoOverlays, NothingDrawn };
            const auto modeName = [](Mode m) {
                switch (m) {
                case Mode::Full:
                    return "full drawing";
                case Mode::Motion:
                    return "motion drawing, full mesh";
                case Mode::MotionLod:
                    return "motion drawing + decimated copy";
                case Mode::Drag:
                    return "mouse drag through the interactor";
                case Mode::DragNoOverlays:
                    return "diagnosis: the same drag, overlays and view graph off";
                case Mode::NothingDrawn:
                    return "diagnosis: VTK draws nothing, the window is composed";
                }
                return "";
            };
            // One trackball degree is MotionFactor (10) * 20 / width pixels
            // of horizontal mouse travel (vtkInteractorStyleTrackballCamera).
            const double dragPixels =
                (360.0 / frames) * view->deviceSize().width() / 200.0 / view->devicePixelRatioF();
            std::vector<Mode> modes{Mode::Full, Mode::Motion, Mode::MotionLod, Mode::Drag};
            if (diagnose)
                modes.insert(modes.end(), {Mode::DragNoOverlays, Mode::NothingDrawn});
            for (const Mode mode : modes) {
                const bool overlays = mode != Mode::DragNoOverlays;
                for (int i = 0; i < kSceneOverlayCount; ++i)
                    view->setOverlayEnabled(static_cast<SceneOverlay>(i), overlays);
                view->setShowViewGraphNodes(overlays);
                view->setShowHiddenCurves(overlays);
                vtkRendererCollection* renderers = view->renderWindow()->GetRenderers();
                renderers->InitTraversal();
                while (vtkRenderer* r = renderers->GetNextItem())
                    r->SetDraw(mode != Mode::NothingDrawn);
                view->setLevelOfDetail(mode != Mode::Motion);
                view->setMotionDrawing(mode == Mode::Motion || mode == Mode::MotionLod);
                QPointF mouse(view->width() / 4.0, view->height() / 2.0);
                const bool drag = mode == Mode::Drag || mode == Mode::DragNoOverlays;
                if (drag) {
                    sendMouse(view, QEvent::MouseButtonPress, mouse);
                    mouse.rx() += dragPixels;
                    sendMouse(view, QEvent::MouseMove, mouse);
                }
                // The first frame builds the GL buffers: not timed.
                renderNextFrame(view);
                const bool lodShown = view->showsLevelOfDetail();
                const int rendersBefore = view->renderCount();
                const double cpuBefore = processCpuSeconds();
                QElapsedTimer timer;
                timer.start();
                for (int f = 0; f < frames; ++f) {
                    if (drag) {
                        mouse.rx() += dragPixels;
                        const int before = view->renderCount();
                        sendMouse(view, QEvent::MouseMove, mouse);
                        QElapsedTimer frame;
                        frame.start();
                        while (view->renderCount() == before && frame.elapsed() < 10000)
                            QApplication::processEvents(QEventLoop::AllEvents, 5);
                        if (view->renderCount() == before)
                            break;
                    } else {
                        view->orbit(360.0 / frames, 0.0);
                        if (!renderNextFrame(view))
                            break;
                    }
                }
                view->makeCurrent();
                QOpenGLContext::currentContext()->functions()->glFinish();
                view->doneCurrent();
                const double seconds = static_cast<double>(timer.nsecsElapsed()) * 1e-9;
                const double cpu = processCpuSeconds() - cpuBefore;
                const int drawn = view->renderCount() - rendersBefore;
                if (drag) {
                    sendMouse(view, QEvent::MouseButtonRelease, mouse);
                    renderNextFrame(view);
                }
                const double fps = drawn / seconds;
                const char* drawing = modeName(mode);
                std::printf("orbit (%s%s): %d frames requested, %d rendered, %.2f s: %.1f frames "
                            "per second (%.1f ms per frame, CPU %.1f ms per frame)\n",
                            drawing, lodShown ? ", copy shown" : "", frames, drawn, seconds, fps,
                            1e3 * seconds / std::max(drawn, 1), 1e3 * cpu / std::max(drawn, 1));
                if (csv)
                    csv << "orbit," << orbitMesh << ',' << orbitMethod << ',' << drawing << ','
                        << faces << ',' << drawn << ',' << seconds << ',' << fps << ",\n";
            }
            view->setLevelOfDetail(true);
            view->setMotionDrawing(false);
            vtkRendererCollection* renderers = view->renderWindow()->GetRenderers();
            renderers->InitTraversal();
            while (vtkRenderer* r = renderers->GetNextItem())
                r->DrawOn();
        }
    } else {
        std::printf("orbit: %s not found in %s: skipped\n", orbitMesh.c_str(), meshesDir.c_str());
    }

    // Part 2: step latency.
    if (!wanted("step")) {
    } else if (const auto path = findMeshFile(meshesDir, stepMesh)) {
        if (!openAndRun(window, *path, QStringLiteral("consistent"))) {
            std::printf("step: %s did not run to the end: %s\n", stepMesh.c_str(),
                        qPrintable(window.lastError()));
        } else {
            window.resetPhases();
            window.waitForIdle();
            const int phases = window.runner()->phaseCount();
            double total = 0.0;
            double totalPhase = 0.0;
            for (int p = 0; p < phases; ++p) {
                QElapsedTimer timer;
                timer.start();
                window.stepPhase();
                if (!window.waitForIdle(3600000))
                    break;
                window.sceneView()->repaint();
                window.imageView()->repaint();
                const double seconds = static_cast<double>(timer.nsecsElapsed()) * 1e-9;
                const Snapshot s = window.currentSnapshot();
                const std::size_t faces = s.mesh ? s.mesh->faceCount() : 0;
                total += seconds;
                totalPhase += s.phaseSeconds;
                std::printf("step: %-22s %7zu faces  %7.3f s to updated views (phase %.3f s, "
                            "window %.3f s)\n",
                            s.phaseName.c_str(), faces, seconds, s.phaseSeconds,
                            seconds - s.phaseSeconds);
                if (csv)
                    csv << "step," << stepMesh << ",consistent," << s.phaseName << ',' << faces
                        << ",," << seconds << ",," << s.phaseSeconds << '\n';
            }
            std::printf("step: %s, %d phases: %.3f s in all to updated views, of which %.3f s "
                        "in the phases\n",
                        stepMesh.c_str(), phases, total, totalPhase);
        }
    } else {
        std::printf("step: %s not found in %s: skipped\n", stepMesh.c_str(), meshesDir.c_str());
    }

    // Part 3: camera-move latency.
    if (!wanted("move")) {
    } else if (const auto path = findMeshFile(meshesDir, moveMesh)) {
        if (!openAndRun(window, *path, QString::fromStdString(moveMethod))) {
            std::printf("move: %s with %s did not run to the end: %s\n", moveMesh.c_str(),
                        moveMethod.c_str(), qPrintable(window.lastError()));
        } else {
            SceneView3D* view = window.sceneView();
            const int phases = window.runner()->phaseCount();
            double total = 0.0, worst = 0.0, totalPhases = 0.0;
            int done = 0;
            for (int m = 0; m < moves; ++m) {
                view->orbit(360.0 / moves, 0.0);
                renderNextFrame(view);
                QElapsedTimer timer;
                timer.start();
                window.setAnalysisCameraFromView();
                if (!window.waitForIdle(3600000) || window.completedPhases() != phases)
                    break;
                view->repaint();
                window.imageView()->repaint();
                const double seconds = static_cast<double>(timer.nsecsElapsed()) * 1e-9;
                double inPhases = 0.0;
                // Every phase re-ran; those taken from the preprocessing
                // cache cost only the lookup.
                for (const Snapshot& s : window.runner()->snapshots())
                    if (s.phaseIndex >= 0)
                        inPhases += s.phaseSeconds;
                total += seconds;
                worst = std::max(worst, seconds);
                totalPhases += inPhases;
                ++done;
                std::printf("move %2d: %.3f s to updated views (per-view phases %.3f s)\n", m + 1,
                            seconds, inPhases);
                if (csv)
                    csv << "move," << moveMesh << ',' << moveMethod << ",,"
                        << ",," << seconds << ",," << inPhases << '\n';
            }
            std::printf("move: %s with %s, %d of %d moves: mean %.3f s, largest %.3f s to updated "
                        "views (per-view phases %.3f s on average)\n",
                        moveMesh.c_str(), moveMethod.c_str(), done, moves,
                        done > 0 ? total / done : 0.0, worst, done > 0 ? totalPhases / done : 0.0);
        }
    } else {
        std::printf("move: %s not found in %s: skipped\n", moveMesh.c_str(), meshesDir.c_str());
    }
    return 0;
}
