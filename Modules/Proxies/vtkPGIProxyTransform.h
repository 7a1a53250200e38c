/**
 * @class   vtkPGIProxyTransform
 * @brief   Moves sphere proxies with an object's rigid motion and scale.
 *
 * Input: proxies (points with "Radius", any other arrays, any levels).
 * Output: the same proxies with centres mapped by the transform and radii
 * multiplied by its largest stretch (the largest singular value of the
 * linear part): exact for rotations, translations and uniform scale (the
 * Guerrero et al. Section 7.1 case), still bounding but looser for a
 * non-uniform scale or shear (a warning says so). Parents keep bounding their
 * subtrees, so no refit is needed.
 *
 * Transform applies to every sphere; SetObjectTransform(id, t) overrides it
 * for the spheres whose "ObjectId" is id (one actor per object). To follow
 * an actor: `transform->SetMatrix(actor->GetMatrix())`.
 */
#ifndef vtkPGIProxyTransform_h
#define vtkPGIProxyTransform_h

#include "ProxyGIProxiesModule.h"
#include "vtkPolyDataAlgorithm.h"

class vtkLinearTransform;

class PROXYGIPROXIES_EXPORT vtkPGIProxyTransform : public vtkPolyDataAlgorithm
{
public:
  static vtkPGIProxyTransform* New();
  vtkTypeMacro(vtkPGIProxyTransform, vtkPolyDataAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  virtual void SetTransform(vtkLinearTransform* transform);
  vtkGetObjectMacro(Transform, vtkLinearTransform);

  void SetObjectTransform(int objectId, vtkLinearTransform* transform);
  vtkLinearTransform* GetObjectTransform(int objectId);
  void RemoveAllObjectTransforms();

  vtkMTimeType GetMTime() override;

protected:
  vtkPGIProxyTransform();
  ~vtkPGIProxyTransform() override;

  int RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;

  vtkLinearTransform* Transform = nullptr;

private:
  vtkPGIProxyTransform(const vtkPGIProxyTransform&) = delete;
  void operator=(const vtkPGIProxyTransform&) = delete;

  struct Internal;
  Internal* Impl;
};

#endif
