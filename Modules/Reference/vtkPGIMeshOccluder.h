/**
 * @class   vtkPGIMeshOccluder
 * @brief   The real meshes of a scene as an occluder for the GI filter's
 *          bright lights: shadow rays on Embree.
 *
 * Add every mesh that casts shadows (the receivers themselves included: a
 * mesh shadows itself; a ground mesh blocks the light below its horizon).
 * The Embree scene is built on the first Prepare() after a change (a mesh
 * added or removed, or a mesh's MTime), so a filter update with the meshes
 * unchanged traces at once. Rays start on the receivers: the GI filter
 * offsets them along the normal by 1e-4 of GetSceneSize().
 *
 * Errors (from Prepare, reported by the filter): no meshes, no polygons,
 * NaN/Inf coordinates.
 */
#ifndef vtkPGIMeshOccluder_h
#define vtkPGIMeshOccluder_h

#include "ProxyGIReferenceModule.h"
#include "vtkPGIOccluder.h"
#include "vtkSmartPointer.h"

#include <memory>
#include <vector>

class vtkPolyData;
namespace proxygi
{
class ReferenceTracer;
}

class PROXYGIREFERENCE_EXPORT vtkPGIMeshOccluder : public vtkPGIOccluder
{
public:
  static vtkPGIMeshOccluder* New();
  vtkTypeMacro(vtkPGIMeshOccluder, vtkPGIOccluder);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  void AddMesh(vtkPolyData* mesh);
  void RemoveAllMeshes();
  int GetNumberOfMeshes() const { return static_cast<int>(this->Meshes.size()); }
  /// Later than any mesh's change.
  vtkMTimeType GetMTime() override;

  bool Prepare(std::string& error) override;
  void Occluded(int count, const float* origins, const float* directions, float tnear,
    unsigned char* blocked) const override;
  void OccludedSegments(int count, const float* origins, const float* directions,
    const float* lengths, float tnear, unsigned char* blocked) const override;
  double GetSceneSize() const override;
  std::string Describe() const override;
  /// How many times Prepare() built the Embree scene.
  vtkGetMacro(NumberOfBuilds, int);

protected:
  vtkPGIMeshOccluder();
  ~vtkPGIMeshOccluder() override;

  std::vector<vtkSmartPointer<vtkPolyData>> Meshes;
  std::unique_ptr<proxygi::ReferenceTracer> Tracer;
  vtkMTimeType BuiltTime = 0;
  vtkIdType Triangles = 0;
  int NumberOfBuilds = 0;

private:
  vtkPGIMeshOccluder(const vtkPGIMeshOccluder&) = delete;
  void operator=(const vtkPGIMeshOccluder&) = delete;
};

#endif
