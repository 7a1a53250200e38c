/**
 * @class   vtkPGILightCloudTransfer
 * @brief   A light cloud as the GI filter's transfer for point lights: the
 *          cloud is one more effect of vtkPGIGlobalIllumination, in its
 *          settings (LightCloud) and its plan.
 *
 * Give it the cloud (SetCloud) and hand it to
 * vtkPGIGlobalIllumination::SetLocalLightTransfer. Each update the GI
 * filter passes the lighting's point lights; this relights the receivers
 * with its vtkPGILightCloudRelight (GetRelight: occluder for visibility,
 * neighbours, fade, view point of glossy receivers) and the GI filter adds
 * the result as "IndirectLocal" to its Radiance. The direct light of the
 * point lights stays the GI filter's (LocalLights, soft shadows), so the
 * cloud must hold indirect light only.
 *
 * The plan (the GI filter's) says what ran: the cloud, the lights weighed,
 * a light outside the cloud (warned, direct light only), and whether the
 * light was reused (the point lights did not move: the relight filter does
 * not re-execute) or recomputed.
 */
#ifndef vtkPGILightCloudTransfer_h
#define vtkPGILightCloudTransfer_h

#include "ProxyGILightCloudModule.h"
#include "vtkNew.h" // for the relight filter
#include "vtkPGILightCloudRelight.h"
#include "vtkPGILocalLightTransfer.h"

class vtkPGILightCloud;

class PROXYGILIGHTCLOUD_EXPORT vtkPGILightCloudTransfer : public vtkPGILocalLightTransfer
{
public:
  static vtkPGILightCloudTransfer* New();
  vtkTypeMacro(vtkPGILightCloudTransfer, vtkPGILocalLightTransfer);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  virtual void SetCloud(vtkPGILightCloud* cloud);
  vtkGetObjectMacro(Cloud, vtkPGILightCloud);
  /// The relighting's knobs (its lights are set from the GI filter's).
  vtkPGILightCloudRelight* GetRelight() { return this->Relight; }

#ifndef __VTK_WRAP__
  bool AddLight(vtkPolyData* receivers, const std::vector<vtkPGILighting::PointLight>& lights,
    float* radiance, std::vector<std::string>& plan, std::string& why) override;
#endif
  bool CarriesDirectLight() override;
  /// How many times the cloud's light was recomputed (a static light reuses it).
  int GetNumberOfRelights() const
  {
    return this->Relights;
  }

  vtkMTimeType GetMTime() override;

protected:
  vtkPGILightCloudTransfer();
  ~vtkPGILightCloudTransfer() override;

  vtkPGILightCloud* Cloud = nullptr;
  vtkNew<vtkPGILightCloudRelight> Relight;
  int Relights = 0;

private:
  vtkPGILightCloudTransfer(const vtkPGILightCloudTransfer&) = delete;
  void operator=(const vtkPGILightCloudTransfer&) = delete;
};

#endif
