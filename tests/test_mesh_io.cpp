// Mesh readers, writers and validation: every malformed input in
// tests/data/bad is rejected with a message naming the file, the place and
// the problem; the same mesh reads identically from every format; writers
// round-trip exactly, PLY labels included.
#include "mesh/MeshError.h"
#include "mesh/MeshValidation.h"
#include "mesh/PolygonTriangulation.h"
#include "mesh/io/MeshReader.h"
#include "mesh/io/MeshWriter.h"

#include <QDir>
#include <QFile>
#include <QFileInfo>
#include <QTemporaryDir>
#include <QtTest>
#include <cmath>
#include <functional>
#include <numbers>
#include <random>
#include <sstream>

using namespace contour;

namespace {

QString dataDir() {
    return QStringLiteral(CONTOUR_SOURCE_DIR "/tests/data");
}
std::string badFile(const QString& name) {
    return (dataDir() + "/bad/" + name).toStdString();
}
std::string goodFile(const QString& name) {
    return (dataDir() + "/good/" + name).toStdString();
}

// The pyramid of tests/data/good (see make_mesh_io_files.py).
PolygonMesh pyramid() {
    PolygonMesh mesh;
    mesh.positions = {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(1, 1, 0), Vec3(0, 1, 0),
                      Vec3(0.5, 0.5, 1)};
    mesh.addFace({0, 3, 2, 1});
    mesh.addFace({0, 1, 4});
    mesh.addFace({1, 2, 4});
    mesh.addFace({2, 3, 4});
    mesh.addFace({3, 0, 4});
    return mesh;
}

bool sameMesh(const PolygonMesh& a, const PolygonMesh& b) {
    return a.positions == b.positions && a.offsets == b.offsets && a.indices == b.indices;
}

std::string describe(const PolygonMesh& m) {
    std::ostringstream out;
    out << m.vertexCount() << " vertices:";
    for (const Vec3& p : m.positions)
        out << " (" << p.x() << ", " << p.y() << ", " << p.z() << ")";
    out << "; " << m.faceCount() << " faces:";
    for (Index f = 0; f < m.faceCount(); ++f) {
        out << " [";
        for (Index v : m.face(f))
            out << " " << v;
        out << " ]";
    }
    return out.str();
}

QByteArray readBytes(const std::string& path) {
    QFile file(QString::fromStdString(path));
    if (!file.open(QIODevice::ReadOnly))
        return {};
    return file.readAll();
}

void writeBytes(const QString& path, const QByteArray& bytes) {
    QFile file(path);
    QVERIFY(file.open(QIODevice::WriteOnly | QIODevice::Truncate));
    QCOMPARE(file.write(bytes), bytes.size());
}

} // namespace

class TestMeshIo : public QObject {
    Q_OBJECT

private slots:
    void withPositionsKeepsTheConnectivity() {
        const TriangleMesh mesh({Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(1, 1, 0)},
                                {{0, 1, 2}, {1, 3, 2}});
        const TriangleMesh moved =
            mesh.withPositions({Vec3(0, 0, 1), Vec3(2, 0, 1), Vec3(0, 2, 1), Vec3(2, 2, 1)});
        QCOMPARE(moved.edgeCount(), mesh.edgeCount());
        QCOMPARE(moved.boundaryEdgeCount(), mesh.boundaryEdgeCount());
        for (Index h = 0; h < mesh.halfedgeCount(); ++h)
            QCOMPARE(moved.opposite(h), mesh.opposite(h));
        QCOMPARE(moved.position(3), Vec3(2, 2, 1));
        QCOMPARE(mesh.position(3), Vec3(1, 1, 0));
        QVERIFY_THROWS_EXCEPTION(std::invalid_argument, mesh.withPositions({Vec3::Zero()}));
    }

    // A non-convex polygon (a U, first corner next to the notch): the fan
    // from corner 0 would cover the notch with reversed triangles; ear
    // clipping keeps every triangle's winding and the polygon's area.
    void nonConvexPolygonTriangulation() {
        const std::vector<Vec3> p{{0, 0, 0}, {3, 0, 0}, {3, 3, 0}, {2, 3, 0},
                                  {2, 1, 0}, {1, 1, 0}, {1, 3, 0}, {0, 3, 0}};
        std::vector<Index> polygon(p.size());
        for (size_t i = 0; i < p.size(); ++i)
            polygon[i] = static_cast<Index>((i + 4) % p.size()); // start at the notch
        const auto triangles = triangulatePolygon(p, polygon);
        QCOMPARE(triangles.size(), p.size() - 2);
        double area = 0.0;
        for (const auto& t : triangles) {
            const double a = (p[t[1]] - p[t[0]]).cross(p[t[2]] - p[t[0]]).z() / 2.0;
            QVERIFY2(a > 0.0, "a triangle is reversed or flat");
            area += a;
        }
        QCOMPARE(area, 7.0); // 3x3 minus the 1x2 notch
        // The fan from the notch corner does reverse triangles (why this exists).
        double fanReversed = 0.0;
        for (size_t i = 1; i + 1 < polygon.size(); ++i) {
            const Vec3 &a = p[polygon[0]], &b = p[polygon[i]], &c = p[polygon[i + 1]];
            fanReversed += (b - a).cross(c - a).z() < 0.0;
        }
        QVERIFY(fanReversed > 0);
    }

    void loaderRejects_data();
    void loaderRejects();
    void formatsReadIdentically_data();
    void formatsReadIdentically();
    void objRelativeIndices();
    void objTextureCoordinates();
    void quadMeshStaysQuads();
    void plyExtraPropertiesAsLabels();
    void writersRoundTrip_data();
    void writersRoundTrip();
    void triangleMeshWriters();
    void writerFailures();
    void validationOfBuiltMeshes();
    void unusedVertexIsAllowed();
    void garbageNeverCrashes();
    void spotControlMesh();
};

void TestMeshIo::loaderRejects_data() {
    QTest::addColumn<QString>("file");
    QTest::addColumn<QString>("location");
    QTest::addColumn<QString>("problem");
    auto row = [](const char* file, const char* location, const char* problem) {
        QTest::newRow(file) << file << location << problem;
    };
    // Topology and geometry (validation).
    row("nonmanifold_edge.obj", "line 9",
        "edge (1, 2) is non-manifold: it is shared by 3 faces (the faces on lines 7, 8 and 9)");
    row("nonmanifold_edge_binary.ply", "edge (0, 1)",
        "the edge is non-manifold: it is shared by 3 faces (faces 0, 1 and 2)");
    row("nonmanifold_vertex.obj", "line 2",
        "vertex 1 is non-manifold: the faces around it form 2 separate fans");
    row("inconsistent_orientation.obj", "line 7",
        "the faces on lines 6 and 7 both run along edge (1, 2) from vertex 1 to vertex 2, so they "
        "are inconsistently oriented");
    row("moebius_strip.obj", "line 10", "inconsistently oriented");
    row("degenerate_repeated_index.obj", "line 5",
        "the face is degenerate: it uses vertex 2 twice");
    row("degenerate_zero_area.obj", "line 7",
        "the face is degenerate: its corners lie on one line (zero area)");
    row("coincident_corners.obj", "line 6",
        "the face is degenerate: its corners lie on one line (zero area); vertices 1 and 3 are "
        "at the same point");
    row("degenerate_collinear_quad.off", "line 8",
        "the face is degenerate: its corners lie on one line");
    row("face_with_two_corners.obj", "line 5", "the face has only 2 corners");
    row("nan_coordinate.obj", "line 2", "vertex 2 has a NaN y coordinate");
    row("inf_coordinate.ply", "line 12", "vertex 2 has an infinite z coordinate");
    row("overflowing_coordinate.obj", "line 3", "vertex 3 has an infinite y coordinate");
    row("empty.obj", "", "the mesh has no vertices");
    row("no_faces.obj", "", "the mesh has no faces");
    // Indices.
    row("index_out_of_range.obj", "line 9",
        "face index 12 is out of range (the file has 6 vertices)");
    row("relative_index_out_of_range.obj", "line 6",
        "relative face index -9 is out of range (only 4 vertices are defined before this line)");
    row("zero_index.obj", "line 4", "face index 0 is invalid");
    row("negative_index.off", "line 8", "face index -1 is negative");
    row("negative_index_binary_be.ply", "face 0", "face index -1 is negative");
    row("ply_index_out_of_range.ply", "line 14 (face 0)",
        "face index 3 is out of range (the file has 3 vertices)");
    // Syntax.
    row("missing_coordinate.obj", "line 2", "a vertex needs 3 coordinates, this one has 2");
    row("not_a_number.obj", "line 2", "vertex coordinate \"zero\" is not a number");
    row("bad_face_corner.obj", "line 4", "face corner \"1/1/1/1\" is not a vertex index");
    row("garbage.obj", "line 1", "unknown statement");
    row("garbage.off", "line 2", "not an OFF file");
    row("off_wrong_keyword.off", "line 1", "not an OFF file (it must start with \"OFF\"");
    row("off_truncated.off", "line 7",
        "the file ends after 4 of the 8 vertices that the header announces");
    row("off_face_too_short.off", "line 6", "face 0 announces 4 corners but lists only 3");
    row("off_huge_count.off", "line 2",
        "the header announces 1000000000000 vertices, more than the 2147483647 supported");
    row("garbage.ply", "line 1", "not a PLY file");
    row("not_a_ply.ply", "line 1", "not a PLY file");
    row("bad_ply_header.ply", "line 6", "unknown property type \"flaot\"");
    row("ply_no_end_header.ply", "line 6", "no \"end_header\" line");
    row("ply_missing_z.ply", "line 3", "the vertex element has no \"z\" property");
    row("ply_no_vertex_indices.ply", "line 7",
        "the face element has no \"vertex_indices\" list property");
    row("huge_vertex_count.ply", "line 3",
        "the header announces 1000000000000 vertices, more than the 2147483647 supported");
    row("huge_count_little_data.ply", "vertex 5",
        "the file ends in the middle of this vertex (binary data ran out");
    row("huge_list_count.ply", "face 0", "the file ends in the middle of this face");
    row("truncated_binary.ply", "face 2",
        "the file ends in the middle of this face (binary data ran out; the header announces 5 "
        "faces)");
    row("truncated_ascii.ply", "line 16 (face 1)", "the file ends in the middle of this face");
    row("random_binary_data.ply", "face 0", "is out of range (the file has 100 vertices)");
    // Files.
    row("unknown_format.stl", "", "unknown mesh format \".stl\" (expected .obj, .off or .ply)");
    row("does_not_exist.obj", "", "cannot open the file (No such file or directory)");
}

void TestMeshIo::loaderRejects() {
    QFETCH(QString, file);
    QFETCH(QString, location);
    QFETCH(QString, problem);
    const std::string path = badFile(file);
    if (file != "does_not_exist.obj")
        QVERIFY2(QFileInfo::exists(QString::fromStdString(path)), path.c_str());
    try {
        const PolygonMesh mesh = readMesh(path);
        QFAIL(qPrintable("accepted: " + QString::fromStdString(describe(mesh))));
    } catch (const MeshError& error) {
        const QString message = QString::fromUtf8(error.what());
        QVERIFY2(message.contains(file), qPrintable(message));
        QCOMPARE(QString::fromStdString(error.file()), QString::fromStdString(path));
        QCOMPARE(QString::fromStdString(error.location()), location);
        if (!location.isEmpty())
            QVERIFY2(message.contains(": " + location + ": "), qPrintable(message));
        QVERIFY2(message.contains(problem), qPrintable(message));
    }
}

void TestMeshIo::formatsReadIdentically_data() {
    QTest::addColumn<QString>("file");
    for (const char* file : {"pyramid.obj", "pyramid_relative.obj", "pyramid_cr.obj", "pyramid.off",
                             "pyramid_ascii.ply", "pyramid_binary_le.ply", "pyramid_binary_be.ply"})
        QTest::newRow(file) << file;
}

void TestMeshIo::formatsReadIdentically() {
    QFETCH(QString, file);
    const PolygonMesh mesh = readMesh(goodFile(file));
    QVERIFY2(sameMesh(mesh, pyramid()), describe(mesh).c_str());
}

void TestMeshIo::objRelativeIndices() {
    QTemporaryDir dir;
    QVERIFY(dir.isValid());
    // Negative indices are relative to the vertices defined so far, not to
    // the whole file: the second face reuses "-1" for a different vertex.
    const QString path = dir.filePath("relative.obj");
    writeBytes(path, "v 0 0 0\nv 1 0 0\nv 0 1 0\nf -3 -2 -1\n"
                     "v 1 1 0\nf -3 -2 -1\n");
    const PolygonMesh mesh = readObj(path.toStdString());
    QCOMPARE(mesh.faceCount(), 2);
    QCOMPARE(std::vector<Index>(mesh.face(0).begin(), mesh.face(0).end()),
             (std::vector<Index>{0, 1, 2}));
    QCOMPARE(std::vector<Index>(mesh.face(1).begin(), mesh.face(1).end()),
             (std::vector<Index>{1, 2, 3}));
    // Relative and absolute indices mix, with v/vt/vn forms.
    writeBytes(path, "v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nvn 0 0 1\nf 1/1/1 -2/1/1 -1//1\n");
    const PolygonMesh mixed = readObj(path.toStdString());
    QCOMPARE(std::vector<Index>(mixed.face(0).begin(), mixed.face(0).end()),
             (std::vector<Index>{0, 1, 2}));
}

void TestMeshIo::objTextureCoordinates() {
    QTemporaryDir dir;
    QVERIFY(dir.isValid());
    const QString path = dir.filePath("uv.obj");
    // Every corner has a vt (one relative, one forward): kept, per corner.
    writeBytes(path, "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\nvt 0.5 0.25\nvt 1 0\n"
                     "f 1/1 2/2 3/-1\nf 2/2/1 4/3 3/1\nvt 0.75 1\n");
    const PolygonMesh mesh = readObj(path.toStdString());
    QVERIFY(mesh.hasTextureCoordinates());
    QCOMPARE(mesh.textureCoordinates.size(), size_t(3));
    QCOMPARE(mesh.cornerTexture, (std::vector<Index>{0, 1, 1, 1, 2, 0}));
    QCOMPARE(mesh.textureCoordinates[0], Vec2(0.5, 0.25));
    // One corner without: none are kept (a partial layout is of no use).
    writeBytes(path, "v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nf 1/1 2/1 3\n");
    QVERIFY(!readObj(path.toStdString()).hasTextureCoordinates());
    // A vt index beyond the file's texture coordinates: dropped too.
    writeBytes(path, "v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nf 1/1 2/1 3/7\n");
    QVERIFY(!readObj(path.toStdString()).hasTextureCoordinates());
    // A malformed vt line names the problem.
    writeBytes(path, "v 0 0 0\nvt 0 x\n");
    try {
        readObj(path.toStdString());
        QFAIL("a bad texture coordinate was accepted");
    } catch (const std::exception& e) {
        QVERIFY2(std::string(e.what()).find("texture coordinate") != std::string::npos, e.what());
    }
}

void TestMeshIo::quadMeshStaysQuads() {
    const PolygonMesh cube = readMesh(goodFile("cube_quads.obj"));
    QCOMPARE(cube.vertexCount(), 8);
    QCOMPARE(cube.faceCount(), 6);
    QVERIFY(cube.isQuadMesh());
    for (Index f = 0; f < cube.faceCount(); ++f)
        QCOMPARE(cube.face(f).size(), size_t{4});
    // Mixed polygons keep their sizes too.
    const PolygonMesh mixed = readMesh(goodFile("pyramid.off"));
    QCOMPARE(mixed.face(0).size(), size_t{4});
    QCOMPARE(mixed.face(1).size(), size_t{3});
}

void TestMeshIo::plyExtraPropertiesAsLabels() {
    PlyLabels labels;
    readPly(goodFile("pyramid_ascii.ply"), &labels);
    QCOMPARE(labels.vertexLabels.size(), size_t{1});
    QCOMPARE(labels.vertexLabels["quality"], (std::vector<int>{0, 1, 2, 3, 4}));
    QVERIFY(labels.faceLabels.empty()); // the texcoord list is skipped
    QVERIFY(labels.faceScalars.empty());

    readPly(goodFile("pyramid_binary_be.ply"), &labels);
    QCOMPARE(labels.vertexLabels["id"], (std::vector<int>{0, 1, 2, 3, 4}));
    QCOMPARE(labels.faceScalars["area"], (std::vector<double>(5, 0.5)));
    QVERIFY(labels.vertexScalars.empty());

    // readMesh passes them through and validates.
    const PolygonMesh mesh = readMesh(goodFile("pyramid_binary_be.ply"), &labels);
    QVERIFY(sameMesh(mesh, pyramid()));
    QCOMPARE(labels.faceScalars["area"].size(), size_t{5});
}

void TestMeshIo::writersRoundTrip_data() {
    QTest::addColumn<QString>("format");
    QTest::newRow("obj") << "obj";
    QTest::newRow("ply ascii") << "ply ascii";
    QTest::newRow("ply binary") << "ply binary";
}

void TestMeshIo::writersRoundTrip() {
    QFETCH(QString, format);
    QTemporaryDir dir;
    QVERIFY(dir.isValid());
    // Coordinates that only an exact writer keeps: thirds, tiny and huge
    // values, negative zero; and a polygon with 300 corners (a PLY list
    // count that does not fit a uchar).
    PolygonMesh mesh = pyramid();
    for (Vec3& p : mesh.positions)
        p = p * (1.0 / 3.0) + Vec3(1e-300, -2.5e7, 0.1);
    mesh.positions[0].z() = -0.0;
    const Index ringStart = mesh.vertexCount();
    std::vector<Index> ring, reversed;
    for (int i = 0; i < 300; ++i) {
        const double angle = 2.0 * std::numbers::pi * i / 300.0;
        mesh.positions.emplace_back(10.0 + std::cos(angle), std::sin(angle), 0.0);
        ring.push_back(ringStart + i);
    }
    reversed.assign(ring.rbegin(), ring.rend());
    mesh.addFace(ring);
    mesh.addFace(reversed); // a closed, two-sided disk: valid
    PlyLabels labels;
    const auto nv = static_cast<size_t>(mesh.vertexCount());
    const auto nf = static_cast<size_t>(mesh.faceCount());
    for (size_t v = 0; v < nv; ++v) {
        labels.vertexLabels["phase"].push_back(static_cast<int>(v) - 3);
        labels.vertexScalars["g"].push_back(std::sqrt(static_cast<double>(v)) - 1.0);
    }
    for (size_t f = 0; f < nf; ++f) {
        labels.faceLabels["facing"].push_back(f % 2 ? 1 : -1);
        labels.faceLabels["inconsistent"].push_back(static_cast<int>(f * 1000003));
        labels.faceScalars["kr"].push_back(f == 0 ? -0.0 : 1.0 / (static_cast<double>(f) + 7));
    }

    const bool obj = format == "obj";
    const std::string path = dir.filePath(obj ? "out.obj" : "out.ply").toStdString();
    if (obj)
        writeObj(mesh, path);
    else
        writePly(mesh, path, labels, format == "ply binary");
    QVERIFY(!QFileInfo::exists(QString::fromStdString(path + ".tmp")));
    PlyLabels reloaded;
    const PolygonMesh back = readMesh(path, &reloaded);
    QVERIFY(sameMesh(back, mesh));
    QVERIFY(std::signbit(back.positions[0].z()));
    if (obj) {
        QVERIFY(reloaded.empty());
    } else {
        QVERIFY(reloaded == labels);
        QVERIFY(std::signbit(reloaded.faceScalars["kr"][0]));
    }
    // Writing again replaces the file.
    if (!obj) {
        writePly(mesh, path, {}, format == "ply binary");
        readMesh(path, &reloaded);
        QVERIFY(reloaded.empty());
    }
}

void TestMeshIo::triangleMeshWriters() {
    QTemporaryDir dir;
    QVERIFY(dir.isValid());
    const TriangleMesh triangles = readMesh(goodFile("cube_quads.obj")).triangulate();
    QCOMPARE(triangles.faceCount(), 12);
    PlyLabels labels;
    labels.faceLabels["source"].resize(12);
    for (Index f = 0; f < 12; ++f)
        labels.faceLabels["source"][f] = triangles.sourcePolygon(f);
    for (const bool binary : {false, true}) {
        const std::string ply = dir.filePath(binary ? "t_bin.ply" : "t.ply").toStdString();
        writePly(triangles, ply, labels, binary);
        PlyLabels back;
        const PolygonMesh mesh = readMesh(ply, &back);
        QVERIFY(mesh.isTriangleMesh());
        QCOMPARE(mesh.faceCount(), 12);
        QCOMPARE(back.faceLabels["source"], labels.faceLabels["source"]);
        for (Index f = 0; f < 12; ++f)
            for (int k = 0; k < 3; ++k)
                QCOMPARE(mesh.face(f)[k], triangles.triangle(f)[k]);
    }
    const std::string obj = dir.filePath("t.obj").toStdString();
    writeObj(triangles, obj);
    const PolygonMesh mesh = readMesh(obj);
    QCOMPARE(mesh.faceCount(), 12);
    QCOMPARE(mesh.positions,
             std::vector<Vec3>(triangles.positions().begin(), triangles.positions().end()));
}

void TestMeshIo::writerFailures() {
    QTemporaryDir dir;
    QVERIFY(dir.isValid());
    const PolygonMesh mesh = pyramid();
    auto expectFailure = [&](const std::function<void()>& write, const std::string& path,
                             const QString& problem) {
        try {
            write();
            QFAIL("no exception");
        } catch (const std::runtime_error& error) {
            const QString message = QString::fromUtf8(error.what());
            QVERIFY2(message.startsWith(QString::fromStdString(path) + ": "), qPrintable(message));
            QVERIFY2(message.contains(problem), qPrintable(message));
        }
        QVERIFY(!QFileInfo::exists(QString::fromStdString(path)));
        QVERIFY(!QFileInfo::exists(QString::fromStdString(path + ".tmp")));
    };
    const std::string missingDir = dir.filePath("no/such/dir/out.obj").toStdString();
    expectFailure([&] { writeObj(mesh, missingDir); }, missingDir, "cannot write");
    const std::string ply = dir.filePath("labels.ply").toStdString();
    PlyLabels shortColumn;
    shortColumn.vertexLabels["phase"] = {1, 2};
    expectFailure([&] { writePly(mesh, ply, shortColumn); }, ply,
                  "it has 2 values but the mesh has 5 vertices");
    PlyLabels badName;
    badName.faceScalars["two words"] = std::vector<double>(5, 1.0);
    expectFailure([&] { writePly(mesh, ply, badName); }, ply, "without spaces");
    PlyLabels reserved;
    reserved.vertexScalars["x"] = std::vector<double>(5, 1.0);
    expectFailure([&] { writePly(mesh, ply, reserved); }, ply, "reserved");
    // A failed rename (the target is a directory) leaves the target alone.
    const QString target = dir.filePath("occupied.ply");
    QVERIFY(QDir(dir.path()).mkdir("occupied.ply"));
    try {
        writePly(mesh, target.toStdString());
        QFAIL("no exception");
    } catch (const std::runtime_error& error) {
        QVERIFY2(QString(error.what()).startsWith(target), error.what());
    }
    QVERIFY(QFileInfo(target).isDir());
    QVERIFY(!QFileInfo::exists(target + ".tmp"));
}

void TestMeshIo::validationOfBuiltMeshes() {
    auto problemOf = [](const PolygonMesh& mesh) -> QString {
        try {
            validatePolygonMesh(mesh, "built");
        } catch (const MeshError& error) {
            return QString::fromUtf8(error.what());
        }
        return {};
    };
    QCOMPARE(problemOf(pyramid()), QString());
    PolygonMesh negative = pyramid();
    negative.indices[1] = -4;
    QCOMPARE(problemOf(negative), "built: face 0: the face uses the negative vertex index -4");
    PolygonMesh outOfRange = pyramid();
    outOfRange.indices[1] = 9;
    QCOMPARE(problemOf(outOfRange),
             "built: face 0: face index 9 is out of range (the mesh has 5 vertices)");
    PolygonMesh broken = pyramid();
    broken.offsets.back() = 99;
    QVERIFY(problemOf(broken).contains("face offsets are inconsistent"));
    PolygonMesh flipped = pyramid();
    std::reverse(flipped.indices.begin() + 4, flipped.indices.begin() + 7); // face 1
    QVERIFY2(problemOf(flipped).startsWith("built: edge ("), qPrintable(problemOf(flipped)));
    QVERIFY(problemOf(flipped).contains("faces 0 and 1 both run along"));
    PolygonMesh samePoint = pyramid();
    samePoint.positions[1] = samePoint.positions[0];
    samePoint.positions[4] = samePoint.positions[0];
    QVERIFY(problemOf(samePoint).contains("all its corners are at the same point"));
    // Two pyramids sharing only their apex: a non-manifold vertex.
    PolygonMesh twoCones = pyramid();
    for (int i = 0; i < 4; ++i)
        twoCones.positions.push_back(twoCones.positions[i] + Vec3(0, 0, 2));
    twoCones.addFace({5, 6, 7, 8});
    for (int i = 0; i < 4; ++i)
        twoCones.addFace({5 + (i + 1) % 4, 5 + i, 4});
    QCOMPARE(problemOf(twoCones),
             "built: vertex 4: the vertex is non-manifold: the faces around it form 2 separate "
             "fans that meet only at this vertex (e.g. faces 1 and 6)");
    // Nearly but not exactly collinear corners are a valid (thin) face.
    PolygonMesh thin;
    thin.positions = {Vec3(0, 0, 0), Vec3(1, 1e-300, 0), Vec3(2, 0, 0)};
    thin.addFace({0, 1, 2});
    QCOMPARE(problemOf(thin), QString());
}

void TestMeshIo::unusedVertexIsAllowed() {
    PolygonMesh mesh = pyramid();
    mesh.positions.emplace_back(5, 5, 5);
    validatePolygonMesh(mesh, "unused");
    QTemporaryDir dir;
    const std::string path = dir.filePath("unused.obj").toStdString();
    writeObj(mesh, path);
    QCOMPARE(readMesh(path).vertexCount(), 6);
}

// Every prefix of every good file and random byte flips: each read returns a
// mesh or throws MeshError; nothing crashes, hangs or throws anything else.
void TestMeshIo::garbageNeverCrashes() {
    QTemporaryDir dir;
    QVERIFY(dir.isValid());
    std::mt19937 random(12345);
    int accepted = 0, rejected = 0;
    const QStringList files = QDir(dataDir() + "/good").entryList(QDir::Files);
    for (const QString& name : files) {
        if (name.endsWith(".py"))
            continue;
        const QByteArray original = readBytes(goodFile(name));
        const QString path = dir.filePath("fuzz." + QFileInfo(name).suffix());
        std::vector<QByteArray> variants;
        for (qsizetype n = 0; n < original.size(); ++n)
            variants.push_back(original.left(n));
        for (int i = 0; i < 300; ++i) {
            QByteArray bytes = original;
            const int flips = 1 + static_cast<int>(random() % 4);
            for (int k = 0; k < flips; ++k)
                bytes[static_cast<qsizetype>(random() % bytes.size())] =
                    static_cast<char>(random() % 256);
            variants.push_back(bytes);
        }
        for (const QByteArray& bytes : variants) {
            writeBytes(path, bytes);
            try {
                readMesh(path.toStdString());
                ++accepted;
            } catch (const MeshError& error) {
                ++rejected;
                QVERIFY(QString::fromUtf8(error.what()).startsWith(path + ": "));
            }
        }
    }
    qInfo("%d variants accepted, %d rejected with MeshError", accepted, rejected);
    QVERIFY(rejected > 0);
}

void TestMeshIo::spotControlMesh() {
    const QString path = QStringLiteral(CONTOUR_SHARED_DIR "/meshes/spot_control_mesh.obj");
    if (!QFileInfo::exists(path))
        QSKIP(qPrintable(path + " is absent (../shared is not part of a clone)"));
    const PolygonMesh spot = readMesh(path.toStdString());
    // Counted from the file: grep -c '^v ' gives 188, grep -c '^f ' gives 180
    // (160 quads, 4 triangles, 16 pentagons).
    QCOMPARE(spot.vertexCount(), 188);
    QCOMPARE(spot.faceCount(), 180);
    int sizes[6] = {0, 0, 0, 0, 0, 0};
    for (Index f = 0; f < spot.faceCount(); ++f)
        ++sizes[std::min<size_t>(spot.face(f).size(), 5)];
    QCOMPARE(sizes[3], 4);
    QCOMPARE(sizes[4], 160);
    QCOMPARE(sizes[5], 16);
}

QTEST_APPLESS_MAIN(TestMeshIo)
#include "test_mesh_io.moc"
