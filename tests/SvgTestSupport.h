#pragma once
// SVG documents read back for the exporters' tests: every element with its
// attributes and enclosing groups, and hand-made view-graph chains.
#include "camera/Camera.h"
#include "pipeline/ViewGraph.h"

#include <QStringList>
#include <QXmlStreamReader>
#include <map>
#include <vector>

namespace contour::testing {

struct SvgElement {
    QString name;
    QStringList groups; // ids of the enclosing <g>, outermost first
    std::map<QString, QString> attributes;
    QString attribute(const QString& key) const {
        const auto it = attributes.find(key);
        return it == attributes.end() ? QString() : it->second;
    }
};

struct ParsedSvg {
    QString error;
    std::vector<SvgElement> elements; // every element, <g> included
    std::vector<const SvgElement*> in(const QString& group, const QString& name) const {
        std::vector<const SvgElement*> found;
        for (const SvgElement& e : elements)
            if (e.name == name && e.groups.contains(group))
                found.push_back(&e);
        return found;
    }
    const SvgElement* group(const QString& id) const {
        for (const SvgElement& e : elements)
            if (e.name == "g" && e.attribute("id") == id)
                return &e;
        return nullptr;
    }
};

inline ParsedSvg parse(const std::string& text) {
    ParsedSvg svg;
    QXmlStreamReader xml(QByteArray::fromStdString(text));
    QStringList stack;
    while (!xml.atEnd()) {
        xml.readNext();
        if (xml.isStartElement()) {
            SvgElement e;
            e.name = xml.name().toString();
            e.groups = stack;
            for (const QXmlStreamAttribute& a : xml.attributes())
                e.attributes[a.name().toString()] = a.value().toString();
            if (e.name == "g")
                stack << e.attribute("id");
            svg.elements.push_back(std::move(e));
        } else if (xml.isEndElement() && xml.name() == QLatin1String("g")) {
            stack.removeLast();
        }
    }
    if (xml.hasError())
        svg.error = xml.errorString();
    return svg;
}

// "x,y x,y ..." as points.
inline std::vector<Vec2> pointList(const QString& text) {
    std::vector<Vec2> out;
    for (const QString& pair : text.split(' ', Qt::SkipEmptyParts)) {
        const QStringList xy = pair.split(',');
        out.emplace_back(xy.value(0).toDouble(), xy.value(1).toDouble());
    }
    return out;
}

inline std::vector<Vec2> points(const SvgElement& polyline) {
    return pointList(polyline.attribute("points"));
}

inline Camera frontCamera() {
    Camera c;
    c.eye = Vec3(0, 0, 5);
    c.target = Vec3::Zero();
    c.up = Vec3(0, 1, 0);
    c.viewport = {400, 300};
    return c;
}

inline ViewChain chain(CurveType type, Index curve, std::vector<Vec3> pts, const Camera& camera,
                       int qi, VisibilityRule rule) {
    ViewChain c;
    c.type = type;
    c.curve = curve;
    c.points = std::move(pts);
    for (const Vec3& p : c.points) {
        const ProjectedPoint q = camera.project(p);
        c.image.push_back(q.pixel);
        c.depth.push_back(q.depth);
    }
    for (size_t i = 1; i < c.image.size(); ++i)
        c.lengthPixels += (c.image[i] - c.image[i - 1]).norm();
    c.segmentElement.assign(c.segmentCount(), 0);
    c.qi = qi;
    c.decidedBy = rule;
    return c;
}

} // namespace contour::testing
