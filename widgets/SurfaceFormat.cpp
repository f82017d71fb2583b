#include "SurfaceFormat.h"

#include <QCoreApplication>
#include <QSurfaceFormat>

namespace contour {

void setDefaultSurfaceFormat() {
    QSurfaceFormat format;
    format.setRenderableType(QSurfaceFormat::OpenGL);
    format.setVersion(3, 2);
    format.setProfile(QSurfaceFormat::CoreProfile);
    format.setSwapBehavior(QSurfaceFormat::DoubleBuffer);
    format.setRedBufferSize(8);
    format.setGreenBufferSize(8);
    format.setBlueBufferSize(8);
    format.setAlphaBufferSize(8);
    format.setDepthBufferSize(24);
    format.setStencilBufferSize(8);
    // VTK renders into its own framebuffer and blits the result; no need for
    // multisampling in Qt's.
    format.setSamples(0);
    QSurfaceFormat::setDefaultFormat(format);
    // Lets a view keep its GL resources when it moves to another top-level
    // window (e.g. a floating dock).
    QCoreApplication::setAttribute(Qt::AA_ShareOpenGLContexts);
}

} // namespace contour
