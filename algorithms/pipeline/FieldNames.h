#pragma once
// Names of the fields that phases publish in a Snapshot. Views and exporters
// look fields up by these names, so a new method only has to publish them.
namespace contour::fields {

// Face, int: +1 front-facing, -1 back-facing, 0 edge-on (exact predicate).
inline constexpr const char* kFacing = "facing";
// Vertex, Vec3: unit vertex normals used by the facing function.
inline constexpr const char* kVertexNormal = "vertex_normal";
// Vertex, double: g = (c - p) · n, > 0 front-facing (Facing.h).
inline constexpr const char* kG = "g";
// Edge, int: 0 not a contour, 1 convex contour edge, 2 concave contour edge.
inline constexpr const char* kContourEdge = "contour_edge";
// Edge, int: 1 on a boundary edge.
inline constexpr const char* kBoundaryEdge = "boundary_edge";
// Face, int: 1 if the face carries an interpolated contour segment.
inline constexpr const char* kContourFace = "contour_face";
// Edge, double: parameter t of the zero crossing of g along the edge's
// stored half-edge, or NaN when g does not change sign on it.
inline constexpr const char* kZeroCrossing = "zero_crossing";

// Smooth surfaces (contours/SurfacePhase.h, surface/SurfaceFields.h for the
// sign conventions). Vertex, int: the domain face of the vertex's preimage.
inline constexpr const char* kPreimageFace = "preimage_face";
// Vertex, Vec3: (u, v, 0), the preimage's coordinates in that face.
inline constexpr const char* kPreimageUv = "preimage_uv";
// Face, int: the domain face of the smooth surface a triangle lies in.
inline constexpr const char* kDomainFace = "domain_face";
// Vertex, double: normal curvature along the view vector projected onto the
// tangent plane; II = f_ij · n with outward n, so -1/R on a sphere and < 0 at
// an ordinary exterior contour; NaN where the view is along the normal.
inline constexpr const char* kRadialCurvature = "radial_curvature";
// Vertex, double: Gaussian (+1/R^2 on a sphere) and mean (-1/R) curvature.
inline constexpr const char* kGaussianCurvature = "gaussian_curvature";
inline constexpr const char* kMeanCurvature = "mean_curvature";

// Consistent contours (Bénard 2014, contours/consistent/). Face, int: the
// Vertex-Based Orientation (Definition 1): +1 F, -1 B, 0 undefined.
inline constexpr const char* kVbo = "vbo";
// Face, int: 1 if the face is contour-consistent (Definition 2), else 0.
inline constexpr const char* kConsistent = "consistent";
// Face, int: index of the phase that created or last changed the face.
inline constexpr const char* kChangedByPhase = "changed_by_phase";
// Vertex, int: index of the phase that created or last changed the vertex.
inline constexpr const char* kVertexChangedByPhase = "vertex_changed_by_phase";
// Vertex, int: R_S label, +1 F, -1 B, 0 C (a contour vertex).
inline constexpr const char* kLabel = "label";
// Vertex, int: 0 initial, 1 inserted, 2 shifted, 3 wiggled.
inline constexpr const char* kProvenance = "provenance";
// Vertex, int: 1 at a cusp vertex (g = 0 and radial curvature 0, §6.2 d).
inline constexpr const char* kCusp = "cusp";
// Vertex, int: 1 at a cusp vertex where the surface is singular (a principal
// curvature radius below 1e-6 of the scene, or no normal): no cusp of a
// smooth surface, so its curtain fold is stepped by the one-ring test.
inline constexpr const char* kSingularCusp = "singular_cusp";
// Vertex, double: offset along n(u) of the final normal wiggle (§6.4);
// position = f(u) + offset * n(u).
inline constexpr const char* kNormalOffset = "normal_offset";
// Face, int: 1 radial triangle (Definition 5), else 0.
inline constexpr const char* kRadial = "radial";
// Face, int: 1 standard radial triangle (§6.3), else 0.
inline constexpr const char* kStandardRadial = "standard_radial";
// Edge, int: 1 on a radial edge p-r (Definition 5).
inline constexpr const char* kRadialEdge = "radial_edge";
// Edge, int: 1 on an FB edge holding a cusp preimage, to be inserted last.
inline constexpr const char* kCuspEdge = "cusp_edge";
// Face, int: 1 where the face is folded in parameter space (its preimages
// wind against the domain's orientation).
inline constexpr const char* kFolded = "folded";

// Powell-Sabin method (contours/powell_sabin, Capouellez et al. 2023 §5).
// Vertex, int: 1 at a cone of the flat metric (§5.1).
inline constexpr const char* kCone = "cone";
// Vertex, int: the cone cluster the vertex belongs to (-1 without cones).
inline constexpr const char* kConeCluster = "cone_cluster";
// Vertex, double: the conformal log scale factor u (l = e^((ui+uj)/2) l0).
inline constexpr const char* kLogScale = "log_scale";
// Vertex, double: 2 pi minus the angle sum in the flat metric (0 except at cones).
inline constexpr const char* kAngleDefectFlat = "flat_angle_defect";
// Face, Vec3 (u, v, 0): the uv of the face's corner 0, 1 and 2 in the layout.
inline constexpr const char* kCornerUv0 = "corner_uv_0";
inline constexpr const char* kCornerUv1 = "corner_uv_1";
inline constexpr const char* kCornerUv2 = "corner_uv_2";
// Edge, int: 1 on an edge of the cut to a disk.
inline constexpr const char* kCutEdge = "cut_edge";
// Face, double: log(uv area / 3D area) minus its value for the whole
// layout: the layout's area distortion (0 where a face keeps the mean scale).
inline constexpr const char* kLogAreaRatio = "log_area_ratio";
// Face, int (spline tessellation): the quadratic patch 12 f + l the triangle lies in.
inline constexpr const char* kPatch = "patch";
// Face, int (spline tessellation): the macro-patch (layout face) it lies in.
inline constexpr const char* kMacroPatch = "macro_patch";
// Edge, int (spline tessellation): 1 patch boundary inside a macro-patch,
// 2 macro-patch boundary (a layout edge), 3 a cut edge.
inline constexpr const char* kPatchEdge = "patch_edge";
// Vertex, double (spline tessellation): distance from the spline to the
// input mesh's triangle at the same parameter.
inline constexpr const char* kFitOffset = "fit_offset";

} // namespace contour::fields
