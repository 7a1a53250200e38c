/**
 * @class   vtkPGIImageSpaceGIView
 * @brief   ParaView's render view with vtkPGIImageSpaceGIPass as its render
 *          pass: image-space soft shadows and one-bounce light from sphere
 *          proxies on every opaque surface the view draws.
 *
 * As ParaView's vtkPVRenderViewWithEDL installs its pass, this view installs
 * the image-space GI pass on its synchronized renderers (each rank's pass
 * sees that rank's geometry). The proxies come from a pipeline source
 * (SetProxiesAlgorithm, e.g. Sphere Proxies) on the processes that render
 * (builtin sessions, pvbatch, a pvserver whose data and render servers are
 * one). The pass's knobs are forwarded; GetPass gives the pass itself.
 * Under MPI the proxies are all-gathered (vtkPGIGatherProxies) during the
 * view's Update, on every rank, so each rank's pass splats every rank's
 * spheres over its own geometry before IceT composites the pictures.
 */
#ifndef vtkPGIImageSpaceGIView_h
#define vtkPGIImageSpaceGIView_h

#include "ProxyGIParaViewRepresentationModule.h"
#include "vtkPVRenderView.h"

#include <string>

class vtkAlgorithm;
class vtkPGIGISettings;
class vtkPGIGatherProxies;
class vtkPGIImageSpaceGIPass;
class vtkPGILighting;

class PROXYGIPARAVIEWREPRESENTATION_EXPORT vtkPGIImageSpaceGIView : public vtkPVRenderView
{
public:
  static vtkPGIImageSpaceGIView* New();
  vtkTypeMacro(vtkPGIImageSpaceGIView, vtkPVRenderView);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  /// The proxies' source (its first output); null: no proxies.
  void SetProxiesAlgorithm(vtkAlgorithm* source);
  void SetSettings(vtkPGIGISettings* settings);
  void SetLighting(vtkPGILighting* lighting);
  void SetReceiverScale(int scale);
  void SetUpsampling(int upsampling);
  void SetExpansionFactor(double factor);
  void SetExposure(double exposure);
  /// What the last frame's pass ran and why.
  const char* GetGIStatus();

  vtkPGIImageSpaceGIPass* GetPass() { return this->Pass; }

  /// Brings the proxies up to date on every rank together (their gather is
  /// collective), so that the pass's render-time update needs no other rank:
  /// a rank with nothing to draw may skip the pass.
  void Update() override;

  /// Always 0: with a server, frames are drawn on its ranks, where the
  /// proxies and the light are (the client has neither).
  void SetRemoteRenderingThreshold(double) override;

protected:
  vtkPGIImageSpaceGIView();
  ~vtkPGIImageSpaceGIView() override;

  vtkPGIImageSpaceGIPass* Pass;
  vtkPGIGatherProxies* Gather;
  std::string GIStatus;

private:
  vtkPGIImageSpaceGIView(const vtkPGIImageSpaceGIView&) = delete;
  void operator=(const vtkPGIImageSpaceGIView&) = delete;
};

#endif
