#include "vtkPGIImageSpaceGIPass.h"

#include "pgiGIShaders.h"
#include "pgiISExpFS.h"
#include "pgiISLibrary.h"
#include "pgiISReceiverDownsampleFS.h"
#include "pgiISReceiverFS.h"
#include "pgiISRestoreDepthFS.h"
#include "pgiISShadowedLightFS.h"
#include "pgiISSplatIndirectFS.h"
#include "pgiISSplatShadowFS.h"
#include "pgiISSplatVS.h"
#include "pgiISUpsampleFS.h"

#include "pgiEnvironmentMap.h"
#include "pgiIndirectLight.h"
#include "pgiMaterial.h"
#include "pgiSH.h"
#include "pgiSHTripleProduct.h"
#include "pgiSHZonal.h"
#include "vtkPGILighting.h"

#include "vtkAlgorithm.h"
#include "vtkAlgorithmOutput.h"
#include "vtkCamera.h"
#include "vtkDataArray.h"
#include "vtkFloatArray.h"
#include "vtkFrameBufferObjectBase.h"
#include "vtkMatrix4x4.h"
#include "vtkNew.h"
#include "vtkObjectFactory.h"
#include "vtkOpenGLBufferObject.h"
#include "vtkOpenGLError.h"
#include "vtkOpenGLFramebufferObject.h"
#include "vtkOpenGLPolyDataMapper.h"
#include "vtkOpenGLQuadHelper.h"
#include "vtkOpenGLRenderUtilities.h"
#include "vtkOpenGLRenderWindow.h"
#include "vtkOpenGLShaderCache.h"
#include "vtkOpenGLState.h"
#include "vtkOpenGLVertexArrayObject.h"
#include "vtkPointData.h"
#include "vtkPolyData.h"
#include "vtkRenderState.h"
#include "vtkRenderStepsPass.h"
#include "vtkRenderer.h"
#include "vtkShaderProgram.h"
#include "vtkSmartPointer.h"
#include "vtkTextureObject.h"
#include "vtk_glew.h"

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <sstream>

vtkStandardNewMacro(vtkPGIImageSpaceGIPass);
vtkCxxSetObjectMacro(vtkPGIImageSpaceGIPass, DelegatePass, vtkRenderPass);
vtkCxxSetObjectMacro(vtkPGIImageSpaceGIPass, Lighting, vtkPGILighting);

namespace
{
constexpr int MaxTargets = 4; // order 4: 16 coefficients
// Shading needs bands 0..2 of the shadowed light (H(N) has no band 3):
// 3 x 9 floats at most.
constexpr int MaxLightTargets = 8; // and 3 floats of indirect light
int ShadeRows(int order)
{
  const int bands = std::min(order, 3);
  return bands * bands;
}

vtkSmartPointer<vtkTextureObject> NewTarget(
  vtkOpenGLRenderWindow* window, int width, int height, bool floating)
{
  auto t = vtkSmartPointer<vtkTextureObject>::New();
  t->SetContext(window);
  t->SetMinificationFilter(vtkTextureObject::Nearest);
  t->SetMagnificationFilter(vtkTextureObject::Nearest);
  t->SetWrapS(vtkTextureObject::ClampToEdge);
  t->SetWrapT(vtkTextureObject::ClampToEdge);
  if (floating)
  {
    t->SetInternalFormat(GL_RGBA32F);
    t->SetFormat(GL_RGBA);
    t->SetDataType(GL_FLOAT);
    t->Allocate2D(width, height, 4, VTK_FLOAT);
  }
  else
  {
    t->Allocate2D(width, height, 4, VTK_UNSIGNED_CHAR);
  }
  return t;
}

// GLSL moving the order^2 coefficients of `array` to or from vec4 targets.
std::string OutputsFrom(const char* array, int n2)
{
  std::ostringstream code;
  for (int k = 0; k < (n2 + 3) / 4; ++k)
  {
    code << "  gl_FragData[" << k << "] = vec4(";
    for (int c = 0; c < 4; ++c)
    {
      const int i = 4 * k + c;
      code << (c ? ", " : "")
           << (i < n2 ? std::string(array) + "[" + std::to_string(i) + "]" : "0.0");
    }
    code << ");\n";
  }
  return code.str();
}

std::string SamplerDeclarations(const char* name, int n2)
{
  std::ostringstream code;
  for (int k = 0; k < (n2 + 3) / 4; ++k)
  {
    code << "uniform sampler2D " << name << k << ";\n";
  }
  return code.str();
}

std::string InputsTo(const char* array, const char* sampler, const char* texel, int n2)
{
  std::ostringstream code;
  const char xyzw[] = "xyzw";
  for (int k = 0; k < (n2 + 3) / 4; ++k)
  {
    code << "    {\n      vec4 t = texelFetch(" << sampler << k << ", " << texel << ", 0);\n";
    for (int c = 0; c < 4 && 4 * k + c < n2; ++c)
    {
      code << "      " << array << "[" << 4 * k + c << "] = t." << xyzw[c] << ";\n";
    }
    code << "    }\n";
  }
  return code.str();
}

// Column-major float copies for glUniformMatrix (VTK matrices are row-major).
void ColumnMajor(const vtkMatrix4x4* m, float out[16])
{
  for (int r = 0; r < 4; ++r)
  {
    for (int c = 0; c < 4; ++c)
    {
      out[4 * c + r] = static_cast<float>(m->GetElement(r, c));
    }
  }
}

// The 36 corners of the unit cube's triangles, counter-clockwise seen from
// outside (the splat draws back faces only: each pixel once, also with the
// camera inside the box).
std::vector<float> CubeTriangles()
{
  std::vector<float> v;
  for (int axis = 0; axis < 3; ++axis)
  {
    for (int sign = -1; sign <= 1; sign += 2)
    {
      const int a = (axis + 1) % 3, b = (axis + 2) % 3;
      std::array<std::array<float, 3>, 4> q;
      const float uv[4][2] = { { -1, -1 }, { 1, -1 }, { 1, 1 }, { -1, 1 } };
      for (int k = 0; k < 4; ++k)
      {
        q[k][axis] = static_cast<float>(sign);
        q[k][a] = uv[k][0];
        q[k][b] = uv[k][1];
      }
      // (a, b, axis) is right-handed, so this quad faces +axis.
      if (sign < 0)
      {
        std::swap(q[1], q[3]);
      }
      for (int k : { 0, 1, 2, 0, 2, 3 })
      {
        v.insert(v.end(), q[k].begin(), q[k].end());
      }
    }
  }
  return v;
}
} // namespace

struct vtkPGIImageSpaceGIPass::Internals
{
  proxygi::gpu::GIResources Resources;
  vtkOpenGLRenderWindow* Window = nullptr;
  int LightOrder = 0;
  vtkMTimeType BakeUploaded = 0;
  int Proxies = 0, Planes = 0;
  std::vector<float> PlaneAlbedos; // pgiPlaneAlbedo

  // Full-resolution receiver targets (VTK colour, view-space position,
  // normal, albedo, depth), the receiver buffer (world position + eye
  // depth, normal + mask), the log-visibility sums and the visibility.
  vtkSmartPointer<vtkOpenGLFramebufferObject> FBO;
  vtkSmartPointer<vtkTextureObject> GColor, GPosition, GNormal, GAlbedo, GDepth;
  vtkSmartPointer<vtkTextureObject> RPosition, RNormal;
  vtkSmartPointer<vtkTextureObject> Accum[MaxTargets], Vis[MaxTargets];
  vtkSmartPointer<vtkTextureObject> Lit[MaxLightTargets];
  vtkSmartPointer<vtkTextureObject> IndirectSum, ProxyAlbedo;
  std::vector<float> Response; // pgiResponse, interleaved RGB
  std::vector<float> Albedos;  // 4 per proxy
  int LightTargets = 0;
  int Width = 0, Height = 0, LowWidth = 0, LowHeight = 0, Scale = 0, Targets = 0;

  std::unique_ptr<vtkOpenGLQuadHelper> Downsample, Exp, Light, Upsample;
  // The Exact fallback's second stage and the depth put back after it.
  std::unique_ptr<vtkOpenGLQuadHelper> UpsampleExact, RestoreDepth;
  int ProgramOrder = 0;
  int ProgramFallback = -1;
  std::string SplatVS, SplatFS, SplatIndirectVS, SplatIndirectFS;
  vtkNew<vtkOpenGLBufferObject> Cube;
  vtkNew<vtkOpenGLVertexArrayObject> CubeVAO;
  int CubeProgram = 0;

  double LightExpansion = 15.0; // LightingExpansionFactor of the light
  double LightExpansionTolerance = 0.0;
  double UsedExpansion = 15.0;
  double Times[NumberOfPasses] = {};
  bool HaveFrame = false;

  // This frame: viewport, buffer sizes, camera matrices (column-major),
  // what runs, the pass clock.
  int X = 0, Y = 0, W = 0, H = 0, Order = 0;
  bool Shadows = true, Indirect = false;
  float VCWC[16], WCDC[16], NVCWC[9];
  float PlaneTolerance = 0.0f;
  std::chrono::steady_clock::time_point Mark;

  void ReleaseTargets(vtkWindow* w)
  {
    for (auto* t : { &GColor, &GPosition, &GNormal, &GAlbedo, &GDepth, &RPosition, &RNormal })
    {
      if (*t)
      {
        (*t)->ReleaseGraphicsResources(w);
        *t = nullptr;
      }
    }
    for (int k = 0; k < MaxTargets; ++k)
    {
      for (auto* t : { &Accum[k], &Vis[k] })
      {
        if (*t)
        {
          (*t)->ReleaseGraphicsResources(w);
          *t = nullptr;
        }
      }
    }
    if (IndirectSum)
    {
      IndirectSum->ReleaseGraphicsResources(w);
      IndirectSum = nullptr;
    }
    for (int k = 0; k < MaxLightTargets; ++k)
    {
      if (Lit[k])
      {
        Lit[k]->ReleaseGraphicsResources(w);
        Lit[k] = nullptr;
      }
    }
    Width = Height = LowWidth = LowHeight = Scale = Targets = LightTargets = 0;
    HaveFrame = false;
  }
};

vtkPGIImageSpaceGIPass::vtkPGIImageSpaceGIPass()
  : GPU(new Internals)
{
  vtkNew<vtkRenderStepsPass> steps;
  this->SetDelegatePass(steps);
  this->Settings = vtkPGIGISettings::New();
  this->Bake->SetSettings(this->Effective);
}

vtkPGIImageSpaceGIPass::~vtkPGIImageSpaceGIPass()
{
  this->SetDelegatePass(nullptr);
  this->SetProxies(nullptr);
  this->SetLighting(nullptr);
  this->Settings->UnRegister(this);
}

void vtkPGIImageSpaceGIPass::SetSettings(vtkPGIGISettings* settings)
{
  if (vtkPGIGISettings::Share(this, this->Settings, settings))
  {
    this->Modified();
  }
}

const vtkPGIGISettings::Support& vtkPGIImageSpaceGIPass::GetSupport()
{
  static const vtkPGIGISettings::Support support = []
  {
    vtkPGIGISettings::Support s =
      proxygi::gpu::KernelSupport("image-space pass", MaxTargets * 4 >= 16 ? 4 : 2);
    s.IndirectModes = 1u << vtkPGIGISettings::INDIRECT_MODE_UNSHADOWED;
    s.SphericalLightBlocking = false;
    s.PlaneBounceShadows = false;
    s.PlaneBounceDirections = false;
    s.PlaneBlockings = 1u << vtkPGIGISettings::PLANES_IN_LOG_SPACE;
    s.LocalLights = false;
    s.LightCloud = false;
    s.ReceiverAlbedo = false;
    return s;
  }();
  return support;
}

void vtkPGIImageSpaceGIPass::SetProxies(vtkPolyData* proxies)
{
  if (proxies != this->Proxies)
  {
    if (this->Proxies)
    {
      this->Proxies->UnRegister(this);
    }
    this->Proxies = proxies;
    if (this->Proxies)
    {
      this->Proxies->Register(this);
    }
    this->Modified();
  }
  this->ProxiesConnection = nullptr;
}

void vtkPGIImageSpaceGIPass::SetProxiesConnection(vtkAlgorithmOutput* output)
{
  this->SetProxies(nullptr);
  this->ProxiesConnection = output;
  this->Modified();
}

vtkPolyData* vtkPGIImageSpaceGIPass::GetProxies()
{
  if (this->ProxiesConnection && this->ProxiesConnection->GetProducer())
  {
    vtkAlgorithm* producer = this->ProxiesConnection->GetProducer();
    const int port = this->ProxiesConnection->GetIndex();
    producer->Update(port);
    return vtkPolyData::SafeDownCast(producer->GetOutputDataObject(port));
  }
  return this->Proxies;
}

void vtkPGIImageSpaceGIPass::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "DelegatePass: " << this->DelegatePass << "\n";
  os << indent << "Proxies: " << this->Proxies << "\n";
  os << indent << "ProxiesConnection: " << this->ProxiesConnection.Get() << "\n";
  os << indent << "Lighting: " << this->Lighting << "\n";
  os << indent << "BlockerPlanes: " << this->Bake->GetNumberOfBlockerPlanes() << "\n";
  os << indent << "Settings:\n";
  this->Settings->PrintSelf(os, indent.GetNextIndent());
  os << indent << "ReceiverScale: " << this->ReceiverScale << "\n";
  os << indent << "Upsampling: " << (this->Upsampling == Bilateral ? "Bilateral" : "Bilinear")
     << "\n";
  os << indent << "ExpansionFactor: " << this->ExpansionFactor << "\n";
  os << indent << "AutomaticExpansionFactor: " << this->AutomaticExpansionFactor << "\n";
  os << indent << "ExpansionTolerance: " << this->ExpansionTolerance << "\n";
  os << indent << "IndirectExpansionFactor: " << this->IndirectExpansionFactor << "\n";
  os << indent << "NormalPower: " << this->NormalPower << "\n";
  os << indent << "DepthEpsilon: " << this->DepthEpsilon << "\n";
  os << indent << "FallbackThreshold: " << this->FallbackThreshold << "\n";
  os << indent << "Fallback: " << (this->Fallback == ExactFallback ? "Exact" : "NearestSample")
     << "\n";
  os << indent << "Exposure: " << this->Exposure << "\n";
  os << indent << "SRGBOutput: " << this->SRGBOutput << "\n";
  os << indent << "MeasurePassTimes: " << this->MeasurePassTimes << "\n";
  os << indent << "Status: " << this->Status << "\n";
}

void vtkPGIImageSpaceGIPass::SetReceiverScale(int scale)
{
  if (scale != 1 && scale != 2 && scale != 4 && scale != 8)
  {
    vtkErrorMacro("ReceiverScale must be 1, 2, 4 or 8, not " << scale << ".");
    return;
  }
  if (scale != this->ReceiverScale)
  {
    this->ReceiverScale = scale;
    this->Modified();
  }
}

void vtkPGIImageSpaceGIPass::AddBlockerPlane(const double origin[3], const double normal[3])
{
  const double black[3] = { 0.0, 0.0, 0.0 };
  this->AddBlockerPlane(origin, normal, black);
}

void vtkPGIImageSpaceGIPass::AddBlockerPlane(
  const double origin[3], const double normal[3], const double albedo[3])
{
  if (this->Bake->GetNumberOfBlockerPlanes() >= proxygi::gpu::MaxPlanes)
  {
    vtkErrorMacro("At most " << proxygi::gpu::MaxPlanes << " blocker planes.");
    return;
  }
  this->Bake->AddBlockerPlane(origin, normal, albedo);
  this->Modified();
}

void vtkPGIImageSpaceGIPass::RemoveAllBlockerPlanes()
{
  this->Bake->RemoveAllBlockerPlanes();
  this->Modified();
}

double vtkPGIImageSpaceGIPass::GetUsedExpansionFactor() const
{
  return this->GPU->UsedExpansion;
}

double vtkPGIImageSpaceGIPass::LightingExpansionFactor(
  int order, const double* red, const double* green, const double* blue, double tolerance)
{
  using namespace proxygi::sh;
  const int n2 = order * order;
  const double* light[3] = { red, green, blue };
  const TripleProduct& tp = TripleProduct::Get(order);
  // Directions: a Fibonacci set (blocker direction = receiver normal).
  const int count = 256;
  std::vector<std::array<double, 3>> dirs(count);
  for (int k = 0; k < count; ++k)
  {
    const double z = 1.0 - (2.0 * k + 1.0) / count;
    const double r = std::sqrt(std::max(0.0, 1.0 - z * z));
    const double phi = 2.0 * Pi * std::fmod(k * 0.38196601125010515, 1.0);
    dirs[k] = { r * std::cos(phi), r * std::sin(phi), z };
  }
  // The brightest unshadowed shading, the normaliser.
  std::vector<double> h(n2), occluder(n2), product(n2), zh(order);
  double brightest = 0.0;
  for (const auto& d : dirs)
  {
    DiffuseTransfer(order, d[0], d[1], d[2], h.data());
    for (int c = 0; c < 3; ++c)
    {
      double e = 0.0;
      for (int i = 0; i < n2; ++i)
      {
        e += h[i] * light[c][i];
      }
      brightest = std::max(brightest, e);
    }
  }
  if (!(brightest > 0.0))
  {
    return 1.0;
  }
  // Largest shading loss over directions for a blocker of sin(radius) alpha:
  // H(d) . (L * cap), the light the cap takes away.
  auto loss = [&](double alpha)
  {
    CapZonal(order, std::asin(std::min(1.0, alpha)), zh.data());
    double worst = 0.0;
    for (const auto& d : dirs)
    {
      RotateZonal(order, zh.data(), d[0], d[1], d[2], occluder.data());
      DiffuseTransfer(order, d[0], d[1], d[2], h.data());
      for (int c = 0; c < 3; ++c)
      {
        tp.Product(light[c], occluder.data(), product.data());
        double e = 0.0;
        for (int i = 0; i < n2; ++i)
        {
          e += h[i] * product[i];
        }
        worst = std::max(worst, std::fabs(e));
      }
    }
    return worst / brightest;
  };
  // Bisection on alpha in [1e-3, 1]: the loss grows with the blocker.
  double lo = 1e-3, hi = 1.0;
  if (loss(lo) >= tolerance)
  {
    return 1.0 / lo;
  }
  if (loss(hi) < tolerance)
  {
    return 1.0;
  }
  for (int k = 0; k < 40; ++k)
  {
    const double mid = 0.5 * (lo + hi);
    (loss(mid) < tolerance ? lo : hi) = mid;
  }
  return 1.0 / lo;
}

double vtkPGIImageSpaceGIPass::GetPassTime(int pass) const
{
  return pass >= 0 && pass < NumberOfPasses ? this->GPU->Times[pass] : 0.0;
}

void vtkPGIImageSpaceGIPass::GetReceiverBufferSize(int size[2]) const
{
  size[0] = this->GPU->LowWidth;
  size[1] = this->GPU->LowHeight;
}

void vtkPGIImageSpaceGIPass::ReleaseGraphicsResources(vtkWindow* w)
{
  Internals& g = *this->GPU;
  if (this->DelegatePass)
  {
    this->DelegatePass->ReleaseGraphicsResources(w);
  }
  g.Resources.ReleaseGraphicsResources(w);
  g.ReleaseTargets(w);
  if (g.FBO)
  {
    g.FBO->ReleaseGraphicsResources(w);
    g.FBO = nullptr;
  }
  g.Downsample.reset();
  g.Exp.reset();
  g.Light.reset();
  g.Upsample.reset();
  g.UpsampleExact.reset();
  g.RestoreDepth.reset();
  g.ProgramOrder = 0;
  if (g.ProxyAlbedo)
  {
    g.ProxyAlbedo->ReleaseGraphicsResources(w);
    g.ProxyAlbedo = nullptr;
  }
  g.Cube->ReleaseGraphicsResources();
  g.CubeVAO->ReleaseGraphicsResources();
  g.CubeProgram = 0;
  g.Window = nullptr;
  g.LightOrder = 0;
  g.BakeUploaded = 0;
  this->Superclass::ReleaseGraphicsResources(w);
}

//------------------------------------------------------------------------------
bool vtkPGIImageSpaceGIPass::PreReplaceShaderValues(
  std::string&, std::string&, std::string& fragmentShader, vtkAbstractMapper* mapper, vtkProp*)
{
  if (vtkOpenGLPolyDataMapper::SafeDownCast(mapper))
  {
    // After VTK's lighting, which defines the position and normal.
    vtkShaderProgram::Substitute(
      fragmentShader, "//VTK::Light::Impl", "//VTK::Light::Impl\n//PGI::Receiver::Impl\n", false);
  }
  return true;
}

bool vtkPGIImageSpaceGIPass::PostReplaceShaderValues(
  std::string&, std::string&, std::string& fragmentShader, vtkAbstractMapper* mapper, vtkProp*)
{
  if (vtkOpenGLPolyDataMapper::SafeDownCast(mapper))
  {
    const bool receiver = fragmentShader.find("vertexVC") != std::string::npos &&
      fragmentShader.find("normalVCVSOutput") != std::string::npos;
    const bool albedo = fragmentShader.find("diffuseColor") != std::string::npos;
    std::string code = pgiISReceiverFS;
    vtkShaderProgram::Substitute(code, "PGI_RECEIVER", receiver ? "1" : "0");
    vtkShaderProgram::Substitute(code, "PGI_ALBEDO", albedo ? "1" : "0");
    vtkShaderProgram::Substitute(fragmentShader, "//PGI::Receiver::Impl", code, false);
  }
  return true;
}

bool vtkPGIImageSpaceGIPass::SetShaderParameters(
  vtkShaderProgram*, vtkAbstractMapper* mapper, vtkProp*, vtkOpenGLVertexArrayObject*)
{
  if (this->GPU->FBO)
  {
    this->GPU->FBO->ActivateDrawBuffers(vtkOpenGLPolyDataMapper::SafeDownCast(mapper) ? 4 : 1);
  }
  return true;
}

//------------------------------------------------------------------------------
bool vtkPGIImageSpaceGIPass::GetVisibilityBuffer(vtkFloatArray* visibility, vtkFloatArray* mask)
{
  Internals& g = *this->GPU;
  if (!g.HaveFrame || !g.Window || !visibility)
  {
    return false;
  }
  g.Window->MakeCurrent();
  const int n2 = g.LightOrder * g.LightOrder;
  const std::size_t texels = static_cast<std::size_t>(g.LowWidth) * g.LowHeight;
  std::vector<float> data(4 * texels);
  visibility->SetNumberOfComponents(n2);
  visibility->SetNumberOfTuples(static_cast<vtkIdType>(texels));
  vtkOpenGLState* ostate = g.Window->GetState();
  ostate->PushFramebufferBindings();
  g.FBO->Bind();
  auto read = [&](vtkTextureObject* texture)
  {
    g.FBO->AddColorAttachment(0, texture);
    g.FBO->ActivateReadBuffer(0);
    glPixelStorei(GL_PACK_ALIGNMENT, 1);
    glReadPixels(0, 0, g.LowWidth, g.LowHeight, GL_RGBA, GL_FLOAT, data.data());
  };
  for (int k = 0; k < g.Targets; ++k)
  {
    read(g.Vis[k]);
    for (std::size_t t = 0; t < texels; ++t)
    {
      for (int c = 0; c < 4 && 4 * k + c < n2; ++c)
      {
        visibility->SetTypedComponent(static_cast<vtkIdType>(t), 4 * k + c, data[4 * t + c]);
      }
    }
  }
  if (mask)
  {
    read(g.RNormal);
    mask->SetNumberOfComponents(1);
    mask->SetNumberOfTuples(static_cast<vtkIdType>(texels));
    for (std::size_t t = 0; t < texels; ++t)
    {
      mask->SetValue(static_cast<vtkIdType>(t), data[4 * t + 3] > 0.5f ? 1.0f : 0.0f);
    }
  }
  g.FBO->RemoveColorAttachments(1);
  ostate->PopFramebufferBindings();
  return glGetError() == GL_NO_ERROR;
}

//------------------------------------------------------------------------------
void vtkPGIImageSpaceGIPass::SetIndirectUniforms(vtkShaderProgram* program)
{
  Internals& g = *this->GPU;
  program->SetUniformf("pgiPlaneTolerance", g.PlaneTolerance);
  program->SetUniformi("pgiIndirect", g.Indirect ? 1 : 0);
  program->SetUniformf("pgiIndirectExpansion", static_cast<float>(this->IndirectExpansionFactor));
  if (g.Indirect)
  {
    program->SetUniform3fv(
      "pgiResponse", static_cast<int>(g.Response.size() / 3), g.Response.data());
  }
  program->SetUniform3fv("pgiPlaneAlbedo", proxygi::gpu::MaxPlanes, g.PlaneAlbedos.data());
}

void vtkPGIImageSpaceGIPass::Splat(vtkOpenGLRenderWindow* window, const std::string& vs,
  const std::string& fs, double expansion, bool albedo)
{
  Internals& g = *this->GPU;
  vtkOpenGLState* ostate = window->GetState();
  vtkShaderProgram* program =
    window->GetShaderCache()->ReadyShaderProgram(vs.c_str(), fs.c_str(), "");
  if (!program)
  {
    vtkErrorMacro("A splat shader did not compile.");
    return;
  }
  if (program->GetHandle() != g.CubeProgram)
  {
    g.CubeVAO->ShaderProgramChanged();
    g.CubeProgram = program->GetHandle();
  }
  if (g.Cube->GetHandle() == 0)
  {
    g.Cube->Upload(CubeTriangles(), vtkOpenGLBufferObject::ArrayBuffer);
  }
  g.Resources.Bind(program);
  this->SetIndirectUniforms(program);
  g.RPosition->Activate();
  g.RNormal->Activate();
  program->SetUniformi("pgiReceiverPosition", g.RPosition->GetTextureUnit());
  program->SetUniformi("pgiReceiverNormal", g.RNormal->GetTextureUnit());
  if (albedo && g.ProxyAlbedo)
  {
    g.ProxyAlbedo->Activate();
    program->SetUniformi("pgiProxyAlbedo", g.ProxyAlbedo->GetTextureUnit());
  }
  program->SetUniformMatrix4x4("pgiWCDC", g.WCDC);
  program->SetUniformf("pgiExpansion", static_cast<float>(expansion));
  g.CubeVAO->Bind();
  g.CubeVAO->AddAttributeArray(program, g.Cube, "pgiCorner", 0, 12, VTK_FLOAT, 3, false);
  ostate->vtkglEnable(GL_BLEND);
  ostate->vtkglBlendFuncSeparate(GL_ONE, GL_ONE, GL_ONE, GL_ONE);
  ostate->vtkglBlendEquationSeparate(GL_FUNC_ADD, GL_FUNC_ADD);
  ostate->vtkglEnable(GL_CULL_FACE);
  ostate->vtkglCullFace(GL_FRONT);
  // Boxes crossing the near or far plane are not clipped there.
  glEnable(GL_DEPTH_CLAMP);
  glDrawArraysInstanced(GL_TRIANGLES, 0, 36, g.Proxies);
  glDisable(GL_DEPTH_CLAMP);
  ostate->vtkglCullFace(GL_BACK);
  ostate->vtkglDisable(GL_CULL_FACE);
  ostate->vtkglDisable(GL_BLEND);
  ostate->vtkglBlendFuncSeparate(
    GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA, GL_ONE, GL_ONE_MINUS_SRC_ALPHA);
  g.CubeVAO->Release();
  if (albedo && g.ProxyAlbedo)
  {
    g.ProxyAlbedo->Deactivate();
  }
  g.RPosition->Deactivate();
  g.RNormal->Deactivate();
  g.Resources.Unbind();
}

void vtkPGIImageSpaceGIPass::Lap(int pass)
{
  Internals& g = *this->GPU;
  if (this->MeasurePassTimes)
  {
    glFinish();
    const auto now = std::chrono::steady_clock::now();
    g.Times[pass] = std::chrono::duration<double>(now - g.Mark).count();
    g.Mark = now;
  }
  else
  {
    g.Times[pass] = 0.0;
  }
}

//------------------------------------------------------------------------------
// The bake (settings resolved for this pass) and what the GPU needs of it.
bool vtkPGIImageSpaceGIPass::PrepareInputs(vtkOpenGLRenderWindow* window, std::string& why)
{
  Internals& g = *this->GPU;
  this->Bake->SetProxies(this->GetProxies());
  this->Bake->SetLighting(this->Lighting);
  if (!this->Bake->UpdateFor(this, this->Settings, GetSupport(), this->SettingsNotes))
  {
    why = "bad environment";
    return false;
  }
  const proxygi::BakedScene& b = this->Bake->GetScene();
  const int order = b.Order, n2 = order * order;
  if (!g.Resources.SetOrder(window, order))
  {
    vtkErrorMacro("Could not upload the SH tables of order " << order << ".");
    why = "no SH tables";
    return false;
  }
  if (this->Bake->GetBuildTime() != g.BakeUploaded || g.LightOrder != order || !g.ProxyAlbedo)
  {
    const double* light = b.Light.data();
    g.Resources.SetLight(light, light + n2, light + 2 * n2);
    g.Resources.SetBlockers(
      proxygi::gpu::PackSpheres(b.SceneBlockers), proxygi::gpu::PackPlanes(b.SceneBlockers));
    g.Proxies = static_cast<int>(b.SceneBlockers.Spheres());
    g.Planes = static_cast<int>(b.SceneBlockers.Planes());
    g.PlaneAlbedos = proxygi::gpu::PackPlaneAlbedos(b.SceneBlockers);
    // Indirect: the leaves' albedo and the secondary lights' response
    // (the planes in log space, as this pass always has them).
    proxygi::gpu::UploadProxyAlbedos(window, b.SceneBlockers, g.Albedos, g.ProxyAlbedo);
    g.Response = b.InterleavedResponse;
    g.LightExpansionTolerance = 0.0; // recomputed below when needed
    g.BakeUploaded = this->Bake->GetBuildTime();
    g.LightOrder = order;
  }
  g.Resources.SetSettings(proxygi::gpu::KernelSettingsOf(this->Effective));
  if (this->AutomaticExpansionFactor && g.LightExpansionTolerance != this->ExpansionTolerance)
  {
    const double* light = b.Light.data();
    g.LightExpansion =
      LightingExpansionFactor(order, light, light + n2, light + 2 * n2, this->ExpansionTolerance);
    g.LightExpansionTolerance = this->ExpansionTolerance;
  }
  g.UsedExpansion = this->AutomaticExpansionFactor ? g.LightExpansion : this->ExpansionFactor;
  g.Order = order;
  g.Shadows = this->Effective->GetShadows();
  g.Indirect = this->Effective->GetIndirect() && g.Shadows && !g.Response.empty();
  return true;
}

// Targets for this size, scale and order.
void vtkPGIImageSpaceGIPass::AllocateTargets(vtkOpenGLRenderWindow* window)
{
  Internals& g = *this->GPU;
  const int w = g.W, h = g.H, scale = this->ReceiverScale;
  const int lowW = (w + scale - 1) / scale, lowH = (h + scale - 1) / scale;
  const int n2 = g.Order * g.Order;
  const int targets = (n2 + 3) / 4;
  const int lightTargets = (3 * ShadeRows(g.Order) + 3 + 3) / 4; // + indirect RGB
  if (w != g.Width || h != g.Height || scale != g.Scale || targets != g.Targets ||
    lightTargets != g.LightTargets || !g.GColor)
  {
    g.ReleaseTargets(window);
    g.GColor = NewTarget(window, w, h, false);
    g.GPosition = NewTarget(window, w, h, true);
    g.GNormal = NewTarget(window, w, h, true);
    g.GAlbedo = NewTarget(window, w, h, false);
    g.GDepth = vtkSmartPointer<vtkTextureObject>::New();
    g.GDepth->SetContext(window);
    g.GDepth->AllocateDepth(w, h, vtkTextureObject::Float32);
    g.RPosition = NewTarget(window, lowW, lowH, true);
    g.RNormal = NewTarget(window, lowW, lowH, true);
    for (int k = 0; k < targets; ++k)
    {
      g.Accum[k] = NewTarget(window, lowW, lowH, true);
      g.Vis[k] = NewTarget(window, lowW, lowH, true);
    }
    for (int k = 0; k < lightTargets; ++k)
    {
      g.Lit[k] = NewTarget(window, lowW, lowH, true);
    }
    g.LightTargets = lightTargets;
    g.IndirectSum = NewTarget(window, lowW, lowH, true);
    g.Width = w;
    g.Height = h;
    g.LowWidth = lowW;
    g.LowHeight = lowH;
    g.Scale = scale;
    g.Targets = targets;
  }
  if (!g.FBO)
  {
    g.FBO = vtkSmartPointer<vtkOpenGLFramebufferObject>::New();
    g.FBO->SetContext(window);
  }
}

// Programs for this order and fallback.
bool vtkPGIImageSpaceGIPass::BuildPrograms(vtkOpenGLRenderWindow* window)
{
  Internals& g = *this->GPU;
  const int order = g.Order, n2 = order * order, rows = ShadeRows(order);
  if (g.ProgramOrder != order || g.ProgramFallback != this->Fallback || !g.Downsample)
  {
    const std::string library = proxygi::gpu::LibrarySource(order) + "#define PGI_SHADE_ROWS " +
      std::to_string(rows) + "\n" + pgiISLibrary;
    const std::string quadVS = vtkOpenGLRenderUtilities::GetFullScreenQuadVertexShader();
    g.Downsample.reset(
      new vtkOpenGLQuadHelper(window, quadVS.c_str(), pgiISReceiverDownsampleFS, ""));
    std::string fs = pgiISExpFS;
    vtkShaderProgram::Substitute(fs, "//PGI::Library", library);
    vtkShaderProgram::Substitute(fs, "//PGI::Input::Dec", SamplerDeclarations("pgiAccum", n2));
    vtkShaderProgram::Substitute(fs, "//PGI::Input::Impl", InputsTo("f", "pgiAccum", "px", n2));
    vtkShaderProgram::Substitute(fs, "//PGI::Output::Impl", OutputsFrom("g", n2));
    g.Exp.reset(new vtkOpenGLQuadHelper(window, quadVS.c_str(), fs.c_str(), ""));
    fs = pgiISShadowedLightFS;
    vtkShaderProgram::Substitute(fs, "//PGI::Library", library);
    vtkShaderProgram::Substitute(fs, "//PGI::Input::Dec", SamplerDeclarations("pgiVis", n2));
    vtkShaderProgram::Substitute(fs, "//PGI::Input::Impl", InputsTo("g", "pgiVis", "px", n2));
    vtkShaderProgram::Substitute(fs, "//PGI::Output::Impl", OutputsFrom("c", 3 * rows + 3));
    g.Light.reset(new vtkOpenGLQuadHelper(window, quadVS.c_str(), fs.c_str(), ""));
    fs = pgiISUpsampleFS;
    vtkShaderProgram::Substitute(fs, "//PGI::Library", library);
    vtkShaderProgram::Substitute(
      fs, "//PGI::Input::Dec", SamplerDeclarations("pgiLit", 3 * rows + 3));
    vtkShaderProgram::Substitute(
      fs, "//PGI::Input::Impl", InputsTo("v", "pgiLit", "s", 3 * rows + 3), true);
    const bool exact = this->Fallback == ExactFallback;
    std::string stage = fs;
    vtkShaderProgram::Substitute(stage, "PGI_UPSAMPLE_STAGE", exact ? "1" : "0", true);
    g.Upsample.reset(new vtkOpenGLQuadHelper(window, quadVS.c_str(), stage.c_str(), ""));
    g.UpsampleExact.reset();
    g.RestoreDepth.reset();
    if (exact)
    {
      vtkShaderProgram::Substitute(fs, "PGI_UPSAMPLE_STAGE", "2", true);
      g.UpsampleExact.reset(new vtkOpenGLQuadHelper(window, quadVS.c_str(), fs.c_str(), ""));
      g.RestoreDepth.reset(
        new vtkOpenGLQuadHelper(window, quadVS.c_str(), pgiISRestoreDepthFS, ""));
    }
    g.SplatVS = pgiISSplatVS;
    vtkShaderProgram::Substitute(g.SplatVS, "//PGI::Splat::Defines", "");
    g.SplatFS = pgiISSplatShadowFS;
    vtkShaderProgram::Substitute(g.SplatFS, "//PGI::Library", library);
    vtkShaderProgram::Substitute(g.SplatFS, "//PGI::Output::Impl", OutputsFrom("f", n2));
    g.SplatIndirectVS = pgiISSplatVS;
    vtkShaderProgram::Substitute(
      g.SplatIndirectVS, "//PGI::Splat::Defines", "#define PGI_SPLAT_ALBEDO\n");
    g.SplatIndirectFS = pgiISSplatIndirectFS;
    vtkShaderProgram::Substitute(g.SplatIndirectFS, "//PGI::Library", library);
    g.ProgramOrder = order;
    g.ProgramFallback = this->Fallback;
  }
  for (auto* q : { g.Downsample.get(), g.Exp.get(), g.Light.get(), g.Upsample.get(),
         g.UpsampleExact.get(), g.RestoreDepth.get() })
  {
    if (q && (!q->Program || !q->Program->GetCompiled()))
    {
      vtkErrorMacro("An image-space GI shader did not compile.");
      g.ProgramOrder = 0;
      return false;
    }
  }
  return true;
}

// Camera: world <-> view and world -> clip, column-major for GL.
void vtkPGIImageSpaceGIPass::SetUpFrame(vtkRenderer* ren)
{
  Internals& g = *this->GPU;
  vtkCamera* camera = ren->GetActiveCamera();
  vtkMatrix4x4* modelView = camera->GetModelViewTransformMatrix();
  vtkNew<vtkMatrix4x4> viewToWorld;
  vtkMatrix4x4::Invert(modelView, viewToWorld);
  ColumnMajor(viewToWorld, g.VCWC);
  ColumnMajor(
    camera->GetCompositeProjectionTransformMatrix(ren->GetTiledAspectRatio(), -1, 1), g.WCDC);
  // Normals view -> world: the inverse transpose of viewToWorld's linear
  // part, i.e. modelView's linear part transposed; column-major of that is
  // modelView's rows.
  for (int r = 0; r < 3; ++r)
  {
    for (int c = 0; c < 3; ++c)
    {
      g.NVCWC[3 * c + r] = static_cast<float>(modelView->GetElement(c, r));
    }
  }
  // Positions rebuilt from view coordinates are off by a few float ulps of
  // the scene's extent: receivers that close to a blocker plane are on it.
  double far[2];
  camera->GetClippingRange(far);
  const double* eye = camera->GetPosition();
  g.PlaneTolerance = static_cast<float>(
    1e-5 * (far[1] + std::sqrt(eye[0] * eye[0] + eye[1] * eye[1] + eye[2] * eye[2])));
}

// 1. Receiver setup: the scene into the full-resolution targets, then one
// sample per block into the receiver buffer.
void vtkPGIImageSpaceGIPass::RenderReceivers(const vtkRenderState* s, vtkOpenGLRenderWindow* window)
{
  Internals& g = *this->GPU;
  vtkOpenGLState* ostate = window->GetState();
  g.FBO->Bind();
  g.FBO->AddColorAttachment(0, g.GColor);
  g.FBO->AddColorAttachment(1, g.GPosition);
  g.FBO->AddColorAttachment(2, g.GNormal);
  g.FBO->AddColorAttachment(3, g.GAlbedo);
  g.FBO->ActivateDrawBuffers(4);
  g.FBO->AddDepthAttachment(g.GDepth);
  g.FBO->StartNonOrtho(g.W, g.H);
  ostate->vtkglViewport(0, 0, g.W, g.H);
  ostate->vtkglScissor(0, 0, g.W, g.H);
  this->PreRender(s);
  this->DelegatePass->Render(s);
  this->NumberOfRenderedProps += this->DelegatePass->GetNumberOfRenderedProps();
  this->PostRender(s);
  g.FBO->RemoveColorAttachments(4);
  g.FBO->RemoveDepthAttachment();

  ostate->vtkglDisable(GL_BLEND);
  ostate->vtkglDisable(GL_DEPTH_TEST);
  ostate->vtkglDisable(GL_CULL_FACE);
  ostate->vtkglViewport(0, 0, g.LowWidth, g.LowHeight);
  ostate->vtkglScissor(0, 0, g.LowWidth, g.LowHeight);
  g.FBO->AddColorAttachment(0, g.RPosition);
  g.FBO->AddColorAttachment(1, g.RNormal);
  g.FBO->ActivateDrawBuffers(2);
  vtkShaderProgram* program = g.Downsample->Program;
  window->GetShaderCache()->ReadyShaderProgram(program);
  g.GPosition->Activate();
  g.GNormal->Activate();
  g.GDepth->Activate();
  program->SetUniformi("pgiGPosition", g.GPosition->GetTextureUnit());
  program->SetUniformi("pgiGNormal", g.GNormal->GetTextureUnit());
  program->SetUniformi("pgiGDepth", g.GDepth->GetTextureUnit());
  program->SetUniformi("pgiScale", g.Scale);
  program->SetUniformMatrix4x4("pgiVCToWC", g.VCWC);
  program->SetUniformMatrix3x3("pgiNormalVCToWC", g.NVCWC);
  g.Downsample->Render();
  g.GPosition->Deactivate();
  g.GNormal->Deactivate();
  g.GDepth->Deactivate();
  g.FBO->RemoveColorAttachments(2);
}

// 2. Splatting: log visibility summed over the proxies' spheres of influence.
void vtkPGIImageSpaceGIPass::SplatShadows(vtkOpenGLRenderWindow* window)
{
  Internals& g = *this->GPU;
  for (int k = 0; k < g.Targets; ++k)
  {
    g.FBO->AddColorAttachment(k, g.Accum[k]);
  }
  g.FBO->ActivateDrawBuffers(g.Targets);
  window->GetState()->vtkglClearColor(0.0, 0.0, 0.0, 0.0);
  window->GetState()->vtkglClear(GL_COLOR_BUFFER_BIT);
  if (g.Shadows && g.Proxies > 0)
  {
    this->Splat(window, g.SplatVS, g.SplatFS, g.UsedExpansion, false);
  }
  g.FBO->RemoveColorAttachments(g.Targets);
}

// 3. Exponentiation: the visibility vector per receiver.
void vtkPGIImageSpaceGIPass::Exponentiate(vtkOpenGLRenderWindow* window)
{
  Internals& g = *this->GPU;
  for (int k = 0; k < g.Targets; ++k)
  {
    g.FBO->AddColorAttachment(k, g.Vis[k]);
  }
  g.FBO->ActivateDrawBuffers(g.Targets);
  vtkShaderProgram* program = g.Exp->Program;
  window->GetShaderCache()->ReadyShaderProgram(program);
  g.Resources.Bind(program);
  program->SetUniformf("pgiPlaneTolerance", g.PlaneTolerance);
  g.RPosition->Activate();
  g.RNormal->Activate();
  program->SetUniformi("pgiReceiverPosition", g.RPosition->GetTextureUnit());
  program->SetUniformi("pgiReceiverNormal", g.RNormal->GetTextureUnit());
  for (int k = 0; k < g.Targets; ++k)
  {
    g.Accum[k]->Activate();
    program->SetUniformi(("pgiAccum" + std::to_string(k)).c_str(), g.Accum[k]->GetTextureUnit());
  }
  g.Exp->Render();
  for (int k = 0; k < g.Targets; ++k)
  {
    g.Accum[k]->Deactivate();
  }
  g.RPosition->Deactivate();
  g.RNormal->Deactivate();
  g.Resources.Unbind();
  g.FBO->RemoveColorAttachments(g.Targets);
}

// Indirect: each proxy's one-bounce light and solid angle, summed.
void vtkPGIImageSpaceGIPass::SplatIndirect(vtkOpenGLRenderWindow* window)
{
  Internals& g = *this->GPU;
  g.FBO->AddColorAttachment(0, g.IndirectSum);
  g.FBO->ActivateDrawBuffers(1);
  window->GetState()->vtkglClearColor(0.0, 0.0, 0.0, 0.0);
  window->GetState()->vtkglClear(GL_COLOR_BUFFER_BIT);
  if (g.Indirect && g.Proxies > 0)
  {
    this->Splat(window, g.SplatIndirectVS, g.SplatIndirectFS, this->IndirectExpansionFactor, true);
  }
  g.FBO->RemoveColorAttachments(1);
}

// The shadowed light M_L g (and the resolved indirect light), which is what
// gets interpolated.
void vtkPGIImageSpaceGIPass::ShadeReceiverBuffer(vtkOpenGLRenderWindow* window)
{
  Internals& g = *this->GPU;
  for (int k = 0; k < g.LightTargets; ++k)
  {
    g.FBO->AddColorAttachment(k, g.Lit[k]);
  }
  g.FBO->ActivateDrawBuffers(g.LightTargets);
  vtkShaderProgram* program = g.Light->Program;
  window->GetShaderCache()->ReadyShaderProgram(program);
  g.Resources.Bind(program);
  this->SetIndirectUniforms(program);
  g.RNormal->Activate();
  g.RPosition->Activate();
  g.IndirectSum->Activate();
  program->SetUniformi("pgiReceiverNormal", g.RNormal->GetTextureUnit());
  program->SetUniformi("pgiReceiverPosition", g.RPosition->GetTextureUnit());
  program->SetUniformi("pgiIndirectSum", g.IndirectSum->GetTextureUnit());
  for (int k = 0; k < g.Targets; ++k)
  {
    g.Vis[k]->Activate();
    program->SetUniformi(("pgiVis" + std::to_string(k)).c_str(), g.Vis[k]->GetTextureUnit());
  }
  g.Light->Render();
  for (int k = 0; k < g.Targets; ++k)
  {
    g.Vis[k]->Deactivate();
  }
  g.IndirectSum->Deactivate();
  g.RPosition->Deactivate();
  g.RNormal->Deactivate();
  g.Resources.Unbind();
  g.FBO->RemoveColorAttachments(g.LightTargets);
}

// 4. Upsampling and shading into the renderer's framebuffer. With the Exact
// fallback in three draws: the upsampling marks the pixels no sample matches
// (depth = the quad's), the fallback shades the marked ones (depth test
// EQUAL, before its shader runs), and the scene's depth goes back.
void vtkPGIImageSpaceGIPass::Upsample(vtkOpenGLRenderWindow* window)
{
  Internals& g = *this->GPU;
  vtkOpenGLState* ostate = window->GetState();
  ostate->vtkglViewport(g.X, g.Y, g.W, g.H);
  ostate->vtkglScissor(g.X, g.Y, g.W, g.H);
  ostate->vtkglEnable(GL_DEPTH_TEST);
  ostate->vtkglDepthFunc(GL_ALWAYS);
  ostate->vtkglDepthMask(GL_TRUE);
  const bool albedoBound = g.Indirect && g.ProxyAlbedo;
  if (albedoBound)
  {
    g.ProxyAlbedo->Activate();
  }
  vtkTextureObject* inputs[] = { g.GColor, g.GPosition, g.GNormal, g.GAlbedo, g.GDepth, g.RPosition,
    g.RNormal };
  const char* names[] = { "pgiGColor", "pgiGPosition", "pgiGNormal", "pgiGAlbedo", "pgiGDepth",
    "pgiReceiverPosition", "pgiReceiverNormal" };
  for (vtkTextureObject* input : inputs)
  {
    input->Activate();
  }
  for (int k = 0; k < g.LightTargets; ++k)
  {
    g.Lit[k]->Activate();
  }
  const auto draw = [&](vtkOpenGLQuadHelper& quad)
  {
    vtkShaderProgram* program = quad.Program;
    window->GetShaderCache()->ReadyShaderProgram(program);
    g.Resources.Bind(program);
    this->SetIndirectUniforms(program);
    if (albedoBound)
    {
      program->SetUniformi("pgiProxyAlbedo", g.ProxyAlbedo->GetTextureUnit());
    }
    for (int k = 0; k < 7; ++k)
    {
      program->SetUniformi(names[k], inputs[k]->GetTextureUnit());
    }
    for (int k = 0; k < g.LightTargets; ++k)
    {
      program->SetUniformi(("pgiLit" + std::to_string(k)).c_str(), g.Lit[k]->GetTextureUnit());
    }
    program->SetUniformi("pgiScale", g.Scale);
    program->SetUniformi("pgiBilateral", this->Upsampling == Bilateral ? 1 : 0);
    program->SetUniformi("pgiShadows", g.Shadows ? 1 : 0);
    program->SetUniformf("pgiDepthEpsilon", static_cast<float>(this->DepthEpsilon));
    program->SetUniformf("pgiNormalPower", static_cast<float>(this->NormalPower));
    program->SetUniformf("pgiFallbackThreshold", static_cast<float>(this->FallbackThreshold));
    program->SetUniformMatrix4x4("pgiVCToWC", g.VCWC);
    program->SetUniformMatrix3x3("pgiNormalVCToWC", g.NVCWC);
    program->SetUniformf("pgiExposure", static_cast<float>(this->Exposure));
    program->SetUniformi("pgiSRGBOutput", this->SRGBOutput ? 1 : 0);
    quad.Render();
    g.Resources.Unbind();
  };
  draw(*g.Upsample);
  if (g.UpsampleExact && g.Shadows)
  {
    ostate->vtkglDepthFunc(GL_EQUAL);
    ostate->vtkglDepthMask(GL_FALSE);
    draw(*g.UpsampleExact);
    ostate->vtkglDepthFunc(GL_ALWAYS);
    ostate->vtkglDepthMask(GL_TRUE);
    vtkShaderProgram* restore = g.RestoreDepth->Program;
    window->GetShaderCache()->ReadyShaderProgram(restore);
    restore->SetUniformi("pgiGDepth", g.GDepth->GetTextureUnit());
    vtkOpenGLState::ScopedglColorMask colorMask(ostate);
    ostate->vtkglColorMask(GL_FALSE, GL_FALSE, GL_FALSE, GL_FALSE);
    g.RestoreDepth->Render();
  }
  if (albedoBound)
  {
    g.ProxyAlbedo->Deactivate();
  }
  for (int k = 0; k < g.LightTargets; ++k)
  {
    g.Lit[k]->Deactivate();
  }
  for (vtkTextureObject* input : inputs)
  {
    input->Deactivate();
  }
  ostate->vtkglDepthFunc(GL_LEQUAL);
}

void vtkPGIImageSpaceGIPass::ComposeStatus()
{
  Internals& g = *this->GPU;
  std::ostringstream status;
  status << "image-space GI: " << g.W << "x" << g.H << " pixels, receiver buffer 1/" << g.Scale
         << " (" << g.LowWidth << "x" << g.LowHeight << "), " << g.Proxies << " proxies, "
         << g.Planes << " planes, order " << g.Order << ", "
         << (g.Shadows ? "SHEXP shadows (HYB)" : "no shadows")
         << (g.Indirect ? ", indirect (averaged, expansion " +
                  std::to_string(this->IndirectExpansionFactor) + ")"
                        : "")
         << ", expansion " << g.UsedExpansion
         << (this->AutomaticExpansionFactor ? " (of the light)" : "") << ", "
         << (this->Upsampling == Bilateral ? "bilateral" : "bilinear") << " upsampling";
  for (const std::string& note : this->SettingsNotes)
  {
    status << "; not honoured: " << note;
  }
  this->Status = status.str();
}

//------------------------------------------------------------------------------
void vtkPGIImageSpaceGIPass::Render(const vtkRenderState* s)
{
  vtkOpenGLClearErrorMacro();
  this->NumberOfRenderedProps = 0;
  Internals& g = *this->GPU;
  vtkRenderer* ren = s->GetRenderer();
  auto* window = vtkOpenGLRenderWindow::SafeDownCast(ren->GetRenderWindow());
  if (!this->DelegatePass || !window)
  {
    vtkWarningMacro("No delegate pass or no OpenGL window: nothing rendered.");
    return;
  }
  if (g.Window != window)
  {
    if (g.Window)
    {
      this->ReleaseGraphicsResources(g.Window);
    }
    g.Window = window;
  }
  g.X = g.Y = g.W = g.H = 0;
  if (vtkFrameBufferObjectBase* target = s->GetFrameBuffer())
  {
    target->GetLastSize(g.W, g.H);
  }
  else
  {
    ren->GetTiledSizeAndOrigin(&g.W, &g.H, &g.X, &g.Y);
  }
  std::string why;
  if (!this->PrepareInputs(window, why) ||
    (this->AllocateTargets(window), !this->BuildPrograms(window)))
  {
    this->Status = "image-space GI off: " + (why.empty() ? std::string("shader error") : why);
    this->DelegatePass->Render(s);
    this->NumberOfRenderedProps += this->DelegatePass->GetNumberOfRenderedProps();
    return;
  }
  this->SetUpFrame(ren);
  if (this->MeasurePassTimes)
  {
    glFinish();
    g.Mark = std::chrono::steady_clock::now();
  }
  vtkOpenGLState* ostate = window->GetState();
  vtkOpenGLState::ScopedglEnableDisable blendSaver(ostate, GL_BLEND);
  vtkOpenGLState::ScopedglEnableDisable depthSaver(ostate, GL_DEPTH_TEST);
  vtkOpenGLState::ScopedglEnableDisable cullSaver(ostate, GL_CULL_FACE);
  ostate->PushFramebufferBindings();
  this->RenderReceivers(s, window);
  this->Lap(ReceiverSetupPass);
  this->SplatShadows(window);
  this->Lap(SplattingPass);
  this->Exponentiate(window);
  this->SplatIndirect(window);
  this->Lap(IndirectPass);
  this->ShadeReceiverBuffer(window);
  ostate->PopFramebufferBindings();
  this->Lap(ExponentiationPass);
  this->Upsample(window);
  this->Lap(UpsamplingPass);
  g.HaveFrame = true;
  this->ComposeStatus();
  vtkOpenGLCheckErrorMacro("failed after vtkPGIImageSpaceGIPass::Render");
}
