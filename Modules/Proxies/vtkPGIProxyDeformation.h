/**
 * @class   vtkPGIProxyDeformation
 * @brief   Moves sphere proxies with the per-vertex deformation of their mesh.
 *
 * Inputs: port 0 the proxies at rest (leaves at "Level" 0, any hierarchy
 * above them), port 1 the mesh at rest, port 2 the deformed mesh (same
 * points, same order). Each leaf sphere follows the average motion of the
 * vertices it bounds at rest (Guerrero et al. Section 7.1, soft
 * deformations): the best-fit rotation and translation (Kabsch) of those
 * vertices moves its centre, its radius is kept. A sphere that holds fewer
 * than three vertices (a sphere of interior samples) follows the vertices of
 * the triangle nearest to its centre (Embree closest-point query) as well.
 * Where the rest mesh has an "ObjectId" point array, a sphere only follows
 * vertices of its own object. Parents are then refitted bottom-up by pairwise
 * bounds, so the hierarchy keeps bounding the leaves.
 *
 * Bounding is exact for rigid motion of each sphere's vertices and may be
 * lost under strong bending or stretching. With MeasureBoundingLoss on, the
 * output field data says by how much: "SurfaceOutsideFraction" (share of
 * surface samples, vertices plus SurfaceSubdivisions-step points on each
 * triangle, in no leaf sphere), "SurfaceGapMaximum" and "SurfaceGapMean"
 * (distance from the samples to the nearest sphere, absolute units).
 *
 * The binding is computed once and reused while the rest inputs are
 * unchanged, so per time step the cost is one rigid fit per sphere.
 */
#ifndef vtkPGIProxyDeformation_h
#define vtkPGIProxyDeformation_h

#include "ProxyGIProxiesModule.h"
#include "vtkPolyDataAlgorithm.h"

class PROXYGIPROXIES_EXPORT vtkPGIProxyDeformation : public vtkPolyDataAlgorithm
{
public:
  static vtkPGIProxyDeformation* New();
  vtkTypeMacro(vtkPGIProxyDeformation, vtkPolyDataAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  /// Convenience: the rest mesh (port 1) and the deformed mesh (port 2).
  void SetRestMeshConnection(vtkAlgorithmOutput* output) { this->SetInputConnection(1, output); }
  void SetRestMeshData(vtkDataObject* mesh) { this->SetInputData(1, mesh); }
  void SetDeformedMeshConnection(vtkAlgorithmOutput* output)
  {
    this->SetInputConnection(2, output);
  }
  void SetDeformedMeshData(vtkDataObject* mesh) { this->SetInputData(2, mesh); }

  vtkSetMacro(MeasureBoundingLoss, bool);
  vtkGetMacro(MeasureBoundingLoss, bool);
  vtkBooleanMacro(MeasureBoundingLoss, bool);
  vtkSetClampMacro(SurfaceSubdivisions, int, 1, 64);
  vtkGetMacro(SurfaceSubdivisions, int);

protected:
  vtkPGIProxyDeformation();
  ~vtkPGIProxyDeformation() override;

  int FillInputPortInformation(int port, vtkInformation* info) override;
  int RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;

  bool MeasureBoundingLoss = false;
  int SurfaceSubdivisions = 4;

private:
  vtkPGIProxyDeformation(const vtkPGIProxyDeformation&) = delete;
  void operator=(const vtkPGIProxyDeformation&) = delete;

  struct Internal;
  Internal* Impl;
};

#endif
