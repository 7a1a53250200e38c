#include "pgiGIShaders.h"

#include "pgiGIComputeFS.h"
#include "pgiGIHarnessVS.h"
#include "pgiGILibrary.h"
#include "pgiGISphericalLights.h"
#include "pgiISLibrary.h"
#include "pgiSHBasisGLSL.h"
#include "pgiSRGBGLSL.h"

#include "pgiMaterial.h"
#include "pgiPlaneLightMap.h"
#include "pgiSHBasis.h"
#include "pgiSHExp.h"
#include "pgiSHLightTables.h"
#include "pgiSHTables.h"
#include "pgiSHTripleProduct.h"
#include "pgiSHZonal.h"
#include "pgiSoftShadows.h"
#include "pgiSphericalLights.h"
#include "vtkPGIGISettings.h"

#include "vtkDataArray.h"
#include "vtkNew.h"
#include "vtkOpenGLBufferObject.h"
#include "vtkOpenGLRenderWindow.h"
#include "vtkOpenGLShaderCache.h"
#include "vtkOpenGLVertexArrayObject.h"
#include "vtkPointData.h"
#include "vtkPolyData.h"
#include "vtkShaderProgram.h"
#include "vtkSmartPointer.h"
#include "vtkTextureObject.h"
#include "vtkTransformFeedback.h"
#include "vtk_glew.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <sstream>

namespace proxygi
{
namespace gpu
{

namespace
{
// Shortest float literal GLSL reads back to the same float.
std::string FloatLiteral(float v)
{
  char text[64];
  std::snprintf(text, sizeof(text), "%.9g", static_cast<double>(v));
  std::string s(text);
  if (s.find_first_of(".eEn") == std::string::npos)
  {
    s += ".0";
  }
  return s;
}

vtkSmartPointer<vtkTextureObject> FloatTexture(
  vtkOpenGLRenderWindow* window, int width, int height, int components, std::vector<float>& data)
{
  auto texture = vtkSmartPointer<vtkTextureObject>::New();
  texture->SetContext(window);
  texture->SetMinificationFilter(vtkTextureObject::Nearest);
  texture->SetMagnificationFilter(vtkTextureObject::Nearest);
  texture->SetWrapS(vtkTextureObject::ClampToEdge);
  texture->SetWrapT(vtkTextureObject::ClampToEdge);
  if (!texture->Create2DFromRaw(static_cast<unsigned int>(width), static_cast<unsigned int>(height),
        components, VTK_FLOAT, data.data()))
  {
    return nullptr;
  }
  return texture;
}
} // namespace

std::vector<float> PackSpheres(const Blockers& blockers)
{
  std::vector<float> spheres;
  spheres.reserve(4 * blockers.Spheres());
  for (std::size_t i = 0; i < blockers.Spheres(); ++i)
  {
    spheres.insert(spheres.end(), { blockers.X[i], blockers.Y[i], blockers.Z[i], blockers.R[i] });
  }
  return spheres;
}

std::vector<float> PackPlanes(const Blockers& blockers)
{
  std::vector<float> planes;
  for (std::size_t k = 0; k < blockers.Planes(); ++k)
  {
    planes.insert(planes.end(), &blockers.PlaneOrigin[3 * k], &blockers.PlaneOrigin[3 * k] + 3);
    planes.insert(planes.end(), &blockers.PlaneNormal[3 * k], &blockers.PlaneNormal[3 * k] + 3);
  }
  return planes;
}

std::vector<float> PackPlaneAlbedos(const Blockers& blockers)
{
  std::vector<float> albedos(3 * MaxPlanes, 0.0f);
  const std::size_t count = std::min(albedos.size(), blockers.PlaneAlbedo.size());
  std::copy_n(blockers.PlaneAlbedo.begin(), count, albedos.begin());
  return albedos;
}

void UploadProxyAlbedos(vtkOpenGLRenderWindow* window, const Blockers& blockers,
  std::vector<float>& texels, vtkSmartPointer<vtkTextureObject>& texture)
{
  texels.clear();
  const int leaves = static_cast<int>(blockers.Spheres());
  for (int i = 0; i < leaves; ++i)
  {
    const float* a = blockers.Albedo.size() >= 3 * static_cast<std::size_t>(leaves)
      ? &blockers.Albedo[3 * i]
      : nullptr;
    texels.insert(texels.end(), { a ? a[0] : 0.0f, a ? a[1] : 0.0f, a ? a[2] : 0.0f, 1.0f });
  }
  const int width = std::max(1, std::min(leaves, 1024));
  const int rows = std::max(1, (leaves + width - 1) / width);
  texels.resize(4 * static_cast<std::size_t>(width) * rows, 0.0f);
  if (texture)
  {
    texture->ReleaseGraphicsResources(window);
  }
  texture = FloatTexture(window, width, rows, 4, texels);
}

void UploadPlaneLightMaps(
  vtkOpenGLRenderWindow* window, const std::vector<PlaneLightMap>& maps, PlaneLightMapsGL& gl)
{
  FreePlaneLightMaps(window, gl);
  const int planes = std::min(static_cast<int>(maps.size()), MaxPlanes);
  const int directions = planes > 0 ? maps[0].GetNumberOfDirections() : 0;
  if (directions == 0)
  {
    return;
  }
  gl.U.assign(3 * MaxPlanes, 0.0f);
  gl.V.assign(3 * MaxPlanes, 0.0f);
  gl.Frame.assign(4 * MaxPlanes, 0.0f);
  gl.Size.assign(4 * MaxPlanes, 0.0f);
  gl.Dual.assign(4 * MaxPlanes, 0.0f);
  int width = 1, rows = 0;
  for (int k = 0; k < planes; ++k)
  {
    width = std::max(width, maps[k].GetColumns());
    rows += maps[k].GetRows();
  }
  std::vector<float> grid(4 * static_cast<std::size_t>(width) * std::max(1, rows), 0.0f);
  std::vector<float> table(8 * static_cast<std::size_t>(directions) * planes, 0.0f);
  // A plane without a sky table (no environment) keeps zeros: no sky past it.
  const int skyWidth = 3 * (PlaneLightMap::SkyHeights + 1);
  std::vector<float> sky(
    4 * static_cast<std::size_t>(skyWidth) * PlaneLightMap::SkyBins * planes, 0.0f);
  int first = 0;
  for (int k = 0; k < planes; ++k)
  {
    const PlaneLightMap& map = maps[k];
    std::copy_n(map.GetU(), 3, &gl.U[3 * k]);
    std::copy_n(map.GetV(), 3, &gl.V[3 * k]);
    map.GetGrid(gl.Frame[4 * k], gl.Frame[4 * k + 1], gl.Frame[4 * k + 2]);
    gl.Frame[4 * k + 3] = map.GetBounded() ? 1.0f : 0.0f;
    const int columns = map.GetColumns(), mapRows = map.GetRows();
    gl.Size[4 * k] = static_cast<float>(columns);
    gl.Size[4 * k + 1] = static_cast<float>(mapRows);
    gl.Size[4 * k + 2] = static_cast<float>(first);
    std::copy_n(map.GetDual1(), 2, &gl.Dual[4 * k]);
    std::copy_n(map.GetDual2(), 2, &gl.Dual[4 * k + 2]);
    const float* s = map.Scales();
    for (int j = 0; j < mapRows; ++j)
    {
      for (int i = 0; i < columns; ++i)
      {
        float* texel = &grid[4 * (static_cast<std::size_t>(first + j) * width + i)];
        std::copy_n(&s[3 * (static_cast<std::size_t>(j) * columns + i)], 3, texel);
      }
    }
    first += mapRows;
    for (int q = 0; q < directions; ++q)
    {
      float* a = &table[4 * (static_cast<std::size_t>(2 * k) * directions + q)];
      float* b = &table[4 * (static_cast<std::size_t>(2 * k + 1) * directions + q)];
      std::copy_n(map.GetDirection(q), 3, a);
      a[3] = map.GetStepU(q);
      b[3] = map.GetStepV(q);
    }
    gl.Points += columns * mapRows;
    const float* from = map.GetSkyTable();
    for (int b = 0; from && b < PlaneLightMap::SkyBins; ++b)
    {
      for (int j = 0; j <= PlaneLightMap::SkyHeights; ++j)
      {
        for (int a = 0; a < 3; ++a)
        {
          const float* t =
            &from[9 * (static_cast<std::size_t>(b) * (PlaneLightMap::SkyHeights + 1) + j) + 3 * a];
          std::copy_n(t, 3,
            &sky[4 *
              ((static_cast<std::size_t>(k) * PlaneLightMap::SkyBins + b) * skyWidth + 3 * j + a)]);
        }
      }
    }
  }
  gl.Grid = FloatTexture(window, width, std::max(1, rows), 4, grid);
  gl.Table = FloatTexture(window, directions, 2 * planes, 4, table);
  gl.Sky = FloatTexture(window, skyWidth, PlaneLightMap::SkyBins * planes, 4, sky);
  gl.Directions = gl.Grid && gl.Table && gl.Sky ? directions : 0;
}

void BindPlaneLightMaps(vtkShaderProgram* program, PlaneLightMapsGL& gl)
{
  program->SetUniformi("pgiPlaneMapDirections", gl.Directions);
  if (gl.Directions == 0)
  {
    return;
  }
  gl.Grid->Activate();
  gl.Table->Activate();
  gl.Sky->Activate();
  program->SetUniformi("pgiPlaneMapGrid", gl.Grid->GetTextureUnit());
  program->SetUniformi("pgiPlaneMapTable", gl.Table->GetTextureUnit());
  program->SetUniformi("pgiPlaneMapSky", gl.Sky->GetTextureUnit());
  program->SetUniformi("pgiPlaneSkyBins", PlaneLightMap::SkyBins);
  program->SetUniformi("pgiPlaneSkyHeights", PlaneLightMap::SkyHeights);
  program->SetUniformi("pgiPlaneSkyRows", PlaneLightMap::SkyRows);
  program->SetUniform3fv("pgiPlaneMapU", MaxPlanes, gl.U.data());
  program->SetUniform3fv("pgiPlaneMapV", MaxPlanes, gl.V.data());
  program->SetUniform4fv("pgiPlaneMapFrame", MaxPlanes, gl.Frame.data());
  program->SetUniform4fv("pgiPlaneMapSize", MaxPlanes, gl.Size.data());
  program->SetUniform4fv("pgiPlaneMapDual", MaxPlanes, gl.Dual.data());
}

void FreePlaneLightMaps(vtkWindow* window, PlaneLightMapsGL& gl)
{
  for (auto* texture : { gl.Grid.Get(), gl.Table.Get(), gl.Sky.Get() })
  {
    if (texture)
    {
      texture->ReleaseGraphicsResources(window);
    }
  }
  gl = PlaneLightMapsGL();
}

void ReleasePlaneLightMaps(PlaneLightMapsGL& gl)
{
  if (gl.Directions > 0)
  {
    gl.Grid->Deactivate();
    gl.Table->Deactivate();
    gl.Sky->Deactivate();
  }
}

vtkPGIGISettings::Support KernelSupport(const char* backend, int maxOrder)
{
  vtkPGIGISettings::Support s;
  s.Backend = backend;
  s.MinOrder = MinOrder;
  s.MaxOrder = maxOrder;
  s.ExpMethods = 1u << vtkPGIGISettings::EXP_HYB;
  s.ExpDegree = false;
  s.AccumulationOrder = false;
  s.WindowSize = false;
  s.ShadingPaths = 1u << vtkPGIGISettings::SHADING_PRODUCT_MATRIX;
  s.Hierarchy = false;
  s.SelfVisibility = false;
  s.BrightLights = false;
  s.IndirectOrder = false;
  s.LightCloud = false;
  s.IndirectOperators = 1u << vtkPGIGISettings::INDIRECT_AVERAGED;
  return s;
}

KernelSettings KernelSettingsOf(vtkPGIGISettings* settings)
{
  KernelSettings k;
  k.MinBlockerAngle = settings->GetMinBlockerAngle();
  k.SelfShadowRules = settings->GetSelfShadowRules();
  k.HybridMaxNorm = settings->GetHybridMaxNorm();
  k.RangeTolerance = settings->GetRangeTolerance();
  return k;
}

std::string SquareSource(int order)
{
  const sh::TripleProduct& tp = sh::TripleProduct::Get(order);
  std::ostringstream code;
  // Same terms, same order, same float coefficients as Square<float>.
  for (const sh::TripleProduct::Term& t : tp.Terms())
  {
    const float v = t.J == t.K ? t.ValueF : 2.0f * t.ValueF;
    code << "  o[" << t.I << "] += " << FloatLiteral(v) << " * f[" << t.J << "] * f[" << t.K
         << "];\n";
  }
  return code.str();
}

std::string LibrarySource(int order)
{
  std::ostringstream defines;
  // 'precise' (GLSL 4.00, or ARB_gpu_shader5) where the driver has it: no
  // FMA contraction in the few places where rounding decides (see
  // pgiReplaceBlocker).
  defines << "#ifdef GL_ARB_gpu_shader5\n"
          << "#extension GL_ARB_gpu_shader5 : enable\n"
          << "#define PGI_PRECISE precise\n"
          << "#else\n"
          << "#define PGI_PRECISE\n"
          << "#endif\n"
          << "#define PGI_SH_ORDER " << order << "\n"
          << "#define PGI_SH_N2 " << order * order << "\n"
          << "#define PGI_MAX_PLANES " << MaxPlanes << "\n";
  std::string library = pgiGILibrary;
  vtkShaderProgram::Substitute(library, "//PGI::Square::Impl", SquareSource(order));
  return defines.str() + pgiSHBasisGLSL + "\n" + library + pgiSRGBGLSL;
}

std::string IndirectLibrarySource()
{
  return pgiISLibrary;
}

std::string SphericalLightsLibrarySource(int lights)
{
  const int size = 32 * std::max(1, (lights + 31) / 32);
  return "#define PGI_MAX_SPHERICAL_LIGHTS " + std::to_string(size) + "\n" + pgiGISphericalLights;
}

//------------------------------------------------------------------------------
struct GIResources::Internals
{
  int Order = 0;
  vtkOpenGLRenderWindow* Window = nullptr;
  vtkSmartPointer<vtkTextureObject> CapLog, OL, LightMatrix, Proxies;
  // Cap visibility and the averaged-indirect D(theta) (indirect light).
  vtkSmartPointer<vtkTextureObject> CapVis, DTable;
  int DResolution = 0;
  float DThetaScale = 0.0f;
  int CapResolution = 0, OLResolution = 0;
  float CapThetaScale = 0.0f, OLScale = 0.0f;
  std::vector<float> TransferZH;
  std::vector<float> Light;           // n2 x 3
  std::vector<float> LightAbove;      // n2 x 3, the light above the planes
  std::vector<float> LightMatrixData; // 2 n2 rows of n2 RGBA: L, then the light above
  bool AboveSet = false;
  bool LightDirty = false;
  std::vector<float> Spheres, Planes;
  bool BlockersDirty = true;
  // AnalyticLightTables' lobe table (local lights), built on demand.
  bool WantLobes = false;
  vtkSmartPointer<vtkTextureObject> Lobes;
  int LobeThetaResolution = 0, LobePhiResolution = 0;
  // Spherical lights (shadowed bounce): geometry + object/ratio rows,
  // radiance rows, intersecting partners (count, indices); w_theta. Uploaded on Bind when dirty.
  std::vector<float> SLGeometry, SLRadiance, SLPartners;
  int SLPartnerWidth = 1;
  int SLCount = 0;
  bool SLPerObject = false, SLDirty = false;
  vtkSmartPointer<vtkTextureObject> SLGeometryTexture, SLRadianceTexture, SLPartnersTexture, WTable;
  int ProxyTextureWidth = 1;
  KernelSettings Settings;
};

GIResources::GIResources()
  : Impl(new Internals)
{
}

GIResources::~GIResources() = default;

int GIResources::GetOrder() const
{
  return this->Impl->Order;
}

bool GIResources::SetOrder(vtkOpenGLRenderWindow* window, int order)
{
  Internals& d = *this->Impl;
  if (order < MinOrder || order > MaxOrder || !window)
  {
    return false;
  }
  if (d.Order == order && d.Window == window && d.CapLog && d.OL && d.CapVis && d.DTable)
  {
    return true;
  }
  if (d.Window && d.Window != window)
  {
    this->ReleaseGraphicsResources(d.Window);
  }
  d.Window = window;
  d.Order = order;
  const sh::CapTables& tables = sh::CapTables::Get(order);
  d.CapResolution = tables.GetResolution();
  d.CapThetaScale = static_cast<float>((d.CapResolution - 1) / sh::CapTables::MaxAngle);
  std::vector<float> log(tables.GetLogTable().begin(), tables.GetLogTable().end());
  d.CapLog = FloatTexture(window, order, d.CapResolution, 1, log);
  std::vector<float> vis(tables.GetVisibilityTable().begin(), tables.GetVisibilityTable().end());
  d.CapVis = FloatTexture(window, order, d.CapResolution, 1, vis);
  const sh::IndirectTables& indirect = sh::IndirectTables::Get(order);
  d.DResolution = indirect.GetResolution();
  d.DThetaScale = static_cast<float>((d.DResolution - 1) / sh::IndirectTables::MaxAngle);
  std::vector<float> averaged(
    indirect.GetAveragedIndirectTable().begin(), indirect.GetAveragedIndirectTable().end());
  d.DTable = FloatTexture(window, order, d.DResolution, 1, averaged);
  d.OLResolution = tables.GetResolution();
  d.OLScale = static_cast<float>((d.OLResolution - 1) / tables.GetOptimalLinearMaxNorm());
  std::vector<float> ol(2 * d.OLResolution);
  for (int i = 0; i < d.OLResolution; ++i)
  {
    ol[2 * i] = static_cast<float>(tables.GetOptimalLinearA()[i]);
    ol[2 * i + 1] = static_cast<float>(tables.GetOptimalLinearB()[i]);
  }
  d.OL = FloatTexture(window, d.OLResolution, 1, 2, ol);
  // Scaled ZH of H(N): DiffuseTransfer at +z over the basis at +z, per band.
  double h[sh::MaxCoefficients], y[sh::MaxCoefficients];
  sh::DiffuseTransfer(order, 0.0, 0.0, 1.0, h);
  sh::EvaluateBasis(order, 0.0, 0.0, 1.0, y);
  d.TransferZH.resize(order);
  for (int l = 0; l < order; ++l)
  {
    d.TransferZH[l] = static_cast<float>(h[sh::Index(l, 0)] / y[sh::Index(l, 0)]);
  }
  d.LightMatrix = nullptr;
  d.Light.assign(3 * order * order, 0.0f);
  d.LightAbove.assign(3 * order * order, 0.0f);
  d.LightMatrixData.assign(2 * 4 * order * order * order * order, 0.0f);
  d.AboveSet = false;
  d.LightDirty = true;
  d.BlockersDirty = true;
  d.Lobes = nullptr;
  // Spherical lights of another order are stale: none until set again.
  d.WTable = nullptr;
  d.SLCount = 0;
  d.SLDirty = true;
  return d.CapLog && d.OL && d.CapVis && d.DTable;
}

namespace
{
// One light's vector and product matrix into the rows of light `which`.
void StoreLight(int order, const double* red, const double* green, const double* blue,
  std::vector<float>& vector, std::vector<float>& matrix, int which)
{
  const int n2 = order * order;
  const double* channels[3] = { red, green, blue };
  const sh::TripleProduct& tp = sh::TripleProduct::Get(order);
  std::vector<double> m(n2 * n2);
  const std::size_t first = 4 * static_cast<std::size_t>(which) * n2 * n2;
  for (int c = 0; c < 3; ++c)
  {
    for (int i = 0; i < n2; ++i)
    {
      vector[3 * i + c] = static_cast<float>(channels[c][i]);
    }
    tp.ProductMatrix(channels[c], m.data());
    for (int i = 0; i < n2; ++i)
    {
      for (int j = 0; j < n2; ++j)
      {
        matrix[first + 4 * (i * n2 + j) + c] = static_cast<float>(m[i * n2 + j]);
      }
    }
  }
}
} // namespace

void GIResources::SetLight(const double* red, const double* green, const double* blue)
{
  Internals& d = *this->Impl;
  if (d.Order == 0)
  {
    return;
  }
  StoreLight(d.Order, red, green, blue, d.Light, d.LightMatrixData, 0);
  if (!d.AboveSet)
  {
    StoreLight(d.Order, red, green, blue, d.LightAbove, d.LightMatrixData, 1);
  }
  d.LightDirty = true;
}

void GIResources::SetLightAbovePlanes(const double* red, const double* green, const double* blue)
{
  Internals& d = *this->Impl;
  if (d.Order == 0)
  {
    return;
  }
  if (!red || !green || !blue)
  {
    // Back to L: copy light 0's rows.
    const std::size_t half = d.LightMatrixData.size() / 2;
    std::copy(d.LightMatrixData.begin(), d.LightMatrixData.begin() + half,
      d.LightMatrixData.begin() + half);
    d.LightAbove = d.Light;
    d.AboveSet = false;
  }
  else
  {
    StoreLight(d.Order, red, green, blue, d.LightAbove, d.LightMatrixData, 1);
    d.AboveSet = true;
  }
  d.LightDirty = true;
}

void GIResources::SetAnalyticLightTable(bool use)
{
  this->Impl->WantLobes = use;
}

double GIResources::GetAnalyticLightMinTheta() const
{
  const int order = this->Impl->Order;
  return order > 0 ? sh::AnalyticLightTables::MaxTheta /
      (sh::AnalyticLightTables::Get(order).GetThetaResolution() - 1)
                   : 0.0;
}

void GIResources::SetSphericalLights(const SphericalLights* lights, bool perObject)
{
  Internals& d = *this->Impl;
  d.SLCount = lights ? static_cast<int>(lights->Count()) : 0;
  d.SLPerObject = perObject;
  d.SLDirty = true;
  d.SLGeometry.clear();
  d.SLRadiance.clear();
  d.SLPartners.clear();
  if (d.SLCount == 0)
  {
    return;
  }
  const std::size_t count = static_cast<std::size_t>(d.SLCount);
  const std::size_t n2 = static_cast<std::size_t>(lights->Order) * lights->Order;
  d.SLGeometry.assign(8 * count, 0.0f);
  std::map<int, int> numbers; // object id -> its number
  d.SLRadiance.assign(4 * n2 * count, 0.0f);
  for (std::size_t i = 0; i < count; ++i)
  {
    float* row0 = &d.SLGeometry[4 * i];
    float* row1 = &d.SLGeometry[4 * (count + i)];
    row0[0] = lights->X[i];
    row0[1] = lights->Y[i];
    row0[2] = lights->Z[i];
    row0[3] = lights->R[i];
    row1[0] = static_cast<float>(lights->Object[i]);
    row1[1] = lights->ReflectionRatio.empty() ? 1.0f : lights->ReflectionRatio[i];
    const auto known = numbers.emplace(lights->Object[i], static_cast<int>(numbers.size())).first;
    row1[2] = static_cast<float>(known->second);
    for (std::size_t t = 0; t < n2 && lights->Radiance.size() == 3 * n2 * count; ++t)
    {
      for (std::size_t c = 0; c < 3; ++c)
      {
        d.SLRadiance[4 * (i * n2 + t) + c] = lights->Radiance[(i * 3 + c) * n2 + t];
      }
    }
  }
  std::vector<std::vector<float>> partners(count);
  std::size_t most = 0;
  for (std::size_t i = 0; i < count && lights->Intersects.size() == count * count; ++i)
  {
    for (std::size_t j = 0; j < count; ++j)
    {
      if (lights->Intersects[i * count + j])
      {
        partners[i].push_back(static_cast<float>(j));
      }
    }
    most = std::max(most, partners[i].size());
  }
  d.SLPartnerWidth = static_cast<int>(most + 1);
  d.SLPartners.assign(count * (most + 1), 0.0f);
  for (std::size_t i = 0; i < count; ++i)
  {
    d.SLPartners[i * (most + 1)] = static_cast<float>(partners[i].size());
    std::copy(partners[i].begin(), partners[i].end(), &d.SLPartners[i * (most + 1) + 1]);
  }
}

void GIResources::SetBlockers(const std::vector<float>& spheres, const std::vector<float>& planes)
{
  Internals& d = *this->Impl;
  d.Spheres = spheres;
  d.Planes.assign(planes.begin(),
    planes.begin() + std::min<std::size_t>(planes.size(), 6 * static_cast<std::size_t>(MaxPlanes)));
  d.BlockersDirty = true;
}

void GIResources::SetSettings(const KernelSettings& settings)
{
  this->Impl->Settings = settings;
}

void GIResources::Bind(vtkShaderProgram* program)
{
  Internals& d = *this->Impl;
  if (!d.Window || d.Order == 0)
  {
    return;
  }
  const int n2 = d.Order * d.Order;
  if (d.LightDirty || !d.LightMatrix)
  {
    d.LightMatrix = FloatTexture(d.Window, n2, 2 * n2, 4, d.LightMatrixData);
    d.LightDirty = false;
  }
  if (d.WantLobes && !d.Lobes)
  {
    const sh::AnalyticLightTables& lobes = sh::AnalyticLightTables::Get(d.Order);
    d.LobeThetaResolution = lobes.GetThetaResolution();
    d.LobePhiResolution = lobes.GetPhiResolution();
    std::vector<float> texels(lobes.GetLobeTable().begin(), lobes.GetLobeTable().end());
    d.Lobes =
      FloatTexture(d.Window, d.Order + 1, d.LobeThetaResolution * d.LobePhiResolution, 1, texels);
  }
  if (d.SLDirty)
  {
    d.SLGeometryTexture = d.SLRadianceTexture = d.SLPartnersTexture = nullptr;
    if (d.SLCount > 0)
    {
      const int n2s = d.Order * d.Order;
      d.SLGeometryTexture = FloatTexture(d.Window, d.SLCount, 2, 4, d.SLGeometry);
      d.SLRadianceTexture = FloatTexture(d.Window, n2s, d.SLCount, 4, d.SLRadiance);
      d.SLPartnersTexture = FloatTexture(d.Window, d.SLPartnerWidth, d.SLCount, 1, d.SLPartners);
      if (!d.WTable)
      {
        const sh::IndirectTables& indirect = sh::IndirectTables::Get(d.Order);
        std::vector<float> w(indirect.GetSphericalLightWeightTable().begin(),
          indirect.GetSphericalLightWeightTable().end());
        d.WTable = FloatTexture(d.Window, d.Order, indirect.GetResolution(), 1, w);
      }
    }
    d.SLDirty = false;
  }
  const int spheres = static_cast<int>(d.Spheres.size() / 4);
  if (d.BlockersDirty || !d.Proxies)
  {
    // Rows of up to 1024 spheres; unused texels have radius 0.
    d.ProxyTextureWidth = std::max(1, std::min(spheres, 1024));
    const int rows = std::max(1, (spheres + d.ProxyTextureWidth - 1) / d.ProxyTextureWidth);
    std::vector<float> texels(4 * static_cast<std::size_t>(d.ProxyTextureWidth) * rows, 0.0f);
    std::copy(d.Spheres.begin(), d.Spheres.begin() + 4 * spheres, texels.begin());
    d.Proxies = FloatTexture(d.Window, d.ProxyTextureWidth, rows, 4, texels);
    d.BlockersDirty = false;
  }
  for (vtkTextureObject* t : { d.CapLog.Get(), d.OL.Get(), d.LightMatrix.Get(), d.Proxies.Get(),
         d.CapVis.Get(), d.DTable.Get() })
  {
    if (t)
    {
      t->Activate();
    }
  }
  program->SetUniformi("pgiCapVisTable", d.CapVis->GetTextureUnit());
  program->SetUniformi("pgiDTable", d.DTable->GetTextureUnit());
  program->SetUniformi("pgiDResolution", d.DResolution);
  program->SetUniformf("pgiDThetaScale", d.DThetaScale);
  program->SetUniformi("pgiCapLogTable", d.CapLog->GetTextureUnit());
  program->SetUniformi("pgiCapResolution", d.CapResolution);
  program->SetUniformf("pgiCapThetaScale", d.CapThetaScale);
  program->SetUniformi("pgiOLTable", d.OL->GetTextureUnit());
  program->SetUniformi("pgiOLResolution", d.OLResolution);
  program->SetUniformf("pgiOLScale", d.OLScale);
  const double limit =
    d.Settings.HybridMaxNorm > 0.0 ? d.Settings.HybridMaxNorm : sh::DefaultHybridMaxNorm(d.Order);
  program->SetUniformf("pgiHybridMaxNorm", static_cast<float>(limit));
  program->SetUniformf("pgiRangeTolerance", static_cast<float>(d.Settings.RangeTolerance));
  program->SetUniformi("pgiProxyTexture", d.Proxies->GetTextureUnit());
  program->SetUniformi("pgiProxyTextureWidth", d.ProxyTextureWidth);
  program->SetUniformi("pgiNumProxies", spheres);
  const int planes = static_cast<int>(d.Planes.size() / 6);
  std::vector<float> origins(3 * MaxPlanes, 0.0f), normals(3 * MaxPlanes, 0.0f);
  for (int k = 0; k < planes; ++k)
  {
    std::copy(&d.Planes[6 * k], &d.Planes[6 * k] + 3, &origins[3 * k]);
    std::copy(&d.Planes[6 * k] + 3, &d.Planes[6 * k] + 6, &normals[3 * k]);
  }
  program->SetUniformi("pgiNumPlanes", planes);
  program->SetUniform3fv("pgiPlaneOrigin", MaxPlanes, origins.data());
  program->SetUniform3fv("pgiPlaneNormal", MaxPlanes, normals.data());
  program->SetUniformf("pgiSinMinAngle", std::sin(static_cast<float>(d.Settings.MinBlockerAngle)));
  program->SetUniformi("pgiSelfShadowRules", d.Settings.SelfShadowRules ? 1 : 0);
  program->SetUniform3fv("pgiLight", n2, d.Light.data());
  program->SetUniform3fv("pgiLightAbove", n2, d.LightAbove.data());
  program->SetUniformi("pgiLightMatrix", d.LightMatrix->GetTextureUnit());
  program->SetUniform1fv("pgiTransferZH", d.Order, d.TransferZH.data());
  const bool lights = d.SLGeometryTexture && d.SLRadianceTexture && d.SLPartnersTexture && d.WTable;
  if (lights)
  {
    for (vtkTextureObject* t : { d.SLGeometryTexture.Get(), d.SLRadianceTexture.Get(),
           d.SLPartnersTexture.Get(), d.WTable.Get() })
    {
      t->Activate();
    }
    program->SetUniformi("pgiSLGeometry", d.SLGeometryTexture->GetTextureUnit());
    program->SetUniformi("pgiSLRadiance", d.SLRadianceTexture->GetTextureUnit());
    program->SetUniformi("pgiSLPartners", d.SLPartnersTexture->GetTextureUnit());
    program->SetUniformi("pgiWTable", d.WTable->GetTextureUnit());
    program->SetUniformi("pgiWResolution", d.DResolution);
    program->SetUniformf("pgiWThetaScale", d.DThetaScale);
    program->SetUniformi("pgiSLPerObject", d.SLPerObject ? 1 : 0);
  }
  program->SetUniformi("pgiNumSphericalLights", lights ? d.SLCount : 0);
  if (d.Lobes)
  {
    d.Lobes->Activate();
    program->SetUniformi("pgiLobeTable", d.Lobes->GetTextureUnit());
    program->SetUniformi("pgiLobeThetaResolution", d.LobeThetaResolution);
    program->SetUniformi("pgiLobePhiResolution", d.LobePhiResolution);
    program->SetUniformf("pgiLobeThetaScale",
      static_cast<float>((d.LobeThetaResolution - 1) / sh::AnalyticLightTables::MaxTheta));
    program->SetUniformf("pgiLobePhiScale",
      static_cast<float>((d.LobePhiResolution - 1) / sh::AnalyticLightTables::MaxPhi));
  }
}

void GIResources::Unbind()
{
  Internals& d = *this->Impl;
  for (vtkTextureObject* t : { d.CapLog.Get(), d.OL.Get(), d.LightMatrix.Get(), d.Proxies.Get(),
         d.CapVis.Get(), d.DTable.Get(), d.Lobes.Get(), d.SLGeometryTexture.Get(),
         d.SLRadianceTexture.Get(), d.SLPartnersTexture.Get(), d.WTable.Get() })
  {
    if (t)
    {
      t->Deactivate();
    }
  }
}

void GIResources::ReleaseGraphicsResources(vtkWindow* window)
{
  Internals& d = *this->Impl;
  for (vtkTextureObject* t : { d.CapLog.Get(), d.OL.Get(), d.LightMatrix.Get(), d.Proxies.Get(),
         d.CapVis.Get(), d.DTable.Get(), d.Lobes.Get(), d.SLGeometryTexture.Get(),
         d.SLRadianceTexture.Get(), d.SLPartnersTexture.Get(), d.WTable.Get() })
  {
    if (t)
    {
      t->ReleaseGraphicsResources(window);
    }
  }
  d.CapLog = d.OL = d.LightMatrix = d.Proxies = d.CapVis = d.DTable = d.Lobes = nullptr;
  d.SLGeometryTexture = d.SLRadianceTexture = d.SLPartnersTexture = d.WTable = nullptr;
  d.SLDirty = d.SLCount > 0;
  d.Order = 0;
  d.Window = nullptr;
}

//------------------------------------------------------------------------------
struct GLSLHarness::Internals
{
  vtkOpenGLRenderWindow* Window = nullptr;
  GIResources Resources;
  std::string Error;
};

GLSLHarness::GLSLHarness(vtkOpenGLRenderWindow* window)
  : Impl(new Internals)
{
  this->Impl->Window = window;
}

GLSLHarness::~GLSLHarness()
{
  if (this->Impl->Window)
  {
    this->Impl->Window->MakeCurrent();
    this->Impl->Resources.ReleaseGraphicsResources(this->Impl->Window);
  }
}

GIResources& GLSLHarness::Resources()
{
  return this->Impl->Resources;
}

const std::string& GLSLHarness::GetError() const
{
  return this->Impl->Error;
}

bool GLSLHarness::Run(int order, const std::string& declarations, const std::string& body,
  int inputs, int outputs, const std::vector<float>& in, std::vector<float>& out,
  const std::function<void(vtkShaderProgram*)>& uniforms)
{
  Internals& d = *this->Impl;
  d.Error.clear();
  if (!d.Window || inputs < 1 || outputs < 1 || in.empty() || in.size() % (4 * inputs) != 0)
  {
    d.Error = "bad harness arguments";
    return false;
  }
  d.Window->MakeCurrent();
  if (!d.Resources.SetOrder(d.Window, order))
  {
    d.Error = "could not build the tables' textures";
    return false;
  }
  const int count = static_cast<int>(in.size() / (4 * inputs));
  std::ostringstream dec, varyings;
  vtkNew<vtkTransformFeedback> capture;
  for (int k = 0; k < inputs; ++k)
  {
    dec << "in vec4 pgiIn" << k << ";\n";
  }
  for (int k = 0; k < outputs; ++k)
  {
    dec << "out vec4 pgiOut" << k << ";\n";
    capture->AddVarying(vtkTransformFeedback::Color_RGBA_F, "pgiOut" + std::to_string(k));
  }
  dec << declarations << "\n";
  std::string vs = pgiGIHarnessVS;
  vtkShaderProgram::Substitute(vs, "//PGI::Defines", "");
  vtkShaderProgram::Substitute(vs, "//PGI::Library", LibrarySource(order));
  vtkShaderProgram::Substitute(vs, "//PGI::Harness::Dec", dec.str());
  vtkShaderProgram::Substitute(vs, "//PGI::Harness::Impl", body);
  vtkShaderProgram* program =
    d.Window->GetShaderCache()->ReadyShaderProgram(vs.c_str(), pgiGIComputeFS, "", capture);
  if (!program)
  {
    d.Error = "the harness shader did not compile";
    return false;
  }
  d.Resources.Bind(program);
  if (uniforms)
  {
    uniforms(program);
  }

  vtkNew<vtkOpenGLBufferObject> input;
  input->Upload(in, vtkOpenGLBufferObject::ArrayBuffer);
  vtkNew<vtkOpenGLVertexArrayObject> vao;
  vao->Bind();
  for (int k = 0; k < inputs; ++k)
  {
    const std::string name = "pgiIn" + std::to_string(k);
    if (program->IsAttributeUsed(name.c_str()) &&
      !vao->AddAttributeArray(program, input, name, static_cast<int>(16 * k),
        static_cast<size_t>(16 * inputs), VTK_FLOAT, 4, false))
    {
      d.Error = "could not bind attribute " + name;
    }
  }
  vtkNew<vtkOpenGLBufferObject> result;
  const std::size_t values = static_cast<std::size_t>(count) * 4 * outputs;
  result->Upload(std::vector<float>(values, 0.0f), vtkOpenGLBufferObject::ArrayBuffer);
  glBindBufferBase(GL_TRANSFORM_FEEDBACK_BUFFER, 0, result->GetHandle());
  glEnable(GL_RASTERIZER_DISCARD);
  glBeginTransformFeedback(GL_POINTS);
  glDrawArrays(GL_POINTS, 0, count);
  glEndTransformFeedback();
  glDisable(GL_RASTERIZER_DISCARD);
  glBindBufferBase(GL_TRANSFORM_FEEDBACK_BUFFER, 0, 0);
  vao->Release();
  d.Resources.Unbind();

  out.assign(values, 0.0f);
  glBindBuffer(GL_ARRAY_BUFFER, result->GetHandle());
  glGetBufferSubData(
    GL_ARRAY_BUFFER, 0, static_cast<GLsizeiptr>(values * sizeof(float)), out.data());
  glBindBuffer(GL_ARRAY_BUFFER, 0);
  const GLenum error = glGetError();
  if (error != GL_NO_ERROR)
  {
    d.Error = "OpenGL error " + std::to_string(error) + " in the harness";
  }
  vao->ReleaseGraphicsResources();
  input->ReleaseGraphicsResources();
  result->ReleaseGraphicsResources();
  return d.Error.empty();
}

} // namespace gpu
} // namespace proxygi
