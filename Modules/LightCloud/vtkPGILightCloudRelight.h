/**
 * @class   vtkPGILightCloudRelight
 * @brief   Lights receivers from user point lights placed anywhere in a
 *          light cloud (Kristensen et al. 2005, section 6), on the CPU.
 *
 * Input 0: the receivers the cloud was computed for (the same points; the
 * filter checks the cloud's ReceiverKey). Input 1: a vtkPGILightCloud.
 * Output: the receivers with the RGB point array "LightCloudRadiance": the
 * exit radiance the user lights cause, as the cloud holds it (indirect only,
 * or direct and indirect: see the cloud's Contents).
 *
 * A glossy cloud (SH coefficients per colour, see vtkPGILightCloud) also
 * gives "LightCloudRadianceSH" (RGB per coefficient, world frame: a viewer
 * evaluates it at its direction, per fragment if it likes), and
 * "LightCloudRadiance" is it evaluated toward ViewPoint, or along each
 * receiver's normal while no view point is set.
 *
 * Per user light at l with intensity I (W/sr, RGB): the m = NeighborCount
 * nearest cloud lights (vtkStaticPointLocator) set r = RadiusScale times the
 * distance of the m-th; every cloud light j within r weighs
 * w_j = (1 - d_j / r)^4 times its visibility f_j, normalised, times I. The
 * paper's r is the m-th light's own distance; with that, a user light at the
 * centre of a grid cell has its m lights on one shell, all weighing almost
 * 0, and the normalised weights jump as it moves: RadiusScale > 1 keeps the
 * weights continuous everywhere. A user light on a cloud light (within 1e-6 of the
 * spacing: float positions) takes that light alone, whatever m.
 *
 * Visibility: with an Occluder (vtkPGIMeshOccluder of the scene's meshes),
 * only cloud lights visible from l count: VisibilityRays rays from l to
 * points around each cloud light, f_j the fraction that arrive, so a light
 * beside a thin wall does not light the far side. As l moves, a cloud light
 * that becomes hidden or visible fades over FadeTime seconds of the
 * filter's Time (the application's clock) instead of jumping; GetFading()
 * says a fade is under way (advance Time and update again). The normaliser
 * is at least 5% of the unweighted sum, so the last visible lights fade out
 * too. Without an occluder every light is visible.
 *
 * Several user lights add up (sum of their weight vectors). A user light
 * outside the cloud (farther than half the cloud's spacing beyond the cloud
 * lights' box) gets a warning and adds nothing: its direct light is the
 * soft-shadow route's. An unchanged light reuses the last result (the
 * pipeline does not re-execute).
 *
 * The field-data string array "Plan" says what ran: the cloud (dense or
 * compressed), the user lights and cloud lights weighed, and each user
 * light that was skipped and why (outside the cloud, nothing visible).
 * With no user lights the radiance is 0 and the plan says so.
 *
 * Errors: an empty cloud, receivers that are not the cloud's, a NaN/Inf
 * light position or intensity.
 */
#ifndef vtkPGILightCloudRelight_h
#define vtkPGILightCloudRelight_h

#include "ProxyGILightCloudModule.h"
#include "vtkPGILighting.h" // for SetLights
#include "vtkPolyDataAlgorithm.h"

#include "vtkSmartPointer.h"       // for the locators
#include "vtkStaticPointLocator.h" // for the locators

#include <map>
#include <string>
#include <utility>
#include <vector>

class vtkPGILightCloud;
class vtkPGIOccluder;

class PROXYGILIGHTCLOUD_EXPORT vtkPGILightCloudRelight : public vtkPolyDataAlgorithm
{
public:
  static vtkPGILightCloudRelight* New();
  vtkTypeMacro(vtkPGILightCloudRelight, vtkPolyDataAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  /// A user point light; returns its index.
  int AddLight(double x, double y, double z, double r, double g, double b);
  void SetLightPosition(int index, double x, double y, double z);
  void SetLightIntensity(int index, double r, double g, double b);
  void RemoveAllLights();
#ifndef __VTK_WRAP__
  /// All user lights at once (a lighting's point lights), changing only
  /// what differs: equal lights leave the filter unmodified.
  void SetLights(const std::vector<vtkPGILighting::PointLight>& lights);
#endif
  int GetNumberOfLights() const
  {
    return static_cast<int>(this->Lights.size());
  }
  /// User light `index`'s position and intensity (null for no such light).
  const double* GetLightPosition(int index) const
  {
    return index >= 0 && index < this->GetNumberOfLights() ? this->Lights[index].Position : nullptr;
  }
  const double* GetLightIntensity(int index) const
  {
    return index >= 0 && index < this->GetNumberOfLights() ? this->Lights[index].Intensity
                                                           : nullptr;
  }

  /// Where glossy receivers are seen from (a camera position).
  void SetViewPoint(double x, double y, double z);
  void SetViewPoint(const double p[3])
  {
    this->SetViewPoint(p[0], p[1], p[2]);
  }
  const double* GetViewPoint() const
  {
    return this->ViewPoint;
  }
  void RemoveViewPoint();
  bool HasViewPoint() const
  {
    return this->ViewPointSet;
  }

  vtkSetClampMacro(NeighborCount, int, 1, 4096);
  vtkGetMacro(NeighborCount, int);
  vtkSetClampMacro(RadiusScale, double, 1.0, 100.0);
  vtkGetMacro(RadiusScale, double);

  virtual void SetOccluder(vtkPGIOccluder* occluder);
  vtkGetObjectMacro(Occluder, vtkPGIOccluder);
  vtkSetClampMacro(VisibilityRays, int, 1, 64);
  vtkGetMacro(VisibilityRays, int);
  /// Seconds a cloud light takes to fade in or out (0: at once).
  vtkSetClampMacro(FadeTime, double, 0.0, VTK_DOUBLE_MAX);
  vtkGetMacro(FadeTime, double);
  /// The application's clock, seconds; the fade advances with it.
  vtkSetMacro(Time, double);
  vtkGetMacro(Time, double);
  /// Whether the last update left a fade under way.
  vtkGetMacro(Fading, bool);
  /// Forgets the fade state (the next update starts from the targets).
  void ResetFade();

  /// The last update: user lights outside the cloud, cloud lights used.
  vtkGetMacro(LightsOutside, int);
  vtkGetMacro(CloudLightsUsed, int);

  void SetCloudConnection(vtkAlgorithmOutput* output)
  {
    this->SetInputConnection(1, output);
  }
  void SetCloudData(vtkDataObject* cloud)
  {
    this->SetInputData(1, cloud);
  }

  vtkMTimeType GetMTime() override;

#ifndef __VTK_WRAP__
  /**
   * One frame's light, before the per-receiver sums: what this filter and
   * the GPU mapper (vtkPGILightCloudPolyDataMapper) share. Dense cloud: the
   * cloud lights weighed and their RGB weights w_t (summed over the user
   * lights). Compressed: per zone (empty where no cloud light of it is
   * weighed), x_m = Xbar w_t for each PCA cluster, then b_i = B_i w_t for
   * each basis vector, Stride values each; a receiver's light is then
   * x_m + sum_i z_i b_i.
   */
  struct Frame
  {
    int Stride = 0; // values per receiver (vtkPGILightCloud::GetValuesPerReceiver)
    bool Compressed = false;
    std::vector<vtkIdType> DenseLights;
    std::vector<double> DenseWeights; // RGB per entry of DenseLights
    std::vector<std::vector<double>> ZoneVectors;
    std::vector<std::string> Plan; // what ran and why, one line each
  };
  /**
   * Checks the receivers and cloud (vtkErrorMacro and false when bad),
   * weighs the cloud lights for the user lights (visibility, fade) and fills
   * `frame`. Advances the fade: call it once per frame.
   */
  bool PrepareFrame(vtkPolyData* receivers, vtkPGILightCloud* cloud, Frame& frame);
#endif

protected:
  vtkPGILightCloudRelight();
  ~vtkPGILightCloudRelight() override;

  int FillInputPortInformation(int port, vtkInformation* info) override;
  int RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;

  struct UserLight
  {
    double Position[3];
    double Intensity[3];
  };
  std::vector<UserLight> Lights;
  double ViewPoint[3] = { 0.0, 0.0, 0.0 };
  bool ViewPointSet = false;
  int NeighborCount = 8;
  double RadiusScale = 1.5;
  vtkPGIOccluder* Occluder = nullptr;
  int VisibilityRays = 4;
  double FadeTime = 0.25;
  double Time = 0.0;
  bool Fading = false;
  int LightsOutside = 0;
  int CloudLightsUsed = 0;

  // The normalised weights of the lights of one set (the dense cloud's or
  // a zone's, found by `locator`) for user light k; false when none of
  // them is visible. Reads Fade[k], writes NextFade[k] (keys fadeKey + id).
  bool WeighLights(int k, vtkStaticPointLocator* locator, double spacing, double fadeStep,
    vtkIdType fadeKey, std::vector<std::pair<vtkIdType, double>>& weights);

  // Per user light: (set << 32) + cloud light -> visibility weight (the fade).
  std::vector<std::map<vtkIdType, double>> Fade, NextFade;
  std::vector<vtkSmartPointer<vtkStaticPointLocator>> Locators;
  const void* LocatorCloud = nullptr;
  vtkMTimeType LocatorTime = 0;
  double FadeClock = 0.0;
  bool FadeStarted = false;
  const void* FadeCloud = nullptr;

private:
  vtkPGILightCloudRelight(const vtkPGILightCloudRelight&) = delete;
  void operator=(const vtkPGILightCloudRelight&) = delete;
};

#endif
