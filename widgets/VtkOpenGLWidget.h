#pragma once
// The bridge between a QOpenGLWidget and VTK (docs/dev/debian-traps.md): Debian's VTK
// Qt module is built for Qt 5, so this widget drives a
// vtkGenericOpenGLRenderWindow in its own GL context and forwards Qt's mouse
// and key events to a vtkGenericRenderWindowInteractor (trackball camera).
//
// Every VTK render happens in paintGL(): interactor renders only schedule a
// repaint, so VTK never touches GL outside a current Qt context. VTK renders
// into its own framebuffer; paintGL() blits the result into the widget's.
#include <QImage>
#include <QOpenGLWidget>
#include <vtkGenericOpenGLRenderWindow.h>
#include <vtkGenericRenderWindowInteractor.h>
#include <vtkNew.h>
#include <vtkRenderer.h>

class vtkObject;

namespace contour {

class VtkOpenGLWidget : public QOpenGLWidget {
    Q_OBJECT

public:
    explicit VtkOpenGLWidget(QWidget* parent = nullptr);
    ~VtkOpenGLWidget() override;

    vtkGenericOpenGLRenderWindow* renderWindow() const { return renderWindow_; }
    vtkRenderer* renderer() const { return renderer_; }
    vtkGenericRenderWindowInteractor* interactor() const { return interactor_; }

    // Renders now and returns the widget's framebuffer (QOpenGLWidget::
    // grabFramebuffer). Works under Xvfb + llvmpipe once the widget is shown.
    QImage grabImage();
    // Schedules a render (the next paint).
    void requestRender() { update(); }
    // Number of completed VTK renders, for tests.
    int renderCount() const { return renderCount_; }
    // Size of the VTK render window in device pixels.
    QSize deviceSize() const;

    QSize sizeHint() const override { return {640, 480}; }
    QSize minimumSizeHint() const override { return {160, 120}; }

signals:
    void rendered();

protected:
    // Hook run in paintGL() just before VTK renders (GL context current).
    virtual void beforeRender() {}

    void initializeGL() override;
    void resizeGL(int width, int height) override;
    void paintGL() override;

    void mousePressEvent(QMouseEvent* event) override;
    void mouseReleaseEvent(QMouseEvent* event) override;
    void mouseMoveEvent(QMouseEvent* event) override;
    void mouseDoubleClickEvent(QMouseEvent* event) override;
    void wheelEvent(QWheelEvent* event) override;
    void keyPressEvent(QKeyEvent* event) override;
    void keyReleaseEvent(QKeyEvent* event) override;
    void enterEvent(QEnterEvent* event) override;
    void leaveEvent(QEvent* event) override;

private slots:
    void onContextAboutToBeDestroyed();

private:
    void onInteractorRender(vtkObject* caller, unsigned long eventId, void* callData);
    void releaseGraphicsResources();
    void setEventPosition(const QPointF& position, Qt::KeyboardModifiers modifiers,
                          bool repeat = false);
    // A press or release of the left, middle or right button, sent to the
    // interactor (false: another button, left to Qt).
    bool forwardButton(QMouseEvent* event, bool press);
    void blitToWidgetFramebuffer();

    vtkNew<vtkGenericOpenGLRenderWindow> renderWindow_;
    vtkNew<vtkRenderer> renderer_;
    vtkNew<vtkGenericRenderWindowInteractor> interactor_;
    unsigned long renderObserver_ = 0;
    bool glReady_ = false;
    int renderCount_ = 0;
};

} // namespace contour
