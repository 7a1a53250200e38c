/**
 * @file pgiVertexGI.h
 * @brief Per-vertex GI on the GPU, the one implementation behind
 * vtkPGIGIPolyDataMapper and the helpers of vtkPGIGICompositePolyDataMapper.
 *
 * A VertexGI belongs to one vtkOpenGLPolyDataMapper (the plain GI mapper, or
 * one composite helper drawing several blocks from one vertex buffer). Given
 * the receivers as blocks laid out in that buffer and an up-to-date
 * vtkPGIGIBake, Update() runs the GI pass (transform feedback, one GL point
 * per vertex) when anything it depends on changed; the surface shader then
 * reads the captured radiance as the attribute pgiRadianceMC, one value per
 * vertex of the mapper's buffer.
 */
#ifndef pgiVertexGI_h
#define pgiVertexGI_h

#include "ProxyGIRenderingModule.h"
#include "pgiAccuracyBudget.h" // for budget::Planner

#include "vtkIndent.h"
#include "vtkPGIGISettings.h"
#include "vtkShader.h"
#include "vtkType.h"

#include <map>
#include <memory>
#include <string>
#include <vector>

class vtkActor;
class vtkAlgorithm;
class vtkFloatArray;
class vtkPGILighting;
class vtkObject;
class vtkOpenGLHelper;
class vtkOpenGLRenderWindow;
class vtkPGIGIBake;
class vtkPolyData;
class vtkRenderer;
class vtkWindow;

namespace proxygi
{
namespace gpu
{

/// The GI mapper knobs that are not GI settings (see vtkPGIGIPolyDataMapper).
struct VertexGIOptions
{
  bool GlobalIllumination = true;
  double Exposure = 1.0;
  bool SRGBOutput = true;
  bool CombineWithVTKLighting = false;
  bool CaptureVisibility = false;
  bool AlwaysRecompute = false;
};

/// One receiver mesh whose points are vertices [Start, Start + points) of
/// the mapper's vertex buffer.
struct ReceiverBlock
{
  vtkPolyData* Data = nullptr;
  vtkIdType Start = 0;
};

/**
 * What both GI mappers hold besides their GPU state: the light, the settings
 * (own or shared), the effective settings and the bake built from them.
 */
class PROXYGIRENDERING_EXPORT MapperScene
{
public:
  explicit MapperScene(vtkObject* owner);
  ~MapperScene();
  MapperScene(const MapperScene&) = delete;
  MapperScene& operator=(const MapperScene&) = delete;

  /// Each returns whether anything changed (the owner then calls Modified).
  bool SetLighting(vtkPGILighting* lighting);
  bool SetSettings(vtkPGIGISettings* settings);
  /// halfEdges (6, null: unbounded): the plane's extent (vtkPGIGIBake).
  bool AddBlockerPlane(const double origin[3], const double normal[3], const double albedo[3],
    const double* halfEdges = nullptr);
  void RemoveAllBlockerPlanes();

  /// The proxies on input port 1 of `mapper`, brought up to date (a mapper's
  /// render updates port 0 only).
  static vtkPolyData* ProxiesOf(vtkAlgorithm* mapper);
  /// What the GPU mappers honour.
  static const vtkPGIGISettings::Support& Support();
  /// Brings the bake up to date for Support() and, with a budget, the
  /// knobs it chooses for `receivers` points; false on error.
  bool PrepareBake(vtkPolyData* proxies, double receivers);
  /// The mappers' SetErrorBudget / SetTimeBudget / SetBudgetModelFileName.
  bool SetBudget(double errorBudget, double timeBudget, const std::string& modelFile);
  /// Appends the budget's line (if any) to a status.
  std::string WithBudget(const std::string& status) const;
  vtkMTimeType GetMTime(vtkMTimeType ownerTime) const;
  void PrintSelf(ostream& os, vtkIndent indent, const VertexGIOptions& options) const;

  vtkObject* Owner;
  vtkPGILighting* Lighting = nullptr;
  vtkPGIGISettings* Settings = nullptr;
  vtkPGIGISettings* Effective = nullptr;
  vtkPGIGIBake* Bake = nullptr;
  std::vector<std::string> Notes;
  /// The accuracy budget (0: none); the settings with its knobs; its line.
  double ErrorBudget = 0.0, TimeBudget = 0.0;
  std::string BudgetModelFileName;
  proxygi::budget::Planner Planner;
  vtkPGIGISettings* Budgeted = nullptr;
  std::string BudgetLine, BudgetError, BudgetWarned; // warned once each
};

class PROXYGIRENDERING_EXPORT VertexGI
{
public:
  static constexpr int MaxLocalLights = 16;

  VertexGI();
  ~VertexGI();
  VertexGI(const VertexGI&) = delete;
  VertexGI& operator=(const VertexGI&) = delete;

  /**
   * Runs the GI pass if anything it depends on changed (receivers, bake,
   * actor matrix, settings, program); false if GI is off or failed. `bake`
   * must be up to date (UpdateFor succeeded); `notes` are its "not
   * honoured" lines. `vertices` is the size of the mapper's vertex buffer.
   * Errors go to `owner`.
   */
  bool Update(vtkObject* owner, vtkOpenGLRenderWindow* window, vtkActor* actor,
    const std::vector<ReceiverBlock>& blocks, vtkIdType vertices, vtkPGIGIBake* bake,
    const std::vector<std::string>& notes, const VertexGIOptions& options);

  /// Whether the surface shader takes the GI code (the last Update's result).
  bool InShaders() const;
  /// When InShaders last changed: shaders built before it are rebuilt.
  vtkMTimeType GetShaderModeTime() const;
  /// Sets InShaders, e.g. false when the bake failed before Update ran.
  void SetInShaders(bool gi);

  /// The surface shader: before and after the mapper's own ReplaceShaderValues.
  void ReplaceShaderValuesBefore(std::map<vtkShader::Type, vtkShader*>& shaders) const;
  void ReplaceShaderValuesAfter(std::map<vtkShader::Type, vtkShader*>& shaders) const;
  /// Binds the results to the surface program and sets its uniforms.
  void SetShaderParameters(
    vtkObject* owner, vtkOpenGLHelper& cellBO, const VertexGIOptions& options) const;

  /**
   * The last pass's results for `count` vertices from `start` of the
   * buffer: radiance (3 components) and, when captured, the visibility.
   */
  bool GetResults(
    vtkIdType start, vtkIdType count, vtkFloatArray* radiance, vtkFloatArray* visibility) const;
  vtkIdType GetNumberOfVertices() const;

  int GetNumberOfUpdates() const { return this->Updates; }
  const std::string& GetStatus() const { return this->Status; }
  /// Whether the last GI pass ran past llvmpipe's loop limit (its results
  /// may be cut short; the status says so).
  bool GetCutShort() const { return this->CutShort; }
  void SetStatus(const std::string& status) { this->Status = status; }

  void ReleaseGraphicsResources(vtkWindow* window);

private:
  void UploadBake(vtkObject* owner, vtkOpenGLRenderWindow* window, vtkPGIGIBake* bake);
  void UploadReceivers(vtkPGIGIBake* bake, const std::vector<ReceiverBlock>& blocks,
    vtkIdType vertices, std::string& why);
  bool RunGIPass(vtkObject* owner, vtkOpenGLRenderWindow* window, vtkPGIGIBake* bake,
    int visibilityVec4s, bool resize);
  void ComposeStatus(vtkObject* owner, vtkPGIGIBake* bake, const std::string& reasons,
    const std::vector<std::string>& notes, const VertexGIOptions& options);

  struct Internals;
  std::unique_ptr<Internals> GPU;
  int Updates = 0;
  bool CutShort = false;
  std::string Status;
};

} // namespace gpu
} // namespace proxygi

// The members both GI mappers define alike (their classes derive from
// different VTK mappers): input port 1, the scene's setters, the options.
// The options are not GI settings: changing one re-renders, never re-bakes.
#define pgiGIMapperOption(cls, Name, Type)                                                         \
  void cls::Set##Name(Type value)                                                                  \
  {                                                                                                \
    if (this->Options.Name != value)                                                               \
    {                                                                                              \
      this->Options.Name = value;                                                                  \
      this->Modified();                                                                            \
    }                                                                                              \
  }

#define pgiGIMapperCommonMembers(cls)                                                              \
  void cls::SetProxies(vtkPolyData* proxies)                                                       \
  {                                                                                                \
    this->SetInputDataObject(1, proxies);                                                          \
  }                                                                                                \
                                                                                                   \
  vtkPolyData* cls::GetProxies()                                                                   \
  {                                                                                                \
    return proxygi::gpu::MapperScene::ProxiesOf(this);                                             \
  }                                                                                                \
                                                                                                   \
  void cls::SetLighting(vtkPGILighting* lighting)                                                  \
  {                                                                                                \
    if (this->Scene.SetLighting(lighting))                                                         \
    {                                                                                              \
      this->Modified();                                                                            \
    }                                                                                              \
  }                                                                                                \
                                                                                                   \
  void cls::SetSettings(vtkPGIGISettings* settings)                                                \
  {                                                                                                \
    if (this->Scene.SetSettings(settings))                                                         \
    {                                                                                              \
      this->Modified();                                                                            \
    }                                                                                              \
  }                                                                                                \
                                                                                                   \
  const vtkPGIGISettings::Support& cls::GetSupport()                                               \
  {                                                                                                \
    return proxygi::gpu::MapperScene::Support();                                                   \
  }                                                                                                \
                                                                                                   \
  vtkMTimeType cls::GetMTime()                                                                     \
  {                                                                                                \
    return this->Scene.GetMTime(this->Superclass::GetMTime());                                     \
  }                                                                                                \
                                                                                                   \
  void cls::AddBlockerPlane(const double origin[3], const double normal[3])                        \
  {                                                                                                \
    const double black[3] = { 0.0, 0.0, 0.0 };                                                     \
    this->AddBlockerPlane(origin, normal, black);                                                  \
  }                                                                                                \
                                                                                                   \
  void cls::AddBlockerPlane(                                                                       \
    const double origin[3], const double normal[3], const double albedo[3])                        \
  {                                                                                                \
    if (this->Scene.AddBlockerPlane(origin, normal, albedo))                                       \
    {                                                                                              \
      this->Modified();                                                                            \
    }                                                                                              \
  }                                                                                                \
                                                                                                   \
  void cls::AddBlockerPlane(const double origin[3], const double normal[3],                        \
    const double albedo[3], const double halfEdge1[3], const double halfEdge2[3])                  \
  {                                                                                                \
    const double halfEdges[6] = { halfEdge1[0], halfEdge1[1], halfEdge1[2], halfEdge2[0],          \
      halfEdge2[1], halfEdge2[2] };                                                                \
    if (this->Scene.AddBlockerPlane(origin, normal, albedo, halfEdges))                            \
    {                                                                                              \
      this->Modified();                                                                            \
    }                                                                                              \
  }                                                                                                \
                                                                                                   \
  void cls::RemoveAllBlockerPlanes()                                                               \
  {                                                                                                \
    this->Scene.RemoveAllBlockerPlanes();                                                          \
    this->Modified();                                                                              \
  }                                                                                                \
                                                                                                   \
  void cls::SetErrorBudget(double fraction)                                                        \
  {                                                                                                \
    if (this->Scene.SetBudget(fraction, this->Scene.TimeBudget, this->Scene.BudgetModelFileName))  \
    {                                                                                              \
      this->Modified();                                                                            \
    }                                                                                              \
  }                                                                                                \
                                                                                                   \
  void cls::SetTimeBudget(double seconds)                                                          \
  {                                                                                                \
    if (this->Scene.SetBudget(this->Scene.ErrorBudget, seconds, this->Scene.BudgetModelFileName))  \
    {                                                                                              \
      this->Modified();                                                                            \
    }                                                                                              \
  }                                                                                                \
                                                                                                   \
  void cls::SetBudgetModelFileName(const char* fileName)                                           \
  {                                                                                                \
    if (this->Scene.SetBudget(                                                                     \
          this->Scene.ErrorBudget, this->Scene.TimeBudget, fileName ? fileName : ""))              \
    {                                                                                              \
      this->Modified();                                                                            \
    }                                                                                              \
  }                                                                                                \
                                                                                                   \
  void cls::SetExposure(double exposure)                                                           \
  {                                                                                                \
    exposure = std::max(0.0, exposure);                                                            \
    if (this->Options.Exposure != exposure)                                                        \
    {                                                                                              \
      this->Options.Exposure = exposure;                                                           \
      this->Modified();                                                                            \
    }                                                                                              \
  }                                                                                                \
  pgiGIMapperOption(cls, GlobalIllumination, bool) pgiGIMapperOption(cls, SRGBOutput, bool)        \
    pgiGIMapperOption(cls, CombineWithVTKLighting, bool)                                           \
      pgiGIMapperOption(cls, CaptureVisibility, bool)                                              \
        pgiGIMapperOption(cls, AlwaysRecompute, bool)

#endif
