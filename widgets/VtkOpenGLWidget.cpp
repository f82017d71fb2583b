#include "VtkOpenGLWidget.h"

#include <QCursor>
#include <QKeyEvent>
#include <QMouseEvent>
#include <QOpenGLContext>
#include <QOpenGLExtraFunctions>
#include <QWheelEvent>
#include <algorithm>
#include <cmath>
#include <vtkCallbackCommand.h>
#include <vtkCommand.h>
#include <vtkInteractorStyleTrackballCamera.h>
#include <vtkOpenGLState.h>

namespace contour {

namespace {

// VTK key symbols (X11 names) for the keys that have no printable text.
const char* keySymbol(int key) {
    switch (key) {
    case Qt::Key_Left:
        return "Left";
    case Qt::Key_Right:
        return "Right";
    case Qt::Key_Up:
        return "Up";
    case Qt::Key_Down:
        return "Down";
    case Qt::Key_Shift:
        return "Shift_L";
    case Qt::Key_Control:
        return "Control_L";
    case Qt::Key_Alt:
        return "Alt_L";
    case Qt::Key_Escape:
        return "Escape";
    case Qt::Key_Return:
        return "Return";
    case Qt::Key_Space:
        return "space";
    case Qt::Key_Plus:
        return "plus";
    case Qt::Key_Minus:
        return "minus";
    default:
        return nullptr;
    }
}

// The interactor style's character commands that are safe here: reset the
// camera (r), wireframe (w), surface (s). The others quit the application
// (e, q), switch to stereo (3) or pick and fly (p, f), which need a GL
// context outside paintGL().
bool isForwardedCharacter(char c) {
    return c == 'r' || c == 'R' || c == 'w' || c == 'W' || c == 's' || c == 'S';
}

} // namespace

VtkOpenGLWidget::VtkOpenGLWidget(QWidget* parent) : QOpenGLWidget(parent) {
    setFocusPolicy(Qt::StrongFocus);
    setMouseTracking(true);
    setUpdateBehavior(QOpenGLWidget::NoPartialUpdate);

    renderWindow_->SetReadyForRendering(false);
    renderWindow_->SetOwnContext(false);
    // Wide lines through VTK's geometry-shader path: core profiles only
    // guarantee a hardware line width of 1.
    renderWindow_->SetForceMaximumHardwareLineWidth(1);
    renderWindow_->SetFrameBlitModeToNoBlit();
    renderWindow_->SetMultiSamples(0);
    renderWindow_->AddRenderer(renderer_);

    interactor_->SetRenderWindow(renderWindow_);
    // Interactor renders only schedule a paint (see onInteractorRender).
    interactor_->EnableRenderOff();
    vtkNew<vtkInteractorStyleTrackballCamera> style;
    interactor_->SetInteractorStyle(style);
    interactor_->Initialize();
    renderObserver_ = interactor_->AddObserver(vtkCommand::RenderEvent, this,
                                               &VtkOpenGLWidget::onInteractorRender);
}

VtkOpenGLWidget::~VtkOpenGLWidget() {
    interactor_->RemoveObserver(renderObserver_);
    // QOpenGLWidget's destructor destroys the context after this one has run.
    if (context())
        disconnect(context(), nullptr, this, nullptr);
    onContextAboutToBeDestroyed();
    interactor_->SetInteractorStyle(nullptr);
    interactor_->SetRenderWindow(nullptr);
    renderWindow_->RemoveRenderer(renderer_);
}

QSize VtkOpenGLWidget::deviceSize() const {
    const int* size = renderWindow_->GetSize();
    return {size[0], size[1]};
}

QImage VtkOpenGLWidget::grabImage() {
    return grabFramebuffer();
}

void VtkOpenGLWidget::initializeGL() {
    // A QOpenGLWidget gets a new context when it moves to another top-level
    // window; VTK's resources must go with the old one.
    connect(context(), &QOpenGLContext::aboutToBeDestroyed, this,
            &VtkOpenGLWidget::onContextAboutToBeDestroyed, Qt::UniqueConnection);
    renderWindow_->SetReadyForRendering(false);
    renderWindow_->SetOwnContext(false);
    renderWindow_->SetIsCurrent(true);
    renderWindow_->OpenGLInitContext();
    renderWindow_->SetIsCurrent(false);
    glReady_ = true;
}

void VtkOpenGLWidget::resizeGL(int width, int height) {
    const double ratio = devicePixelRatioF();
    const int w = std::max(1, static_cast<int>(std::lround(width * ratio)));
    const int h = std::max(1, static_cast<int>(std::lround(height * ratio)));
    // UpdateSize keeps the interactor's size (used to flip y) in step and
    // resizes the render window.
    interactor_->UpdateSize(w, h);
    renderWindow_->SetSize(w, h);
}

void VtkOpenGLWidget::paintGL() {
    if (!glReady_)
        return;
    beforeRender();

    vtkOpenGLState* state = renderWindow_->GetState();
    // Qt changed GL state (its framebuffer, the viewport) behind VTK's cache.
    state->Reset();
    state->Push();
    // Qt leaves GL_LESS; VTK expects GL_LEQUAL.
    state->vtkglDepthFunc(GL_LEQUAL);

    renderWindow_->SetReadyForRendering(true);
    renderWindow_->SetIsCurrent(true);
    renderWindow_->Render();
    blitToWidgetFramebuffer();
    renderWindow_->SetIsCurrent(false);
    renderWindow_->SetReadyForRendering(false);

    state->Pop();
    ++renderCount_;
    emit rendered();
}

void VtkOpenGLWidget::blitToWidgetFramebuffer() {
    QOpenGLExtraFunctions* f = context()->extraFunctions();
    const int* size = renderWindow_->GetSize();
    f->glBindFramebuffer(GL_DRAW_FRAMEBUFFER, defaultFramebufferObject());
    const GLenum drawBuffer = GL_COLOR_ATTACHMENT0;
    f->glDrawBuffers(1, &drawBuffer);
    const bool scissor = f->glIsEnabled(GL_SCISSOR_TEST) == GL_TRUE;
    if (scissor) {
        renderWindow_->GetState()->vtkglDisable(GL_SCISSOR_TEST);
        f->glDisable(GL_SCISSOR_TEST);
    }
    renderWindow_->BlitDisplayFramebuffer(0, 0, 0, size[0], size[1], 0, 0, size[0], size[1],
                                          GL_COLOR_BUFFER_BIT, GL_NEAREST);
    // Make the result opaque: Mesa and some compositors blend with what is
    // behind the widget when alpha < 1.
    GLboolean mask[4];
    f->glGetBooleanv(GL_COLOR_WRITEMASK, mask);
    GLfloat clear[4];
    f->glGetFloatv(GL_COLOR_CLEAR_VALUE, clear);
    GLint viewport[4];
    f->glGetIntegerv(GL_VIEWPORT, viewport);
    f->glColorMask(GL_FALSE, GL_FALSE, GL_FALSE, GL_TRUE);
    f->glClearColor(0.0f, 0.0f, 0.0f, 1.0f);
    f->glViewport(0, 0, size[0], size[1]);
    f->glClear(GL_COLOR_BUFFER_BIT);
    f->glColorMask(mask[0], mask[1], mask[2], mask[3]);
    f->glClearColor(clear[0], clear[1], clear[2], clear[3]);
    f->glViewport(viewport[0], viewport[1], viewport[2], viewport[3]);
    if (scissor) {
        renderWindow_->GetState()->vtkglEnable(GL_SCISSOR_TEST);
        f->glEnable(GL_SCISSOR_TEST);
    }
}

void VtkOpenGLWidget::onContextAboutToBeDestroyed() {
    if (!glReady_)
        return;
    makeCurrent();
    releaseGraphicsResources();
    doneCurrent();
}

void VtkOpenGLWidget::releaseGraphicsResources() {
    renderWindow_->SetIsCurrent(true);
    renderWindow_->Finalize();
    renderWindow_->SetIsCurrent(false);
    renderWindow_->SetReadyForRendering(false);
    glReady_ = false;
}

void VtkOpenGLWidget::onInteractorRender(vtkObject*, unsigned long, void*) {
    update();
}

void VtkOpenGLWidget::setEventPosition(const QPointF& position, Qt::KeyboardModifiers modifiers,
                                       bool repeat) {
    const double ratio = devicePixelRatioF();
    interactor_->SetEventInformationFlipY(static_cast<int>(std::lround(position.x() * ratio)),
                                          static_cast<int>(std::lround(position.y() * ratio)),
                                          (modifiers & Qt::ControlModifier) ? 1 : 0,
                                          (modifiers & Qt::ShiftModifier) ? 1 : 0, 0,
                                          repeat ? 1 : 0);
    interactor_->SetAltKey((modifiers & Qt::AltModifier) ? 1 : 0);
}

void VtkOpenGLWidget::mousePressEvent(QMouseEvent* event) {
    if (!forwardButton(event, true))
        QOpenGLWidget::mousePressEvent(event);
}

void VtkOpenGLWidget::mouseReleaseEvent(QMouseEvent* event) {
    if (!forwardButton(event, false))
        QOpenGLWidget::mouseReleaseEvent(event);
}

bool VtkOpenGLWidget::forwardButton(QMouseEvent* event, bool press) {
    setEventPosition(event->position(), event->modifiers());
    // The interactor's own press/release methods, not InvokeEvent: they also
    // keep VTK's multi-touch gesture bookkeeping.
    using InteractorEvent = void (vtkRenderWindowInteractor::*)();
    InteractorEvent forward = nullptr;
    switch (event->button()) {
    case Qt::LeftButton:
        forward = press ? &vtkRenderWindowInteractor::LeftButtonPressEvent
                        : &vtkRenderWindowInteractor::LeftButtonReleaseEvent;
        break;
    case Qt::MiddleButton:
        forward = press ? &vtkRenderWindowInteractor::MiddleButtonPressEvent
                        : &vtkRenderWindowInteractor::MiddleButtonReleaseEvent;
        break;
    case Qt::RightButton:
        forward = press ? &vtkRenderWindowInteractor::RightButtonPressEvent
                        : &vtkRenderWindowInteractor::RightButtonReleaseEvent;
        break;
    default:
        return false;
    }
    (interactor_.GetPointer()->*forward)();
    event->accept();
    return true;
}

void VtkOpenGLWidget::mouseDoubleClickEvent(QMouseEvent* event) {
    // VTK's repeat count marks a double click; the press is delivered too.
    setEventPosition(event->position(), event->modifiers(), true);
    if (event->button() == Qt::LeftButton)
        interactor_->LeftButtonPressEvent();
    event->accept();
}

void VtkOpenGLWidget::mouseMoveEvent(QMouseEvent* event) {
    setEventPosition(event->position(), event->modifiers());
    interactor_->MouseMoveEvent();
    event->accept();
}

void VtkOpenGLWidget::wheelEvent(QWheelEvent* event) {
    setEventPosition(event->position(), event->modifiers());
    const int delta = event->angleDelta().y();
    if (delta > 0)
        interactor_->MouseWheelForwardEvent();
    else if (delta < 0)
        interactor_->MouseWheelBackwardEvent();
    event->accept();
}

void VtkOpenGLWidget::keyPressEvent(QKeyEvent* event) {
    const QByteArray text = event->text().toLatin1();
    const char c = text.isEmpty() ? '\0' : text.at(0);
    const char* symbol = keySymbol(event->key());
    const QByteArray textSymbol = text.left(1);
    if (!symbol && !textSymbol.isEmpty())
        symbol = textSymbol.constData();
    const QPointF position = mapFromGlobal(QCursor::pos());
    setEventPosition(position, event->modifiers(), event->isAutoRepeat());
    interactor_->SetKeyEventInformation((event->modifiers() & Qt::ControlModifier) ? 1 : 0,
                                        (event->modifiers() & Qt::ShiftModifier) ? 1 : 0, c,
                                        event->isAutoRepeat() ? 1 : 0, symbol);
    interactor_->KeyPressEvent();
    if (isForwardedCharacter(c))
        interactor_->CharEvent();
    // Leave shortcuts and dialog keys to Qt.
    QOpenGLWidget::keyPressEvent(event);
}

void VtkOpenGLWidget::keyReleaseEvent(QKeyEvent* event) {
    const QByteArray text = event->text().toLatin1();
    const char c = text.isEmpty() ? '\0' : text.at(0);
    const char* symbol = keySymbol(event->key());
    const QByteArray textSymbol = text.left(1);
    if (!symbol && !textSymbol.isEmpty())
        symbol = textSymbol.constData();
    interactor_->SetKeyEventInformation((event->modifiers() & Qt::ControlModifier) ? 1 : 0,
                                        (event->modifiers() & Qt::ShiftModifier) ? 1 : 0, c,
                                        event->isAutoRepeat() ? 1 : 0, symbol);
    interactor_->KeyReleaseEvent();
    QOpenGLWidget::keyReleaseEvent(event);
}

void VtkOpenGLWidget::enterEvent(QEnterEvent* event) {
    setEventPosition(event->position(), event->modifiers());
    interactor_->EnterEvent();
    QOpenGLWidget::enterEvent(event);
}

void VtkOpenGLWidget::leaveEvent(QEvent* event) {
    interactor_->LeaveEvent();
    QOpenGLWidget::leaveEvent(event);
}

} // namespace contour
