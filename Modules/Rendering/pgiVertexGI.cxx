#include "pgiVertexGI.h"

#include "pgiGIComputeFS.h"
#include "pgiGIComputeVS.h"
#include "pgiGIMapperFS.h"
#include "pgiGIMapperFSImpl.h"
#include "pgiGIMapperVS.h"
#include "pgiGIMapperVSImpl.h"
#include "pgiGIShaders.h"
#include "pgiSRGBGLSL.h"

#include "pgiMaterial.h"
#include "pgiPlaneLightMap.h"
#include "pgiSphericalLights.h"
#include "vtkPGIGIBake.h"
#include "vtkPGIGISettings.h"
#include "vtkPGILighting.h"

#include "vtkActor.h"
#include "vtkAlgorithm.h"
#include "vtkAlgorithmOutput.h"
#include "vtkDataArray.h"
#include "vtkFloatArray.h"
#include "vtkMatrix3x3.h"
#include "vtkMatrix4x4.h"
#include "vtkNew.h"
#include "vtkOpenGLBufferObject.h"
#include "vtkOpenGLHelper.h"
#include "vtkOpenGLRenderWindow.h"
#include "vtkOpenGLShaderCache.h"
#include "vtkOpenGLVertexArrayObject.h"
#include "vtkPolyData.h"
#include "vtkShaderProgram.h"
#include "vtkSmartPointer.h"
#include "vtkTextureObject.h"
#include "vtkTimeStamp.h"
#include "vtkTransformFeedback.h"
#include "vtk_glew.h"

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstring>
#include <sstream>

namespace proxygi
{
namespace gpu
{

struct VertexGI::Internals
{
  GIResources Resources;
  vtkOpenGLRenderWindow* Window = nullptr;
  // Receivers (positions, normals, albedo: 9 floats per vertex) and results.
  vtkNew<vtkOpenGLBufferObject> Receivers;
  vtkNew<vtkOpenGLBufferObject> Results;
  vtkNew<vtkOpenGLVertexArrayObject> VAO;
  vtkSmartPointer<vtkTransformFeedback> Capture;
  std::string CaptureKey;
  vtkIdType Points = 0;
  int ResultFloats = 0; // per vertex
  bool HaveResults = false;
  // What the last GI pass used, to skip it when nothing changed.
  vtkMTimeType BakeUploaded = 0, SettingsTime = 0;
  std::string ReceiversKey; // the blocks, their times and the albedo knobs
  std::array<double, 16> Matrix{};
  int UploadedOrder = 0;
  int ProxyCount = 0, PlaneCount = 0;
  int ProgramHandle = 0;
  bool GIInShaders = false;
  vtkTimeStamp ShaderModeTime;
  // From the bake, as the GLSL reads them.
  bool PlanesInLight = false;
  std::vector<float> PlaneVisibility, Response, Albedos, PlaneAlbedos;
  vtkSmartPointer<vtkTextureObject> ProxyAlbedo;
  // The planes' light maps (PlaneBounceDirections > 0), rebuilt with the bake.
  std::vector<PlaneLightMap> PlaneMaps;
  PlaneLightMapsGL PlaneMapsGL;
  double PlaneMapMs = 0.0;
  // Local lights: centre and radius (-1: point light), radiance.
  std::vector<float> LocalLights, LocalRadiance;
  int SphericalLightCount = 0;
  std::string SphericalLightSummary;
  bool WarnedBudget = false;
};

namespace
{
// One transform-feedback description per set of captured outputs, shared by
// all mappers: the shader cache relinks a program whenever it is handed a
// different vtkTransformFeedback object, and mappers of the same order share
// their compute program.
vtkTransformFeedback* SharedCapture(int visibilityVec4s)
{
  static std::map<int, vtkSmartPointer<vtkTransformFeedback>> captures;
  vtkSmartPointer<vtkTransformFeedback>& capture = captures[visibilityVec4s];
  if (!capture)
  {
    capture = vtkSmartPointer<vtkTransformFeedback>::New();
    capture->AddVarying(vtkTransformFeedback::Color_RGBA_F, "pgiRadiance");
    for (int k = 0; k < visibilityVec4s; ++k)
    {
      capture->AddVarying(vtkTransformFeedback::Color_RGBA_F, "pgiVisibility" + std::to_string(k));
    }
  }
  return capture;
}
} // namespace

MapperScene::MapperScene(vtkObject* owner)
  : Owner(owner)
  , Settings(vtkPGIGISettings::New())
  , Effective(vtkPGIGISettings::New())
  , Bake(vtkPGIGIBake::New())
  , Budgeted(vtkPGIGISettings::New())
{
  this->Bake->SetSettings(this->Effective);
}

MapperScene::~MapperScene()
{
  this->SetLighting(nullptr);
  this->Settings->UnRegister(this->Owner);
  this->Effective->Delete();
  this->Bake->Delete();
  this->Budgeted->Delete();
}

bool MapperScene::SetLighting(vtkPGILighting* lighting)
{
  if (lighting == this->Lighting)
  {
    return false;
  }
  if (lighting)
  {
    lighting->Register(this->Owner);
  }
  if (this->Lighting)
  {
    this->Lighting->UnRegister(this->Owner);
  }
  this->Lighting = lighting;
  return true;
}

bool MapperScene::SetSettings(vtkPGIGISettings* settings)
{
  return vtkPGIGISettings::Share(this->Owner, this->Settings, settings);
}

bool MapperScene::AddBlockerPlane(
  const double origin[3], const double normal[3], const double albedo[3], const double* halfEdges)
{
  if (this->Bake->GetNumberOfBlockerPlanes() >= MaxPlanes)
  {
    vtkErrorWithObjectMacro(this->Owner, "At most " << MaxPlanes << " blocker planes.");
    return false;
  }
  this->Bake->AddBlockerPlane(origin, normal, albedo, halfEdges);
  return true;
}

void MapperScene::RemoveAllBlockerPlanes()
{
  this->Bake->RemoveAllBlockerPlanes();
}

vtkPolyData* MapperScene::ProxiesOf(vtkAlgorithm* mapper)
{
  if (mapper->GetNumberOfInputConnections(1) == 0)
  {
    return nullptr;
  }
  vtkAlgorithmOutput* connection = mapper->GetInputConnection(1, 0);
  if (connection && connection->GetProducer())
  {
    connection->GetProducer()->Update(connection->GetIndex());
  }
  return vtkPolyData::SafeDownCast(mapper->GetInputDataObject(1, 0));
}

const vtkPGIGISettings::Support& MapperScene::Support()
{
  static const vtkPGIGISettings::Support support = KernelSupport("GPU mapper", MaxOrder);
  return support;
}

bool MapperScene::SetBudget(double errorBudget, double timeBudget, const std::string& modelFile)
{
  if (errorBudget == this->ErrorBudget && timeBudget == this->TimeBudget &&
    modelFile == this->BudgetModelFileName)
  {
    return false;
  }
  this->ErrorBudget = errorBudget;
  this->TimeBudget = timeBudget;
  this->BudgetModelFileName = modelFile;
  return true;
}

std::string MapperScene::WithBudget(const std::string& status) const
{
  return this->BudgetLine.empty() ? status : status + "; " + this->BudgetLine;
}

bool MapperScene::PrepareBake(vtkPolyData* proxies, double receivers)
{
  this->Bake->SetProxies(proxies);
  this->Bake->SetLighting(this->Lighting);
  vtkPGIGISettings* requested = this->Settings;
  this->BudgetLine.clear();
  const auto b = budget::Budget::FromSetters(this->ErrorBudget, this->TimeBudget);
  if (b.Any())
  {
    // The user's settings stay as set; the budget's knobs go on a copy.
    vtkNew<vtkPGIGISettings> chosen;
    chosen->DeepCopy(this->Settings);
    budget::Choice choice;
    std::string error;
    if (this->Planner.Plan(this->BudgetModelFileName, budget::Route::Mapper, proxies, receivers,
          false, this->Lighting, b, chosen, choice, this->BudgetLine, error))
    {
      const char* gl = reinterpret_cast<const char*>(glGetString(GL_RENDERER));
      std::string why;
      if (gl && !budget::MapperTimesApply(this->Planner.GetModel(), gl, why))
      {
        this->BudgetLine += "; its times do not hold here: " + why;
      }
      // DeepCopy sets knob by knob: Budgeted changes only with the choice.
      this->Budgeted->DeepCopy(chosen);
      if (!choice.Valid && choice.Reason != this->BudgetWarned)
      {
        vtkWarningWithObjectMacro(this->Owner, << "Budget: " << choice.Reason << ".");
      }
      this->BudgetWarned = choice.Valid ? std::string() : choice.Reason;
      requested = this->Budgeted;
      this->BudgetError.clear();
    }
    else
    {
      if (error != this->BudgetError)
      {
        vtkErrorWithObjectMacro(this->Owner, << error << "; the settings as set instead.");
      }
      this->BudgetError = error;
      this->BudgetLine = error + "; the settings as set instead";
    }
  }
  return this->Bake->UpdateFor(this->Owner, requested, Support(), this->Notes);
}

vtkMTimeType MapperScene::GetMTime(vtkMTimeType ownerTime) const
{
  vtkMTimeType t = std::max(ownerTime, this->Settings->GetMTime());
  return this->Lighting ? std::max(t, this->Lighting->GetMTime()) : t;
}

void MapperScene::PrintSelf(ostream& os, vtkIndent indent, const VertexGIOptions& options) const
{
  os << indent << "Lighting: " << this->Lighting << "\n";
  os << indent << "BlockerPlanes: " << this->Bake->GetNumberOfBlockerPlanes() << "\n";
  os << indent << "Settings:\n";
  this->Settings->PrintSelf(os, indent.GetNextIndent());
  os << indent << "GlobalIllumination: " << options.GlobalIllumination << "\n";
  os << indent << "Exposure: " << options.Exposure << "\n";
  os << indent << "SRGBOutput: " << options.SRGBOutput << "\n";
  os << indent << "CombineWithVTKLighting: " << options.CombineWithVTKLighting << "\n";
  os << indent << "CaptureVisibility: " << options.CaptureVisibility << "\n";
  os << indent << "AlwaysRecompute: " << options.AlwaysRecompute << "\n";
  os << indent << "ErrorBudget: " << this->ErrorBudget << "\n";
  os << indent << "TimeBudget: " << this->TimeBudget << "\n";
  os << indent << "BudgetModelFileName: "
     << (this->BudgetModelFileName.empty() ? "(the model that ships)" : this->BudgetModelFileName)
     << "\n";
}

VertexGI::VertexGI()
  : GPU(new Internals)
{
}

VertexGI::~VertexGI() = default;

bool VertexGI::InShaders() const
{
  return this->GPU->GIInShaders;
}

vtkMTimeType VertexGI::GetShaderModeTime() const
{
  return this->GPU->ShaderModeTime.GetMTime();
}

void VertexGI::SetInShaders(bool gi)
{
  if (gi != this->GPU->GIInShaders)
  {
    this->GPU->GIInShaders = gi;
    this->GPU->ShaderModeTime.Modified();
  }
}

vtkIdType VertexGI::GetNumberOfVertices() const
{
  return this->GPU->HaveResults ? this->GPU->Points : 0;
}

void VertexGI::ReleaseGraphicsResources(vtkWindow* window)
{
  Internals& g = *this->GPU;
  g.Resources.ReleaseGraphicsResources(window);
  g.Receivers->ReleaseGraphicsResources();
  g.Results->ReleaseGraphicsResources();
  g.VAO->ReleaseGraphicsResources();
  g.Capture = nullptr;
  g.ProgramHandle = 0;
  g.CaptureKey.clear();
  g.HaveResults = false;
  if (g.ProxyAlbedo)
  {
    g.ProxyAlbedo->ReleaseGraphicsResources(window);
    g.ProxyAlbedo = nullptr;
  }
  FreePlaneLightMaps(window, g.PlaneMapsGL);
  g.Window = nullptr;
  g.ReceiversKey.clear();
  g.UploadedOrder = 0;
}

void VertexGI::UploadBake(vtkObject* owner, vtkOpenGLRenderWindow* window, vtkPGIGIBake* bake)
{
  Internals& g = *this->GPU;
  const BakedScene& b = bake->GetScene();
  if (bake->GetBuildTime() == g.BakeUploaded && g.UploadedOrder == b.Order && g.ProxyAlbedo)
  {
    return;
  }
  const int n2 = b.Order * b.Order;
  const double* light = b.Light.data();
  g.Resources.SetLight(light, light + n2, light + 2 * n2);
  const double* above = b.LightAbovePlanes.data();
  if (b.PlanesInLight)
  {
    g.Resources.SetLightAbovePlanes(above, above + n2, above + 2 * n2);
  }
  else
  {
    g.Resources.SetLightAbovePlanes(nullptr, nullptr, nullptr);
  }
  g.PlanesInLight = b.PlanesInLight;
  g.PlaneVisibility.assign(b.PlaneVisibility.begin(), b.PlaneVisibility.end());
  g.Response = b.InterleavedResponse;
  g.Resources.SetBlockers(PackSpheres(b.SceneBlockers), PackPlanes(b.SceneBlockers));
  g.ProxyCount = static_cast<int>(b.SceneBlockers.Spheres());
  g.PlaneCount = static_cast<int>(b.SceneBlockers.Planes());
  g.PlaneAlbedos = PackPlaneAlbedos(b.SceneBlockers);
  UploadProxyAlbedos(window, b.SceneBlockers, g.Albedos, g.ProxyAlbedo);

  // The planes' light maps, built on the CPU as the GI filter builds them
  // (no bright lights here: the whole map is in the SH).
  vtkPGIGISettings* settings = bake->GetSettings();
  const int directions = settings->GetPlaneBounceDirections();
  g.PlaneMaps.clear();
  if (directions > 0 && settings->GetIndirect() && settings->GetPlaneBounceShadows() &&
    g.PlaneCount > 0 && g.PlaneCount <= MaxPlanes && !b.Dark)
  {
    const auto start = std::chrono::steady_clock::now();
    const SoftShadows shadows(b.Kernel);
    PlaneLightMapShading how;
    how.Shadows = &shadows;
    how.MinAngle = static_cast<float>(settings->GetMinBlockerAngle());
    BuildPlaneLightMaps(b, how, directions, g.PlaneMaps);
    g.PlaneMapMs =
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  }
  UploadPlaneLightMaps(window, g.PlaneMaps, g.PlaneMapsGL);

  // The shadowed bounce's spherical lights after the bake's first pass.
  g.SphericalLightCount = b.RunShadowed ? static_cast<int>(b.Lights.Count()) : 0;
  g.SphericalLightSummary = b.SphericalLightsSummary;
  g.Resources.SetSphericalLights(b.RunShadowed ? &b.Lights : nullptr,
    bake->GetSettings()->GetSphericalLightBlocking() == vtkPGIGISettings::BLOCKING_PER_OBJECT);

  // Local lights as pgiLocalLights reads them: radius -1 for a point light.
  g.LocalLights.clear();
  g.LocalRadiance.clear();
  const std::size_t lights = b.Locals.Count();
  for (std::size_t k = 0; k < lights && k < static_cast<std::size_t>(MaxLocalLights); ++k)
  {
    g.LocalLights.insert(g.LocalLights.end(),
      { b.Locals.X[k], b.Locals.Y[k], b.Locals.Z[k], b.Locals.Point[k] ? -1.0f : b.Locals.R[k] });
    g.LocalRadiance.insert(
      g.LocalRadiance.end(), &b.Locals.Radiance[3 * k], &b.Locals.Radiance[3 * k] + 3);
  }
  if (lights > static_cast<std::size_t>(MaxLocalLights))
  {
    vtkErrorWithObjectMacro(owner,
      "At most " << MaxLocalLights << " local lights on the GPU; " << lights << " given, the first "
                 << MaxLocalLights << " used.");
  }
  g.Resources.SetAnalyticLightTable(!g.LocalLights.empty());
  g.BakeUploaded = bake->GetBuildTime();
  g.UploadedOrder = b.Order;
}

void VertexGI::UploadReceivers(vtkPGIGIBake* bake, const std::vector<ReceiverBlock>& blocks,
  vtkIdType vertices, std::string& why)
{
  Internals& g = *this->GPU;
  vtkPGIGISettings* settings = bake->GetSettings();
  const char* albedoArray = settings->GetAlbedoArrayName();
  const double* fallback = settings->GetDefaultAlbedo();
  std::ostringstream key;
  key.precision(17);
  key << (albedoArray ? albedoArray : "") << " " << fallback[0] << " " << fallback[1] << " "
      << fallback[2] << " " << vertices;
  for (const ReceiverBlock& block : blocks)
  {
    key << " " << block.Data << "@" << block.Start << ":" << block.Data->GetMTime();
  }
  if (key.str() == g.ReceiversKey)
  {
    return;
  }
  // Vertices no block covers (none in practice) get a zero normal: black.
  std::vector<float> data(9 * static_cast<std::size_t>(vertices), 0.0f);
  for (const ReceiverBlock& block : blocks)
  {
    vtkPolyData* input = block.Data;
    const vtkIdType n = std::min(input->GetNumberOfPoints(), vertices - block.Start);
    vtkSmartPointer<vtkDataArray> normals = ReceiverNormals(input);
    const AlbedoReader albedoOf(input, albedoArray, fallback);
    for (vtkIdType i = 0; i < n; ++i)
    {
      double p[3], nd[3] = { 0.0, 0.0, 1.0 }, albedo[3];
      input->GetPoint(i, p);
      // Normalised in double, as the CPU filter does, so both start from
      // the same floats.
      if (normals)
      {
        normals->GetTuple(i, nd);
        const double len = std::sqrt(nd[0] * nd[0] + nd[1] * nd[1] + nd[2] * nd[2]);
        if (len > 0.0)
        {
          nd[0] /= len;
          nd[1] /= len;
          nd[2] /= len;
        }
        else
        {
          nd[0] = nd[1] = 0.0;
          nd[2] = 1.0;
        }
      }
      albedoOf.Get(i, albedo);
      float* row = &data[9 * static_cast<std::size_t>(block.Start + i)];
      for (int k = 0; k < 3; ++k)
      {
        row[k] = static_cast<float>(p[k]);
        row[3 + k] = static_cast<float>(nd[k]);
        row[6 + k] = static_cast<float>(albedo[k]);
      }
    }
  }
  g.Receivers->Upload(data, vtkOpenGLBufferObject::ArrayBuffer);
  g.Points = vertices;
  g.ReceiversKey = key.str();
  why += "mesh; ";
}

bool VertexGI::RunGIPass(vtkObject* owner, vtkOpenGLRenderWindow* window, vtkPGIGIBake* bake,
  int visibilityVec4s, bool resize)
{
  Internals& g = *this->GPU;
  const BakedScene& b = bake->GetScene();
  vtkPGIGISettings* settings = bake->GetSettings();
  const std::array<double, 16>& matrix = g.Matrix;
  const int order = b.Order, n2 = order * order;
  const vtkIdType n = g.Points;
  std::string vs = pgiGIComputeVS;
  std::ostringstream captureDec, captureImpl;
  for (int k = 0; k < visibilityVec4s; ++k)
  {
    captureDec << "out vec4 pgiVisibility" << k << ";\n";
    captureImpl << "  pgiVisibility" << k << " = vec4(";
    for (int c = 0; c < 4; ++c)
    {
      const int i = 4 * k + c;
      captureImpl << (c ? ", " : "") << (i < n2 ? "g[" + std::to_string(i) + "]" : "0.0");
    }
    captureImpl << ");\n";
  }
  // The shadowed bounce's code only where it runs (it is the costliest to compile).
  const bool sphericalLights = g.SphericalLightCount > 0;
  vtkShaderProgram::Substitute(vs, "//PGI::Defines",
    std::string("#define PGI_SPHERICAL_LIGHTS ") + (sphericalLights ? "1" : "0"));
  vtkShaderProgram::Substitute(vs, "//PGI::Library", LibrarySource(order));
  vtkShaderProgram::Substitute(vs, "//PGI::ISLibrary", IndirectLibrarySource());
  vtkShaderProgram::Substitute(vs, "//PGI::SLLibrary",
    sphericalLights ? SphericalLightsLibrarySource(g.SphericalLightCount) : "");
  vtkShaderProgram::Substitute(vs, "//PGI::Capture::Dec", captureDec.str());
  vtkShaderProgram::Substitute(vs, "//PGI::Capture::Impl", captureImpl.str());
  vtkShaderProgram* program =
    window->GetShaderCache()->ReadyShaderProgram(vs.c_str(), pgiGIComputeFS, "", g.Capture);
  if (!program)
  {
    vtkErrorWithObjectMacro(owner, "The GI shader did not compile.");
    return false;
  }
  if (program->GetHandle() != g.ProgramHandle)
  {
    g.VAO->ShaderProgramChanged();
    g.ProgramHandle = program->GetHandle();
  }
  g.Resources.SetSettings(KernelSettingsOf(settings));
  g.Resources.Bind(program);
  // Column-major uploads of the actor matrix and its normal matrix.
  float modelToWorld[16];
  for (int r = 0; r < 4; ++r)
  {
    for (int c = 0; c < 4; ++c)
    {
      modelToWorld[4 * c + r] = static_cast<float>(matrix[4 * r + c]);
    }
  }
  vtkNew<vtkMatrix3x3> normalMatrix;
  for (int r = 0; r < 3; ++r)
  {
    for (int c = 0; c < 3; ++c)
    {
      normalMatrix->SetElement(r, c, matrix[4 * r + c]);
    }
  }
  normalMatrix->Invert();
  normalMatrix->Transpose();
  float normalToWorld[9];
  for (int r = 0; r < 3; ++r)
  {
    for (int c = 0; c < 3; ++c)
    {
      normalToWorld[3 * c + r] = static_cast<float>(normalMatrix->GetElement(r, c));
    }
  }
  const bool indirect = settings->GetIndirect();
  const bool shadowedMode =
    indirect && settings->GetIndirectMode() == vtkPGIGISettings::INDIRECT_MODE_SHADOWED;
  program->SetUniformMatrix4x4("pgiModelToWorld", modelToWorld);
  program->SetUniformMatrix3x3("pgiNormalToWorld", normalToWorld);
  const bool identity =
    matrix == std::array<double, 16>{ 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1 };
  program->SetUniformi("pgiMoved", identity ? 0 : 1);
  program->SetUniformi("pgiShadows", settings->GetShadows() ? 1 : 0);
  program->SetUniformi("pgiPlanesInLight", g.PlanesInLight ? 1 : 0);
  program->SetUniform1fv("pgiPlaneVisibility", n2, g.PlaneVisibility.data());
  program->SetUniformi("pgiIndirect", indirect ? 1 : 0);
  program->SetUniformi("pgiIndirectShadowed", shadowedMode ? 1 : 0);
  program->SetUniformi("pgiPlaneBounceShadows", settings->GetPlaneBounceShadows() ? 1 : 0);
  program->SetUniform3fv("pgiResponse", n2, g.Response.data());
  program->SetUniform3fv("pgiPlaneAlbedo", MaxPlanes, g.PlaneAlbedos.data());
  {
    const int lights = static_cast<int>(g.LocalLights.size() / 4);
    std::vector<float> centres(4 * MaxLocalLights, 0.0f), radiance(3 * MaxLocalLights, 0.0f);
    std::copy(g.LocalLights.begin(), g.LocalLights.end(), centres.begin());
    std::copy(g.LocalRadiance.begin(), g.LocalRadiance.end(), radiance.begin());
    program->SetUniformi("pgiNumLocalLights", lights);
    program->SetUniform4fv("pgiLocalLight", MaxLocalLights, centres.data());
    program->SetUniform3fv("pgiLocalRadiance", MaxLocalLights, radiance.data());
    program->SetUniformf("pgiLobeMinTheta",
      lights > 0 ? static_cast<float>(g.Resources.GetAnalyticLightMinTheta()) : 0.0f);
  }
  g.ProxyAlbedo->Activate();
  program->SetUniformi("pgiProxyAlbedo", g.ProxyAlbedo->GetTextureUnit());
  BindPlaneLightMaps(program, g.PlaneMapsGL);

  g.VAO->Bind();
  const struct
  {
    const char* Name;
    int Offset;
  } attributes[] = { { "pgiPositionMC", 0 }, { "pgiNormalMC", 12 }, { "pgiAlbedoMC", 24 } };
  for (const auto& a : attributes)
  {
    if (program->IsAttributeUsed(a.Name) &&
      !g.VAO->AddAttributeArray(program, g.Receivers, a.Name, a.Offset, 36, VTK_FLOAT, 3, false))
    {
      vtkErrorWithObjectMacro(owner, "Could not bind " << a.Name << ".");
    }
  }
  const int floats = 4 * (1 + visibilityVec4s);
  if (!g.HaveResults || g.ResultFloats != floats || g.Results->GetHandle() == 0 || resize)
  {
    g.Results->Upload(std::vector<float>(static_cast<std::size_t>(n) * floats, 0.0f),
      vtkOpenGLBufferObject::ArrayBuffer);
    g.ResultFloats = floats;
  }
  glBindBufferBase(GL_TRANSFORM_FEEDBACK_BUFFER, 0, g.Results->GetHandle());
  glEnable(GL_RASTERIZER_DISCARD);
  glBeginTransformFeedback(GL_POINTS);
  glDrawArrays(GL_POINTS, 0, static_cast<GLsizei>(n));
  glEndTransformFeedback();
  glDisable(GL_RASTERIZER_DISCARD);
  glBindBufferBase(GL_TRANSFORM_FEEDBACK_BUFFER, 0, 0);
  g.VAO->Release();
  g.ProxyAlbedo->Deactivate();
  ReleasePlaneLightMaps(g.PlaneMapsGL);
  g.Resources.Unbind();
  return true;
}

void VertexGI::ComposeStatus(vtkObject* owner, vtkPGIGIBake* bake, const std::string& reasons,
  const std::vector<std::string>& notes, const VertexGIOptions& options)
{
  Internals& g = *this->GPU;
  vtkPGIGISettings* settings = bake->GetSettings();
  const bool indirect = settings->GetIndirect();
  const bool shadowedMode =
    indirect && settings->GetIndirectMode() == vtkPGIGISettings::INDIRECT_MODE_SHADOWED;
  std::ostringstream status;
  status << "GI on the GPU: " << g.Points << " vertices, " << g.ProxyCount << " proxies, "
         << g.PlaneCount << " planes, order " << g.UploadedOrder;
  if (reasons.empty() && !options.AlwaysRecompute)
  {
    status << "; reused (nothing changed)";
  }
  else
  {
    status << ", " << (settings->GetShadows() ? "SHEXP shadows (HYB)" : "no shadows")
           << (g.PlaneCount == 0    ? ""
                  : g.PlanesInLight ? ", planes carried by the light"
                                    : ", planes in log space")
           << (!indirect ? ""
                  : shadowedMode
                  ? ", one-bounce indirect (shadowed: " + g.SphericalLightSummary + ")"
                  : std::string(", one-bounce indirect (averaged, xi)"))
           << (indirect && settings->GetPlaneBounceShadows() && g.PlaneCount > 0
                  ? ", planes' bounce shadowed"
                  : "");
    if (g.PlaneMapsGL.Directions > 0)
    {
      status << " (light maps: " << g.PlaneMapsGL.Points << " grid points built on the CPU in "
             << g.PlaneMapMs << " ms, " << g.PlaneMapsGL.Directions << " directions per vertex)";
    }
    else if (indirect && settings->GetPlaneBounceShadows() && g.PlaneCount > 0)
    {
      status << " (one plane point per vertex)";
    }
    if (!g.LocalLights.empty())
    {
      status << ", " << g.LocalLights.size() / 4 << " local lights";
    }
    // Mesa's llvmpipe ends every loop of a shader invocation once all its
    // loops together ran 65535 iterations (gallivm's loop limiter): past the
    // sizes measured to stay inside it (Documentation/Rendering.md), say so.
    const char* renderer = reinterpret_cast<const char*>(glGetString(GL_RENDERER));
    const bool llvmpipe = renderer && std::strstr(renderer, "llvmpipe");
    const bool overBudget =
      g.ProxyCount > 1000 || (indirect && g.ProxyCount > 600) || g.SphericalLightCount > 96;
    this->CutShort = llvmpipe && overBudget;
    if (this->CutShort)
    {
      status << "; on llvmpipe beyond its loop budget (more than 1000 proxies, 600 with the "
                "bounce or 96 spherical lights): results may be cut short";
      if (!g.WarnedBudget)
      {
        vtkWarningWithObjectMacro(
          owner, << "llvmpipe stops a shader's loops after 65535 iterations in all: with "
                 << g.ProxyCount << " proxies and " << g.SphericalLightCount
                 << " spherical lights the GI pass may be cut short. Use a hardware "
                    "GPU, fewer proxies or vtkPGIGlobalIllumination.");
        g.WarnedBudget = true;
      }
    }
    status << "; recomputed ("
           << (reasons.empty() ? "AlwaysRecompute" : reasons.substr(0, reasons.size() - 2)) << ")";
  }
  for (const std::string& note : notes)
  {
    status << "; not honoured: " << note;
  }
  this->Status = status.str();
}

bool VertexGI::Update(vtkObject* owner, vtkOpenGLRenderWindow* window, vtkActor* actor,
  const std::vector<ReceiverBlock>& blocks, vtkIdType vertices, vtkPGIGIBake* bake,
  const std::vector<std::string>& notes, const VertexGIOptions& options)
{
  Internals& g = *this->GPU;
  if (!options.GlobalIllumination || vertices == 0 || blocks.empty() || !window)
  {
    this->Status = !options.GlobalIllumination ? "GI off: VTK lighting" : "GI: nothing to draw";
    return false;
  }
  std::string why;
  if (g.Window != window)
  {
    if (g.Window)
    {
      this->ReleaseGraphicsResources(g.Window);
    }
    g.Window = window;
    why += "new context; ";
  }
  if (bake->GetBuildTime() != g.BakeUploaded)
  {
    why += "scene; ";
  }
  const int order = bake->GetScene().Order, n2 = order * order;
  if (!g.Resources.SetOrder(window, order))
  {
    vtkErrorWithObjectMacro(owner, "Could not upload the SH tables of order " << order << ".");
    return false;
  }
  this->UploadBake(owner, window, bake);
  this->UploadReceivers(bake, blocks, vertices, why);

  // The actor's matrix (the mesh moves, proxies stay in world coordinates).
  std::array<double, 16> matrix;
  vtkMatrix4x4* m = actor->GetMatrix();
  std::copy(&m->Element[0][0], &m->Element[0][0] + 16, matrix.begin());
  if (matrix != g.Matrix)
  {
    why += "actor matrix; ";
  }
  if (bake->GetSettings()->GetMTime() != g.SettingsTime)
  {
    why += "settings; ";
  }
  // The compute program: order and the captured outputs fix the source.
  const int visibilityVec4s = options.CaptureVisibility ? (n2 + 3) / 4 : 0;
  const std::string key = std::to_string(order) + "/" + std::to_string(visibilityVec4s);
  if (!g.Capture || g.CaptureKey != key)
  {
    g.Capture = SharedCapture(visibilityVec4s);
    g.CaptureKey = key;
    g.HaveResults = false;
    why += "program; ";
  }
  if (g.HaveResults && why.empty() && !options.AlwaysRecompute)
  {
    this->ComposeStatus(owner, bake, why, notes, options);
    return true;
  }
  g.Matrix = matrix;
  if (!this->RunGIPass(owner, window, bake, visibilityVec4s, why.find("mesh") != std::string::npos))
  {
    g.Matrix = std::array<double, 16>{};
    return false;
  }
  g.SettingsTime = bake->GetSettings()->GetMTime();
  g.HaveResults = true;
  ++this->Updates;
  this->ComposeStatus(owner, bake, why, notes, options);
  return true;
}

void VertexGI::ReplaceShaderValuesBefore(std::map<vtkShader::Type, vtkShader*>& shaders) const
{
  // Ours first, keeping VTK's tags for VTK; the colour override goes after
  // VTK's lighting code, hence a tag of our own that VTK leaves alone.
  std::string vs = shaders[vtkShader::Vertex]->GetSource();
  std::string fs = shaders[vtkShader::Fragment]->GetSource();
  vtkShaderProgram::Substitute(vs, "//VTK::Color::Dec", pgiGIMapperVS, false);
  vtkShaderProgram::Substitute(vs, "//VTK::Color::Impl", pgiGIMapperVSImpl, false);
  std::string dec = pgiGIMapperFS;
  vtkShaderProgram::Substitute(dec, "//PGI::SRGB", pgiSRGBGLSL);
  vtkShaderProgram::Substitute(fs, "//VTK::Light::Dec", dec, false);
  vtkShaderProgram::Substitute(
    fs, "//VTK::Light::Impl", "//VTK::Light::Impl\n//PGI::GI::Impl\n", false);
  shaders[vtkShader::Vertex]->SetSource(vs);
  shaders[vtkShader::Fragment]->SetSource(fs);
}

void VertexGI::ReplaceShaderValuesAfter(std::map<vtkShader::Type, vtkShader*>& shaders) const
{
  std::string fs = shaders[vtkShader::Fragment]->GetSource();
  vtkShaderProgram::Substitute(fs, "//PGI::GI::Impl", pgiGIMapperFSImpl, false);
  shaders[vtkShader::Fragment]->SetSource(fs);
}

void VertexGI::SetShaderParameters(
  vtkObject* owner, vtkOpenGLHelper& cellBO, const VertexGIOptions& options) const
{
  const Internals& g = *this->GPU;
  vtkShaderProgram* program = cellBO.Program;
  if (!g.GIInShaders || !program || !program->IsAttributeUsed("pgiRadianceMC"))
  {
    return;
  }
  // The results buffer may have been reallocated since the VAO last saw it.
  cellBO.VAO->Bind();
  if (!cellBO.VAO->AddAttributeArray(program, g.Results.GetPointer(), "pgiRadianceMC", 0,
        4 * static_cast<size_t>(g.ResultFloats), VTK_FLOAT, 4, false))
  {
    vtkErrorWithObjectMacro(owner, "Could not bind the GI results.");
  }
  program->SetUniformf("pgiExposure", static_cast<float>(options.Exposure));
  program->SetUniformi("pgiCombineWithVTKLighting", options.CombineWithVTKLighting ? 1 : 0);
  program->SetUniformi("pgiSRGBOutput", options.SRGBOutput ? 1 : 0);
}

bool VertexGI::GetResults(
  vtkIdType start, vtkIdType count, vtkFloatArray* radiance, vtkFloatArray* visibility) const
{
  const Internals& g = *this->GPU;
  if (!g.HaveResults || !g.Window || !radiance || start < 0 || count < 0 ||
    start + count > g.Points)
  {
    return false;
  }
  g.Window->MakeCurrent();
  const std::size_t floats = static_cast<std::size_t>(g.ResultFloats);
  const std::size_t size = static_cast<std::size_t>(count) * floats;
  std::vector<float> data(size);
  glBindBuffer(GL_ARRAY_BUFFER, g.Results->GetHandle());
  glGetBufferSubData(GL_ARRAY_BUFFER,
    static_cast<GLintptr>(static_cast<std::size_t>(start) * floats * sizeof(float)),
    static_cast<GLsizeiptr>(size * sizeof(float)), data.data());
  glBindBuffer(GL_ARRAY_BUFFER, 0);
  const int n2 = g.UploadedOrder * g.UploadedOrder;
  radiance->SetNumberOfComponents(3);
  radiance->SetNumberOfTuples(count);
  if (visibility)
  {
    visibility->SetNumberOfComponents(g.ResultFloats > 4 ? n2 : 1);
    visibility->SetNumberOfTuples(g.ResultFloats > 4 ? count : 0);
  }
  for (vtkIdType i = 0; i < count; ++i)
  {
    const float* row = &data[static_cast<std::size_t>(i) * floats];
    radiance->SetTypedTuple(i, row);
    if (visibility && g.ResultFloats > 4)
    {
      visibility->SetTypedTuple(i, row + 4);
    }
  }
  return glGetError() == GL_NO_ERROR;
}

} // namespace gpu
} // namespace proxygi
