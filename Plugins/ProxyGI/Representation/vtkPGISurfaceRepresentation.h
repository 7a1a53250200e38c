/**
 * @class   vtkPGISurfaceRepresentation
 * @brief   ParaView's surface representation with per-vertex GI on the GPU:
 *          soft shadows and one-bounce indirect light from sphere proxies.
 *
 * A vtkGeometryRepresentationWithFaces (ParaView's Surface) whose mappers are
 * vtkPGIGICompositePolyDataMapper: every block of the surface receives light
 * and the proxies cast the shadows. The proxies come from input port 1 (for
 * example the Sphere Proxies filter), delivered to the rendering processes
 * with the geometry; without them the representation bounds the surface it
 * draws with NumberOfAutomaticProxies spheres itself (k-means, fast and less
 * tight than the variational Sphere Proxies; 0: no proxies, no shadows),
 * leaving out flat blocks (thinnest extent under 1% of the largest: grounds,
 * slices), which receive light but bound no volume.
 * The GI knobs (SetSettings) and the light (SetLighting) are shared by the
 * full-resolution and the LOD mapper. GI is recomputed when the geometry,
 * the proxies, the light or a knob change; camera moves only re-render.
 *
 * Under MPI (pvbatch, pvserver with several ranks) each rank draws its own
 * piece; the proxies (connected or automatic, the automatic count shared by
 * the ranks' triangles) are all-gathered in rank order unless they are
 * global already (Sphere Proxies' are), so each rank's mapper shades its
 * piece against all of them and IceT composites the pictures.
 */
#ifndef vtkPGISurfaceRepresentation_h
#define vtkPGISurfaceRepresentation_h

#include "ProxyGIParaViewRepresentationModule.h"
#include "vtkGeometryRepresentationWithFaces.h"
#include "vtkNew.h"
#include "vtkSmartPointer.h"

#include <string>

class vtkMultiProcessController;
class vtkPGIGISettings;
class vtkPGILighting;
class vtkPolyData;

class PROXYGIPARAVIEWREPRESENTATION_EXPORT vtkPGISurfaceRepresentation
  : public vtkGeometryRepresentationWithFaces
{
public:
  static vtkPGISurfaceRepresentation* New();
  vtkTypeMacro(vtkPGISurfaceRepresentation, vtkGeometryRepresentationWithFaces);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  int ProcessViewRequest(vtkInformationRequestKey* request_type, vtkInformation* inInfo,
    vtkInformation* outInfo) override;

  /// The GI knobs and the light, shared by both mappers.
  void SetSettings(vtkPGIGISettings* settings);
  void SetLighting(vtkPGILighting* lighting);

  /// Spheres the representation fits itself when no proxies are connected.
  void SetNumberOfAutomaticProxies(int spheres);
  vtkGetMacro(NumberOfAutomaticProxies, int);

  void SetExposure(double exposure);
  void SetCombineWithVTKLighting(bool on);
  void SetAlwaysRecompute(bool on);
  /// The accuracy budget of both mappers (vtkPGIGIPolyDataMapper::SetErrorBudget).
  void SetErrorBudget(double fraction);
  void SetTimeBudget(double seconds);
  void SetBudgetModelFileName(const char* fileName);
  void AddBlockerPlane(double ox, double oy, double oz, double nx, double ny, double nz, double ar,
    double ag, double ab);
  void RemoveAllBlockerPlanes();

  /// What the last frame's GI did and why (the full-resolution mapper's).
  const char* GetGIStatus();
  /// The proxies the last update delivered (connected or automatic).
  vtkPolyData* GetProxies();

protected:
  vtkPGISurfaceRepresentation();
  ~vtkPGISurfaceRepresentation() override;

  int FillInputPortInformation(int port, vtkInformation* info) override;
  int RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;

  /// Proxies bounding the surface this representation draws.
  void FitAutomaticProxies(vtkMultiProcessController* controller);

  int NumberOfAutomaticProxies = 32;
  vtkSmartPointer<vtkPolyData> Proxies;
  std::string GIStatus;
  // What the automatic proxies were fitted to.
  vtkDataObject* FittedInput = nullptr;
  vtkMTimeType FittedTime = 0;
  int FittedCount = -1;
  bool FittedConnected = false;

private:
  vtkPGISurfaceRepresentation(const vtkPGISurfaceRepresentation&) = delete;
  void operator=(const vtkPGISurfaceRepresentation&) = delete;
};

#endif
