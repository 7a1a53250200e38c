// The three ways proxygi draws a scene with GI, shared by `render` and
// `view`: the CPU filter's radiance as vertex colours, the GI mapper per
// object, and the image-space pass over plain mappers; and the exposure
// each of them is tone-mapped with.
#ifndef proxygiBackends_h
#define proxygiBackends_h

#include "pgiSceneSetup.h"
#include "vtkPGIGISettings.h" // Support
#include "vtkSmartPointer.h"

#include <string>
#include <vector>

class vtkPGIGIPolyDataMapper;
class vtkPGIImageSpaceGIPass;
class vtkPolyData;
class vtkRenderWindow;
class vtkRenderer;

namespace proxygi
{
namespace cli
{
/// What the backend a --mode names ("gpu", "vertex", "image-space") honours.
const vtkPGIGISettings::Support& BackendSupport(const std::string& mode);

/// The backend's own plane handling on `settings`: the image-space pass keeps
/// the planes in log space with no plane-bounce shadows (its defaults, so a
/// plain run has nothing to report); the others carry them in the light,
/// shadowed.
void SetBackendPlaneDefaults(vtkPGIGISettings* settings, const std::string& mode);

/// The automatic exposure (AutoExposure) of per-vertex "Radiance" arrays.
double AutomaticExposure(const std::vector<vtkSmartPointer<vtkPolyData>>& shaded);

/// `shaded`'s "Radiance" times `exposure` as sRGB bytes, the scalars of `display`
/// (a shallow copy of `shaded`).
void ColourByRadiance(vtkPolyData* shaded, double exposure, vtkPolyData* display);

/// One unlit actor per object drawing ColourByRadiance; returns the displayed data.
std::vector<vtkSmartPointer<vtkPolyData>> AddVertexColourActors(
  vtkRenderer* renderer, const std::vector<vtkSmartPointer<vtkPolyData>>& shaded, double exposure);

/// One GI mapper per object, all on `settings` (shared, not copied).
std::vector<vtkSmartPointer<vtkPGIGIPolyDataMapper>> AddGPUMappers(vtkRenderer* renderer,
  const std::vector<vtkSmartPointer<vtkPolyData>>& receivers, vtkPGIGISettings* settings,
  const LoadedScene& loaded, const SceneProxies& proxies, double exposure);

/// After a frame drew them: each GI mapper's per-vertex radiance read back,
/// as "Radiance" on a shallow copy of the mapper's input, appended to
/// `shaded`. False, with why, when a mapper's GI pass did not run.
bool ReadBackRadiance(const std::vector<vtkSmartPointer<vtkPGIGIPolyDataMapper>>& mappers,
  std::vector<vtkSmartPointer<vtkPolyData>>& shaded, std::string& error);
/// Seconds of one frame that recomputes GI (AlwaysRecompute for that frame).
double TimeGIFrame(
  vtkRenderWindow* window, const std::vector<vtkSmartPointer<vtkPGIGIPolyDataMapper>>& mappers);

/// The GI mappers of `receivers` run once in a fresh offscreen window of
/// `size` (the camera's): their radiance read back into `shaded` (cleared),
/// then one frame that recomputes GI timed, as the budget's mapper times
/// are. `cutShort`: llvmpipe's loop limit cut a GI pass short; `renderer`:
/// the window's GL renderer. False, with why, when no window or GI ran.
bool ShadeOnGPU(const std::vector<vtkSmartPointer<vtkPolyData>>& receivers,
  vtkPGIGISettings* settings, const LoadedScene& loaded, const SceneProxies& proxies,
  const int size[2], std::vector<vtkSmartPointer<vtkPolyData>>& shaded, double& frameSeconds,
  bool& cutShort, std::string& renderer, std::string& error);

/// Plain mappers (the albedo as diffuse colour) under `pass`, the renderer's pass.
void AddImageSpacePass(vtkRenderer* renderer, vtkPGIImageSpaceGIPass* pass,
  const SceneDescription& scene, const std::vector<vtkSmartPointer<vtkPolyData>>& receivers,
  vtkPGIGISettings* settings, const LoadedScene& loaded, const SceneProxies& proxies,
  int receiverScale, double exposure);

/// Image-space mode has no per-vertex radiance: AutoExposure of the
/// geometry pixels of a frame drawn at a low exposure, read back to
/// radiance. Sets it on the pass and returns it.
double ExposureFromPicture(vtkRenderWindow* window, vtkPGIImageSpaceGIPass* pass);
} // namespace cli
} // namespace proxygi

#endif
