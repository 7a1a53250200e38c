/**
 * @class   vtkPGISelfVisibility
 * @brief   Per-vertex SH log-visibility of a rigid object's own geometry,
 *          traced once with Embree, so that the GI filter adds only the
 *          other objects' proxies at run time.
 *
 * Bounding spheres shadow an object too much where they stand in for its own
 * surface; the object's own mesh shadows it exactly. Per vertex this filter
 * traces Samples rays over the hemisphere around the normal
 * (spherical Fibonacci directions, turned about the normal by a random angle
 * per vertex) against the input mesh alone. The visibility V is 1 below the
 * tangent plane (the self-shadow rules' convention: the object's back is not
 * a shadow of its front), is projected into SH of Order and its logarithm
 * taken by sh::Log, so that vtkPGIGlobalIllumination adds it to the other
 * blockers' logs before the one exp.
 *
 * Input: a polygonal mesh (triangulated as needed); point normals are used if
 * present, computed without splitting otherwise (give the normals the GI
 * filter will see). Output: the input with point arrays
 *  - SelfLogVisibility (Order^2 floats): log of the SH visibility, exactly 0
 *    where no ray is blocked;
 *  - SelfVisibilityRest (3): the points it was traced at; the GI filter uses
 *    the arrays only while the points stay there (moved or deformed: rules);
 *  - ObjectId (1): the ObjectId property, unless the input has the array;
 *    the GI filter leaves the proxies of this object out;
 * and field data arrays
 *  - SelfBounceOffsets (points + 1 ids), SelfBounceTargets (ids),
 *    SelfBounceWeights (floats) and SelfBounceHitPoints (3 floats): the
 *    bounce off the mesh onto itself as a sparse gather. Vertex i receives
 *    the sum over e in [Offsets[i], Offsets[i + 1]) of Weights[e] times the
 *    exit radiance at point Targets[e]: one entry per blocked ray (the hit
 *    triangle's nearest corner, weight 2 cos(theta) / Samples; a hit on a
 *    triangle's back, the unlit inside or a sheet's other side, blocks but
 *    brings no light), points hit twice merged; HitPoints[e] is where the
 *    largest of the hits merged into e lies (the GI filter lights that point
 *    by the bright lights itself where the entry is heavy: a near hit). About
 *    24 bytes per entry (the bunny at 256 rays: 34 entries per vertex);
 *  - SelfVisibilitySamples, SelfVisibilityBlockedFraction (rays blocked over
 *    rays traced).
 *
 * | property | default | cost and accuracy |
 * |---|---|---|
 * | Order | 4 | the GI settings' accumulation order must match |
 * | Samples | 256 | time grows linearly; stratified, so the error falls faster than 1/sqrt |
 * | Seed | 1 | the per-vertex turn of the directions; same seed, same result on any thread count |
 * | ObjectId | 0 | which proxies (by their "ObjectId") are this mesh's |
 *
 * Errors: no points, no polygons, NaN/Inf coordinates.
 */
#ifndef vtkPGISelfVisibility_h
#define vtkPGISelfVisibility_h

#include "ProxyGIReferenceModule.h"
#include "vtkPolyDataAlgorithm.h"

class PROXYGIREFERENCE_EXPORT vtkPGISelfVisibility : public vtkPolyDataAlgorithm
{
public:
  static vtkPGISelfVisibility* New();
  vtkTypeMacro(vtkPGISelfVisibility, vtkPolyDataAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  vtkSetClampMacro(Order, int, 2, 8);
  vtkGetMacro(Order, int);
  vtkSetClampMacro(Samples, int, 4, 1 << 16);
  vtkGetMacro(Samples, int);
  vtkSetMacro(Seed, unsigned int);
  vtkGetMacro(Seed, unsigned int);
  vtkSetMacro(ObjectId, int);
  vtkGetMacro(ObjectId, int);

protected:
  vtkPGISelfVisibility();
  ~vtkPGISelfVisibility() override;
  int RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;

  int Order = 4;
  int Samples = 256;
  unsigned int Seed = 1;
  int ObjectId = 0;

private:
  vtkPGISelfVisibility(const vtkPGISelfVisibility&) = delete;
  void operator=(const vtkPGISelfVisibility&) = delete;
};

#endif
