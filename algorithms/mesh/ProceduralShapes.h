#pragma once
// Procedural test shapes, all with outward normals (counter-clockwise faces
// seen from outside) and closed unless stated. `resolution` is the number of
// segments around the main circle; other counts follow from it.
#include "mesh/PolygonMesh.h"

#include <string>
#include <vector>

namespace contour {

// Latitude-longitude sphere: quads, with triangle fans at the poles.
PolygonMesh makeSphere(double radius, int resolution, const Vec3& center = Vec3::Zero());
PolygonMesh makeEllipsoid(const Vec3& radii, int resolution);
// Torus around the z axis, major radius R, minor radius r, quads.
PolygonMesh makeTorus(double majorRadius, double minorRadius, int resolution);
// Torus whose minor radius varies with bumps: r (1 + amplitude sin(k u) sin(k v)).
PolygonMesh makeBumpyTorus(double majorRadius, double minorRadius, int resolution,
                           double amplitude = 0.15, int bumps = 5);
// z = (x^2 - y^2) / 2 over [-1, 1]^2, an open patch with one boundary loop.
PolygonMesh makeSaddlePatch(int resolution);
// Two unit spheres on the z axis, one at z = 0 and one at z = -3 (behind
// the first for a camera on the +z axis), as one mesh with two components.
PolygonMesh makeTwoSpheres(int resolution);

// The shapes by name: "sphere", "ellipsoid", "torus", "bumpy-torus",
// "saddle", "two-spheres". Throws std::invalid_argument on an unknown name.
std::vector<std::string> proceduralShapeNames();
PolygonMesh makeProceduralShape(const std::string& name, int resolution);
// The shape at the resolution whose triangulation has about `faces` triangles.
PolygonMesh makeProceduralShapeWithFaces(const std::string& name, long long faces);

} // namespace contour
