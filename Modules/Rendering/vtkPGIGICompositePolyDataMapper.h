/**
 * @class   vtkPGIGICompositePolyDataMapper
 * @brief   vtkPGIGIPolyDataMapper's per-vertex GI for composite data: every
 *          polydata block receives light, the proxies cast the shadows.
 *
 * ParaView's surface representations draw through a
 * vtkCompositePolyDataMapper2 whose helpers each draw several blocks from
 * one vertex buffer. This mapper's helpers run the GI pass of
 * vtkPGIGIPolyDataMapper (the same implementation, pgiVertexGI.h) over the
 * blocks they draw, laid out as their vertex buffer lays them out. One bake
 * (proxies, light, planes, settings) serves all blocks and is rebuilt only
 * when one of those changes; a block's GI is recomputed when the block, the
 * bake, the actor matrix or the knobs change, so camera moves only re-render.
 *
 * The knobs, inputs and limits are vtkPGIGIPolyDataMapper's: proxies on
 * input port 1 (SetProxiesConnection or SetProxies, world coordinates; all
 * blocks share them, e.g. sphere proxies of the whole data set), SetLighting,
 * GetSettings/SetSettings, AddBlockerPlane, Exposure, SRGBOutput,
 * CombineWithVTKLighting, CaptureVisibility, AlwaysRecompute.
 */
#ifndef vtkPGIGICompositePolyDataMapper_h
#define vtkPGIGICompositePolyDataMapper_h

#include "ProxyGIRenderingModule.h"
#include "pgiVertexGI.h" // for the shared GPU implementation
#include "vtkCompositePolyDataMapper2.h"
#include "vtkPGIGIBake.h"
#include "vtkPGIGISettings.h"

#include <string>

class vtkFloatArray;
class vtkPGILighting;
class vtkPolyData;

class PROXYGIRENDERING_EXPORT vtkPGIGICompositePolyDataMapper : public vtkCompositePolyDataMapper2
{
public:
  static vtkPGIGICompositePolyDataMapper* New();
  vtkTypeMacro(vtkPGIGICompositePolyDataMapper, vtkCompositePolyDataMapper2);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  /// Sphere proxies for all blocks: points with a "Radius" point array.
  virtual void SetProxies(vtkPolyData* proxies);
  vtkPolyData* GetProxies();
  void SetProxiesConnection(vtkAlgorithmOutput* output) { this->SetInputConnection(1, output); }

  virtual void SetLighting(vtkPGILighting* lighting);
  vtkPGILighting* GetLighting() { return this->Scene.Lighting; }

  /// The GI knobs (never null); SetSettings(nullptr) restores a private default set.
  vtkPGIGISettings* GetSettings() { return this->Scene.Settings; }
  virtual void SetSettings(vtkPGIGISettings* settings);
  /// What this mapper honours (vtkPGIGIPolyDataMapper's).
  static const vtkPGIGISettings::Support& GetSupport();
  vtkPGIGIBake* GetBake() { return this->Scene.Bake; }

  /// Infinite planes blocking the half-space beneath them (at most 8).
  void AddBlockerPlane(const double origin[3], const double normal[3]);
  void AddBlockerPlane(const double origin[3], const double normal[3], const double albedo[3]);
  /// A plane of finite extent (vtkPGIGlobalIllumination::AddBlockerPlane):
  /// with PlaneBounceDirections > 0 it reflects from that area only.
  void AddBlockerPlane(const double origin[3], const double normal[3], const double albedo[3],
    const double halfEdge1[3], const double halfEdge2[3]);
  void RemoveAllBlockerPlanes();

  void SetGlobalIllumination(bool on);
  bool GetGlobalIllumination() const { return this->Options.GlobalIllumination; }
  vtkBooleanMacro(GlobalIllumination, bool);
  void SetExposure(double exposure);
  double GetExposure() const { return this->Options.Exposure; }
  void SetSRGBOutput(bool on);
  bool GetSRGBOutput() const { return this->Options.SRGBOutput; }
  vtkBooleanMacro(SRGBOutput, bool);
  void SetCombineWithVTKLighting(bool on);
  bool GetCombineWithVTKLighting() const { return this->Options.CombineWithVTKLighting; }
  vtkBooleanMacro(CombineWithVTKLighting, bool);
  void SetCaptureVisibility(bool on);
  bool GetCaptureVisibility() const { return this->Options.CaptureVisibility; }
  vtkBooleanMacro(CaptureVisibility, bool);
  void SetAlwaysRecompute(bool on);
  bool GetAlwaysRecompute() const { return this->Options.AlwaysRecompute; }
  vtkBooleanMacro(AlwaysRecompute, bool);

  /// The accuracy budget, as vtkPGIGIPolyDataMapper's (its receivers: every
  /// block's points).
  void SetErrorBudget(double fraction);
  double GetErrorBudget() const { return this->Scene.ErrorBudget; }
  void SetTimeBudget(double seconds);
  double GetTimeBudget() const { return this->Scene.TimeBudget; }
  void SetBudgetModelFileName(const char* fileName);
  const char* GetBudgetModelFileName() const { return this->Scene.BudgetModelFileName.c_str(); }

  vtkMTimeType GetMTime() override;
  void Render(vtkRenderer* ren, vtkActor* act) override;

  /**
   * The last GI pass's results for one block (a polydata of the input), in
   * its point order; false if the block was not drawn yet.
   */
  bool GetPerVertexResults(
    vtkPolyData* block, vtkFloatArray* radiance, vtkFloatArray* visibility = nullptr);

  /// GI passes run by all helpers together.
  vtkGetMacro(NumberOfGIUpdates, int);
  /// What the last frame did and why (one line per helper, joined by " | ").
  std::string GetGIStatus();

protected:
  vtkPGIGICompositePolyDataMapper();
  ~vtkPGIGICompositePolyDataMapper() override;

  int FillInputPortInformation(int port, vtkInformation* info) override;
  vtkCompositeMapperHelper2* CreateHelper() override;

  proxygi::gpu::MapperScene Scene;
  proxygi::gpu::VertexGIOptions Options;
  bool BakeReady = false;
  int NumberOfGIUpdates = 0;

private:
  friend class vtkPGIGICompositeMapperHelper;
  vtkPGIGICompositePolyDataMapper(const vtkPGIGICompositePolyDataMapper&) = delete;
  void operator=(const vtkPGIGICompositePolyDataMapper&) = delete;
};

#endif
