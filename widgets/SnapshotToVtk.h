#pragma once
// Conversion of a Snapshot's parts to VTK data for the 3D view. Pure data
// conversion: no rendering and no algorithm runs here.
#include "ViewGraphStyle.h"
#include "camera/Camera.h"
#include "pipeline/Snapshot.h"
#include "reference/DenseGroundTruth.h"

#include <string>
#include <vector>
#include <vtkSmartPointer.h>

class vtkDoubleArray;
class vtkIntArray;
class vtkPolyData;

namespace contour {

// Name of the cell array holding fields::kFacing on the mesh polydata, and of
// the cell array holding the CurveType of each curve.
inline constexpr const char* kVtkFacingArray = "facing";
inline constexpr const char* kVtkCurveTypeArray = "curve_type";

// The triangle mesh as polydata (points and triangles, no attributes).
vtkSmartPointer<vtkPolyData> meshToPolyData(const TriangleMesh& mesh);

// The face field fields::kFacing of `snapshot` as a cell array named
// kVtkFacingArray (+1 front, -1 back, 0 edge-on), or null when the snapshot
// has no facing field yet or it does not match the mesh.
vtkSmartPointer<vtkIntArray> facingToCellArray(const Snapshot& snapshot);

// The integer face fields besides fields::kFacing that a view can colour
// faces front/back by (+1 F, -1 B, 0 undefined): the vertex-based orientation
// fields::kVbo (Bénard 2014, Definition 1), when the snapshot has it on every
// face.
std::vector<std::string> faceLabelFieldNames(const Snapshot& snapshot);

// The integer face field `name` as a cell array named `name`, or null when
// the snapshot has no such field on the mesh's faces.
vtkSmartPointer<vtkIntArray> faceLabelsToCellArray(const Snapshot& snapshot,
                                                   const std::string& name);

// The double fields of `snapshot` on the mesh's vertices or faces whose size
// matches the mesh: the ones a view can colour by. Known fields first (g,
// radial, Gaussian, mean curvature), then the others by name.
std::vector<std::string> scalarFieldNames(const Snapshot& snapshot);

// The scalar field `name` (one of scalarFieldNames) as an array named `name`
// holding one value per vertex or per face (see `location`), or null.
vtkSmartPointer<vtkDoubleArray> scalarFieldToArray(const Snapshot& snapshot,
                                                   const std::string& name,
                                                   FieldLocation* location = nullptr);

// The exact unit normals of a tessellated smooth surface (fields::kVertexNormal
// on a mesh whose vertices have preimages, fields::kPreimageFace) as a point
// array for smooth shading, or null: a plain triangle mesh is drawn with its
// flat faces.
vtkSmartPointer<vtkDoubleArray> smoothSurfaceNormals(const Snapshot& snapshot);

// The curves as polylines (a closed curve repeats its first point) with the
// cell array kVtkCurveTypeArray holding static_cast<int>(CurveType).
vtkSmartPointer<vtkPolyData> curvesToPolyData(const std::vector<Polyline>& curves);

// The control cage as a wireframe: every edge of the polygons once, as a
// line cell between two of the cage's own points.
vtkSmartPointer<vtkPolyData> cageToPolyData(const PolygonMesh& cage);

// The view graph (Snapshot::viewGraph, pipeline/ViewGraph.h). The chains in
// `state` (ViewGraphStyle.h: visible, hidden, simplified away) as one polyline
// each through its 3D points (a closed chain already repeats its first
// point), with the cell arrays kVtkChainIndexArray (the chain's index in the
// graph) and kVtkChainQiArray (its QI, -1 unknown). Chains with fewer than two
// points are left out.
inline constexpr const char* kVtkChainIndexArray = "chain";
inline constexpr const char* kVtkChainQiArray = "qi";
vtkSmartPointer<vtkPolyData> viewChainsToPolyData(const ViewGraph& graph, ChainState state);

// One vertex cell per node at its 3D position, in node order, with the point
// array kVtkNodeTypeArray (static_cast<int>(ViewNodeType)): the nodes whose
// chains are all hidden (ViewNodeClass::Hidden) when `hidden`, the others
// otherwise.
inline constexpr const char* kVtkNodeTypeArray = "node_type";
vtkSmartPointer<vtkPolyData> viewNodesToPolyData(const ViewGraph& graph, bool hidden);

// The dense ground truth of the smooth contour (reference/DenseGroundTruth.h):
// its loops as polylines through their points (a closed loop repeats its
// first point), loops of fewer than two points left out; its cusps as one
// vertex cell each.
vtkSmartPointer<vtkPolyData> groundTruthLoopsToPolyData(const GroundTruth& truth);
vtkSmartPointer<vtkPolyData> groundTruthCuspsToPolyData(const GroundTruth& truth);

// Overlays of the consistent method (Bénard 2014, contours/consistent/). Each
// is null when the snapshot lacks the fields it needs or their sizes do not
// match the mesh, so a view shows an overlay only where it means something.

// The name of the cell array of radialFacesToPolyData: 1 on a standard radial
// triangle, 0 on another radial one.
inline constexpr const char* kVtkStandardRadialArray = "standard_radial";

// One closed polyline (4 point ids, the first repeated) per face whose
// fields::kConsistent is 0, so the line count is the inconsistent face count.
vtkSmartPointer<vtkPolyData> inconsistentFaceOutlines(const Snapshot& snapshot);

// The triangles with fields::kRadial or fields::kStandardRadial set, with the
// cell array kVtkStandardRadialArray (all 0 without a standard_radial field).
vtkSmartPointer<vtkPolyData> radialFacesToPolyData(const Snapshot& snapshot);

// One vertex cell per mesh vertex whose integer vertex field `field` equals
// `value`: fields::kLabel 0 gives the contour (C) vertices, fields::kCusp 1
// the cusps.
vtkSmartPointer<vtkPolyData> markedVerticesToPolyData(const Snapshot& snapshot,
                                                      const std::string& field, int value);

// One line per mesh edge whose integer edge field `field` is non-zero (e.g.
// fields::kRadialEdge).
vtkSmartPointer<vtkPolyData> markedEdgesToPolyData(const Snapshot& snapshot,
                                                   const std::string& field);
// The edges whose label in the int edge field `field` is not 0, as lines
// with that label as cell scalars (null when the snapshot lacks the field).
vtkSmartPointer<vtkPolyData> labelledEdgesToPolyData(const Snapshot& snapshot,
                                                     const std::string& field);

// The camera's viewing frustum as lines: perspective, a pyramid from the eye
// to the image rectangle at `depth`; orthographic, a box from the eye plane
// to `depth`.
vtkSmartPointer<vtkPolyData> frustumToPolyData(const Camera& camera, double depth);

} // namespace contour
