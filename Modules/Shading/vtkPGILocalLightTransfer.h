/**
 * @class   vtkPGILocalLightTransfer
 * @brief   Precomputed transfer of local point lights (a light cloud):
 *          what vtkPGIGlobalIllumination calls for the point lights'
 *          indirect light when the settings' LightCloud is on.
 *
 * An interface, so that the shading does not depend on how the transfer is
 * stored: vtkPGILightCloudTransfer (ProxyGI::LightCloud) implements it with
 * a light cloud (Kristensen et al. 2005). The GI filter passes the
 * lighting's point lights and its receivers; the transfer adds their exit
 * radiance to a per-receiver RGB array and says what it ran in the plan.
 */
#ifndef vtkPGILocalLightTransfer_h
#define vtkPGILocalLightTransfer_h

#include "ProxyGIShadingModule.h"
#include "vtkObject.h"
#include "vtkPGILighting.h" // for the point lights

#include <string>
#include <vector>

class vtkPolyData;

class PROXYGISHADING_EXPORT vtkPGILocalLightTransfer : public vtkObject
{
public:
  vtkTypeMacro(vtkPGILocalLightTransfer, vtkObject);
  void PrintSelf(ostream& os, vtkIndent indent) override;

#ifndef __VTK_WRAP__
  /**
   * Adds the transferred light of `lights` at the points of `receivers` to
   * `radiance` (RGB floats per point). Appends plan lines (what ran, lights
   * skipped and why, reused or recomputed). False, with the reason in
   * `why`, when the transfer cannot serve these receivers or lights.
   */
  virtual bool AddLight(vtkPolyData* receivers,
    const std::vector<vtkPGILighting::PointLight>& lights, float* radiance,
    std::vector<std::string>& plan, std::string& why) = 0;
#endif
  /// Whether the transferred light includes the lights' direct light.
  virtual bool CarriesDirectLight() = 0;

protected:
  vtkPGILocalLightTransfer() = default;
  ~vtkPGILocalLightTransfer() override = default;

private:
  vtkPGILocalLightTransfer(const vtkPGILocalLightTransfer&) = delete;
  void operator=(const vtkPGILocalLightTransfer&) = delete;
};

#endif
