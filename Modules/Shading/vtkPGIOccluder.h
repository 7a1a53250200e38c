/**
 * @class   vtkPGIOccluder
 * @brief   Shadow rays against real geometry for the GI filter's bright
 *          lights and the light cloud's visibility tests: an interface, so that the Shading module
 * needs no ray tracer (vtkPGIMeshOccluder, in the Reference module, is Embree's).
 *
 * vtkPGIGlobalIllumination calls Prepare() once per update, outside its
 * parallel loop, then Occluded() from many threads at once.
 */
#ifndef vtkPGIOccluder_h
#define vtkPGIOccluder_h

#include "ProxyGIShadingModule.h"
#include "vtkObject.h"

#include <string>

class PROXYGISHADING_EXPORT vtkPGIOccluder : public vtkObject
{
public:
  vtkTypeMacro(vtkPGIOccluder, vtkObject);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  /// Builds what the rays need; false with `error` set when it cannot.
  virtual bool Prepare(std::string& error) = 0;
  /**
   * For `count` rays from origins (3 floats each) along unit directions,
   * whether something lies between `tnear` and infinity: blocked[i] = 1
   * or 0. Thread-safe after Prepare().
   */
  virtual void Occluded(int count, const float* origins, const float* directions, float tnear,
    unsigned char* blocked) const = 0;
  /// The same for segments: blocked when something lies between tnear and
  /// lengths[i] along ray i (visibility between two points).
  virtual void OccludedSegments(int count, const float* origins, const float* directions,
    const float* lengths, float tnear, unsigned char* blocked) const = 0;
  /// The size of what it holds (its bounding box diagonal), for ray offsets.
  virtual double GetSceneSize() const = 0;
  /// A few words for the plan ("Embree, 3 meshes, 120,000 triangles").
  virtual std::string Describe() const = 0;

protected:
  vtkPGIOccluder() = default;
  ~vtkPGIOccluder() override = default;

private:
  vtkPGIOccluder(const vtkPGIOccluder&) = delete;
  void operator=(const vtkPGIOccluder&) = delete;
};

#endif
