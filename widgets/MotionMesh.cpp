#include "MotionMesh.h"

#include "SnapshotToVtk.h"

#include <chrono>
#include <vtkCellArray.h>
#include <vtkCellLocator.h>
#include <vtkGenericCell.h>
#include <vtkIdList.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkPolyDataNormals.h>
#include <vtkQuadricDecimation.h>

namespace contour {

MotionMesh buildMotionMesh(const TriangleMesh& mesh, Index targetFaces) {
    const auto start = std::chrono::steady_clock::now();
    MotionMesh result;
    vtkSmartPointer<vtkPolyData> full = meshToPolyData(mesh);
    const Index faces = mesh.faceCount();
    if (faces == 0)
        return result;
    if (faces <= targetFaces) {
        result.data = full;
        result.sourceFaces.resize(static_cast<size_t>(faces));
        for (Index f = 0; f < faces; ++f)
            result.sourceFaces[static_cast<size_t>(f)] = f;
    } else {
        vtkNew<vtkQuadricDecimation> decimate;
        decimate->SetInputData(full);
        decimate->SetTargetReduction(1.0 - static_cast<double>(targetFaces) / faces);
        // Geometry only: the colours come from the face map below.
        decimate->AttributeErrorMetricOff();
        decimate->Update();
        result.data = vtkSmartPointer<vtkPolyData>::New();
        result.data->SetPoints(decimate->GetOutput()->GetPoints());
        result.data->SetPolys(decimate->GetOutput()->GetPolys());

        // The source face nearest to each triangle's centre.
        vtkNew<vtkCellLocator> locator;
        locator->SetDataSet(full);
        locator->BuildLocator();
        vtkPolyData* lod = result.data;
        const vtkIdType count = lod->GetNumberOfPolys();
        result.sourceFaces.resize(static_cast<size_t>(count));
        vtkCellArray* polys = lod->GetPolys();
        vtkNew<vtkIdList> ids;
        vtkNew<vtkGenericCell> cell;
        for (vtkIdType c = 0; c < count; ++c) {
            polys->GetCellAtId(c, ids);
            double centre[3] = {0.0, 0.0, 0.0};
            for (vtkIdType i = 0; i < ids->GetNumberOfIds(); ++i) {
                double p[3];
                lod->GetPoint(ids->GetId(i), p);
                for (int k = 0; k < 3; ++k)
                    centre[k] += p[k] / static_cast<double>(ids->GetNumberOfIds());
            }
            double closest[3];
            vtkIdType face = 0;
            int subId = 0;
            double distance2 = 0.0;
            locator->FindClosestPoint(centre, closest, cell, face, subId, distance2);
            result.sourceFaces[static_cast<size_t>(c)] =
                face >= 0 && face < faces ? static_cast<Index>(face) : 0;
        }
    }

    vtkNew<vtkPolyDataNormals> normals;
    normals->SetInputData(result.data);
    normals->SplittingOff();
    normals->ConsistencyOff();
    normals->AutoOrientNormalsOff();
    normals->ComputePointNormalsOn();
    normals->ComputeCellNormalsOff();
    normals->Update();
    result.normals = normals->GetOutput()->GetPointData()->GetNormals();

    result.seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    return result;
}

} // namespace contour
