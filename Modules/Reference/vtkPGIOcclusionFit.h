/**
 * @class   vtkPGIOcclusionFit
 * @brief   Sphere proxies whose radii are fitted so that their occlusion
 *          matches the mesh's, measured by Embree rays around the object.
 *
 * Bounding spheres are right for collision-like queries but shadow too much:
 * 64 spheres that contain a bunny block about a third more of the sky around
 * it than the bunny does. This filter keeps each sphere's centre and scales
 * its radius so that, seen from points around the object, the spheres block
 * the rays the mesh blocks.
 *
 * Sample points: half at random surface points pushed out along the face
 * normal by 1% to 50% of the mesh's bounding radius R (log-uniform; points
 * found inside the mesh are drawn again), half on random directions at
 * 1.05 R to 3 R from the bounding sphere's centre. From each point
 * Directions rays (a spherical Fibonacci set, turned at random per point)
 * are traced against the mesh (Embree) and against the spheres (exactly).
 * A ray disagrees when one blocks it and the other does not.
 *
 * The fit: first one common scale (golden-section search over
 * [MinimumScale, MaximumScale]), then Iterations rounds of per-sphere
 * multiplicative updates: a sphere grows with the rays it alone blocks
 * rightly and the blocked rays the spheres miss nearest to it, and shrinks
 * with the free rays it blocks; each sphere's scale stays within
 * [MinimumScale, MaximumScale] of its input radius. The scales with the
 * fewest disagreeing rays are kept.
 *
 * Input 0: proxies (points with "Radius"; every point is a leaf: build the
 * hierarchy after the fit). Input 1 (SetMeshConnection): the mesh they stand
 * for (polygons). Output: the proxies with "Radius" fitted, and point arrays
 * "BoundingRadius" (the input radius) and "RadiusScale"; field data
 * (measured on a second, independent set of sample points, not the one
 * fitted on):
 *  - OcclusionErrorBefore/After: rays where spheres and mesh disagree, over
 *    the rays the mesh blocks;
 *  - OcclusionBiasBefore/After: rays the spheres block minus rays the mesh
 *    blocks, over the rays the mesh blocks (positive: too dark);
 *  - CommonScale: the first step's scale.
 *
 * | property | default | cost and accuracy |
 * |---|---|---|
 * | Samples | 2048 | points; the rays are traced once, the spheres tested each round |
 * | Directions | 128 | rays per point (more points fit better than more rays per point) |
 * | Iterations | 24 | per-sphere rounds; each tests every ray against every sphere |
 * | MinimumScale, MaximumScale | 0.3, 1.1 | bounds of each radius over its input radius |
 * | Seed | 1 | same seed, same radii, whatever the thread count |
 *
 * Errors: no proxies, no Radius, a non-positive or non-finite radius, no
 * mesh, a mesh without polygons, NaN/Inf coordinates.
 */
#ifndef vtkPGIOcclusionFit_h
#define vtkPGIOcclusionFit_h

#include "ProxyGIReferenceModule.h"
#include "vtkPolyDataAlgorithm.h"

class PROXYGIREFERENCE_EXPORT vtkPGIOcclusionFit : public vtkPolyDataAlgorithm
{
public:
  static vtkPGIOcclusionFit* New();
  vtkTypeMacro(vtkPGIOcclusionFit, vtkPolyDataAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  /// The mesh the proxies stand for (input 1).
  void SetMeshConnection(vtkAlgorithmOutput* output) { this->SetInputConnection(1, output); }
  void SetMeshData(vtkDataObject* mesh) { this->SetInputData(1, mesh); }

  vtkSetClampMacro(Samples, int, 8, 1 << 20);
  vtkGetMacro(Samples, int);
  vtkSetClampMacro(Directions, int, 8, 1 << 14);
  vtkGetMacro(Directions, int);
  vtkSetClampMacro(Iterations, int, 0, 1000);
  vtkGetMacro(Iterations, int);
  vtkSetClampMacro(MinimumScale, double, 0.01, 1.0);
  vtkGetMacro(MinimumScale, double);
  vtkSetClampMacro(MaximumScale, double, 1.0, 4.0);
  vtkGetMacro(MaximumScale, double);
  vtkSetMacro(Seed, unsigned int);
  vtkGetMacro(Seed, unsigned int);

protected:
  vtkPGIOcclusionFit();
  ~vtkPGIOcclusionFit() override;
  int FillInputPortInformation(int port, vtkInformation* info) override;
  int RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;

  int Samples = 2048;
  int Directions = 128;
  int Iterations = 24;
  double MinimumScale = 0.3;
  double MaximumScale = 1.1;
  unsigned int Seed = 1;

private:
  vtkPGIOcclusionFit(const vtkPGIOcclusionFit&) = delete;
  void operator=(const vtkPGIOcclusionFit&) = delete;
};

#endif
