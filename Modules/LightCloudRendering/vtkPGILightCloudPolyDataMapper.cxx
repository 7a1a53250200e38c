#include "vtkPGILightCloudPolyDataMapper.h"

#include "pgiLightCloudMapperFS.h"
#include "pgiLightCloudMapperFSImpl.h"
#include "pgiLightCloudMapperVS.h"
#include "pgiLightCloudMapperVSImpl.h"
#include "pgiSHBasisCloudGLSL.h"
#include "pgiSRGBCloudGLSL.h"
#include "vtkPGILightCloud.h"
#include "vtkPGILighting.h"

#include "vtkActor.h"
#include "vtkCamera.h"
#include "vtkMatrix4x4.h"
#include "vtkObjectFactory.h"
#include "vtkOpenGLBufferObject.h"
#include "vtkOpenGLHelper.h"
#include "vtkOpenGLRenderWindow.h"
#include "vtkOpenGLVertexArrayObject.h"
#include "vtkOpenGLVertexBufferObject.h"
#include "vtkOpenGLVertexBufferObjectGroup.h"
#include "vtkPolyData.h"
#include "vtkRenderer.h"
#include "vtkShaderProgram.h"
#include "vtkSmartPointer.h"
#include "vtkTextureObject.h"
#include "vtkTimeStamp.h"
#include "vtk_glew.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <sstream>
#include <string>
#include <vector>

vtkStandardNewMacro(vtkPGILightCloudPolyDataMapper);
vtkCxxSetObjectMacro(vtkPGILightCloudPolyDataMapper, Cloud, vtkPGILightCloud);

namespace
{
// Floats into `buffer` and a one-component texture buffer over them.
bool TextureBuffer(vtkOpenGLRenderWindow* window, const std::vector<float>& values,
  vtkOpenGLBufferObject* buffer, vtkSmartPointer<vtkTextureObject>& texture)
{
  if (!buffer->Upload(values, vtkOpenGLBufferObject::TextureBuffer))
  {
    return false;
  }
  if (texture)
  {
    texture->ReleaseGraphicsResources(window);
  }
  texture = vtkSmartPointer<vtkTextureObject>::New();
  texture->SetContext(window);
  return texture->CreateTextureBuffer(
    static_cast<unsigned int>(values.size()), 1, VTK_FLOAT, buffer);
}
} // namespace

struct vtkPGILightCloudPolyDataMapper::Internals
{
  vtkOpenGLRenderWindow* Window = nullptr;
  vtkNew<vtkOpenGLBufferObject> Codes;   // per point: 4 floats
  vtkNew<vtkOpenGLBufferObject> Data;    // compressed: the PCA weights; dense: the responses
  vtkNew<vtkOpenGLBufferObject> Vectors; // per frame
  vtkSmartPointer<vtkTextureObject> DataTexture, VectorTexture;
  // What the static upload was made from.
  const void* Cloud = nullptr;
  vtkMTimeType CloudTime = 0;
  vtkMTimeType InputTime = 0;
  bool Uploaded = false;
  // Compressed: per zone, its first vector in the frame's buffer (vector
  // 0 is zero: receivers in no zone point at it).
  std::vector<std::size_t> ZoneBase;
  std::size_t VectorCount = 0;
  // The frame.
  vtkMTimeType RelightTime = 0;
  vtkMTimeType FrameCloudTime = 0;
  bool HaveFrame = false;
  bool InShaders = false;
  bool Compressed = false;
  int Stride = 3, Varyings = 1, Order = 1, DenseCount = 0;
  std::vector<std::string> Plan;
  std::string ShaderKey;
  vtkTimeStamp ShaderKeyTime;
  std::string LastError;
  std::string Described; // the last recomputed frame, for the status

  void Release()
  {
    if (this->DataTexture)
    {
      this->DataTexture->ReleaseGraphicsResources(this->Window);
    }
    if (this->VectorTexture)
    {
      this->VectorTexture->ReleaseGraphicsResources(this->Window);
    }
    this->DataTexture = nullptr;
    this->VectorTexture = nullptr;
    this->Codes->ReleaseGraphicsResources();
    this->Data->ReleaseGraphicsResources();
    this->Vectors->ReleaseGraphicsResources();
    this->Uploaded = false;
    this->HaveFrame = false;
    this->Cloud = nullptr;
  }
};

vtkPGILightCloudPolyDataMapper::vtkPGILightCloudPolyDataMapper()
  : GPU(new Internals)
{
  // On its own the cloud adds to VTK's lighting; GI is asked for.
  this->Options.GlobalIllumination = false;
  this->Options.CombineWithVTKLighting = true;
}

vtkPGILightCloudPolyDataMapper::~vtkPGILightCloudPolyDataMapper()
{
  this->SetCloud(nullptr);
}

vtkMTimeType vtkPGILightCloudPolyDataMapper::GetMTime()
{
  vtkMTimeType t = std::max(this->Superclass::GetMTime(), this->Relight->GetMTime());
  return this->Cloud ? std::max(t, this->Cloud->GetMTime()) : t;
}

void vtkPGILightCloudPolyDataMapper::ReleaseGraphicsResources(vtkWindow* window)
{
  this->GPU->Release();
  this->GPU->Window = nullptr;
  this->Superclass::ReleaseGraphicsResources(window);
}

bool vtkPGILightCloudPolyDataMapper::UpdateCloudLight(vtkRenderer* ren)
{
  Internals& g = *this->GPU;
  vtkPolyData* input = this->CurrentInput;
  auto refuse = [&](const std::string& why)
  {
    this->Status = "light cloud: " + why +
      (this->Options.GlobalIllumination ? ": the GI mapper's light only" : ": VTK lighting only");
    // Tried again next frame (cheap: the checks come before any upload).
    g.HaveFrame = false;
    if (why != g.LastError)
    {
      vtkErrorMacro(<< "Light cloud not drawn: " << why << ".");
      g.LastError = why;
    }
    return false;
  };
  if (!this->Cloud)
  {
    return refuse("no cloud (SetCloud)");
  }
  if (!input || input->GetNumberOfPoints() == 0)
  {
    this->Status = "light cloud: nothing to draw";
    return false;
  }
  auto* window = vtkOpenGLRenderWindow::SafeDownCast(ren->GetRenderWindow());
  if (!window)
  {
    return refuse("not an OpenGL render window");
  }
  if (g.Window != window)
  {
    g.Release();
    g.Window = window;
  }
  const int coefficients = this->Cloud->GetCoefficients();
  const int order = static_cast<int>(std::lround(std::sqrt(coefficients)));
  if (coefficients > 1 && order > 6)
  {
    return refuse("glossy order " + std::to_string(order) +
      " is above the GPU basis's 6 (use vtkPGILightCloudRelight)");
  }

  std::string why;
  if (!g.Uploaded || g.Cloud != this->Cloud || g.CloudTime != this->Cloud->GetMTime() ||
    g.InputTime != input->GetMTime())
  {
    why += "cloud; ";
  }
  if (!g.HaveFrame || g.RelightTime != this->Relight->GetMTime())
  {
    why += "lights; ";
  }
  const bool perFragment =
    coefficients > 1 && this->GlossyPerFragment && order <= MaxPerFragmentOrder;
  const int varyings = perFragment ? coefficients : 1;
  const std::string key = std::to_string(3 * coefficients) + "/" + std::to_string(varyings);
  if (key != g.ShaderKey)
  {
    why += "shader; ";
  }
  if (why.empty())
  {
    this->Status = g.Described + "; reused (nothing changed)";
    return g.InShaders;
  }

  // The cloud lights' weights: the CPU filter's formula (PrepareFrame).
  vtkPGILightCloudRelight::Frame frame;
  if (!this->Relight->PrepareFrame(input, this->Cloud, frame))
  {
    g.HaveFrame = false;
    return refuse("the relight filter refused the cloud, the receivers or the lights (see its "
                  "error)");
  }
  const vtkIdType n = input->GetNumberOfPoints();
  const int stride = frame.Stride;
  GLint maxTexels = 0;
  glGetIntegerv(GL_MAX_TEXTURE_BUFFER_SIZE, &maxTexels);

  if (why.find("cloud") != std::string::npos)
  {
    // Static: per receiver its code, and the PCA weights or the responses.
    std::vector<float> codes(static_cast<std::size_t>(4) * n, 0.0f);
    std::vector<float> data;
    g.ZoneBase.clear();
    g.VectorCount = 0;
    if (frame.Compressed)
    {
      g.VectorCount = 1; // the zero vector
      for (const vtkPGILightCloud::Zone& zone : this->Cloud->GetZones())
      {
        const std::size_t base = g.VectorCount;
        const std::size_t clusters = zone.BasisCount.size();
        g.ZoneBase.push_back(base);
        const std::size_t weightBase = data.size();
        data.insert(data.end(), zone.Weights.begin(), zone.Weights.end());
        for (std::size_t r = 0; r < zone.Receivers.size(); ++r)
        {
          const int q = zone.Cluster[r];
          float* code = &codes[4 * static_cast<std::size_t>(zone.Receivers[r])];
          code[0] = static_cast<float>(base + q);
          code[1] = static_cast<float>(base + clusters + zone.BasisStart[q]);
          code[2] = static_cast<float>(zone.BasisCount[q]);
          code[3] = static_cast<float>(weightBase + zone.WeightStart[r]);
        }
        g.VectorCount += clusters + zone.Basis.size() / std::max(1, zone.Dimension);
      }
      if (data.empty())
      {
        data.push_back(0.0f);
      }
    }
    else
    {
      const vtkIdType lights = this->Cloud->GetNumberOfLights();
      const double texels = static_cast<double>(lights) * n * stride;
      if (texels > maxTexels)
      {
        return refuse("the dense cloud's " + std::to_string(static_cast<long long>(texels)) +
          " floats exceed the GPU's texture buffer limit of " + std::to_string(maxTexels) +
          " (compress the cloud)");
      }
      data.resize(static_cast<std::size_t>(texels));
      for (vtkIdType j = 0; j < lights; ++j)
      {
        const float* x = this->Cloud->GetResponse(j);
        std::copy(x, x + static_cast<std::size_t>(n) * stride,
          data.begin() + static_cast<std::ptrdiff_t>(j) * n * stride);
      }
      for (vtkIdType i = 0; i < n; ++i)
      {
        codes[4 * static_cast<std::size_t>(i)] = static_cast<float>(i);
      }
    }
    if (static_cast<double>(std::max(data.size(), g.VectorCount * stride)) > maxTexels)
    {
      return refuse("the cloud exceeds the GPU's texture buffer limit of " +
        std::to_string(maxTexels) + " floats");
    }
    if (!g.Codes->Upload(codes, vtkOpenGLBufferObject::ArrayBuffer) ||
      !TextureBuffer(window, data, g.Data, g.DataTexture))
    {
      return refuse("could not upload the cloud");
    }
    g.Cloud = this->Cloud;
    g.CloudTime = this->Cloud->GetMTime();
    g.InputTime = input->GetMTime();
    g.Uploaded = true;
  }

  // Per frame: the compressed cloud's x_m and b_i, or the dense weights.
  std::vector<float> vectors;
  if (frame.Compressed)
  {
    vectors.assign(g.VectorCount * stride, 0.0f);
    for (std::size_t z = 0; z < frame.ZoneVectors.size() && z < g.ZoneBase.size(); ++z)
    {
      std::transform(frame.ZoneVectors[z].begin(), frame.ZoneVectors[z].end(),
        vectors.begin() + static_cast<std::ptrdiff_t>(g.ZoneBase[z] * stride),
        [](double v) { return static_cast<float>(v); });
    }
    g.DenseCount = 0;
  }
  else
  {
    for (std::size_t q = 0; q < frame.DenseLights.size(); ++q)
    {
      vectors.push_back(static_cast<float>(frame.DenseLights[q]));
      for (int c = 0; c < 3; ++c)
      {
        vectors.push_back(static_cast<float>(frame.DenseWeights[3 * q + c]));
      }
    }
    g.DenseCount = static_cast<int>(frame.DenseLights.size());
    if (vectors.empty())
    {
      vectors.assign(4, 0.0f);
    }
  }
  if (!TextureBuffer(window, vectors, g.Vectors, g.VectorTexture))
  {
    return refuse("could not upload the frame's vectors");
  }
  g.Compressed = frame.Compressed;
  g.Stride = stride;
  g.Order = coefficients > 1 ? order : 1;
  g.Varyings = varyings;
  if (key != g.ShaderKey)
  {
    g.ShaderKey = key;
    g.ShaderKeyTime.Modified();
  }
  g.Plan = frame.Plan;
  for (std::string& line : g.Plan)
  {
    // The camera is the mapper's view point.
    for (const char* seen : { "seen along the normals", "seen from the view point" })
    {
      const std::size_t at = line.find(seen);
      if (at != std::string::npos)
      {
        line.replace(at, std::strlen(seen), "seen from the camera");
      }
    }
  }
  g.RelightTime = this->Relight->GetMTime();
  g.HaveFrame = true;
  g.InShaders = true;
  g.LastError.clear();
  ++this->LightUpdates;

  std::ostringstream status;
  status << "light cloud on the GPU: ";
  for (std::size_t k = 0; k < g.Plan.size(); ++k)
  {
    status << (k ? "; " : "") << g.Plan[k];
  }
  status << "; sums per vertex ("
         << (g.Compressed ? std::to_string(g.VectorCount) + " cluster vectors"
                          : std::to_string(g.DenseCount) + " cloud lights")
         << ")";
  if (coefficients > 1)
  {
    status << ", glossy SH of order " << order
           << (perFragment ? " per fragment"
                  : this->GlossyPerFragment
                  ? " per vertex (above order " + std::to_string(MaxPerFragmentOrder) + ")"
                  : std::string(" per vertex (GlossyPerFragment off)"));
  }
  g.Described = status.str();
  this->Status = g.Described + "; recomputed (" + why.substr(0, why.size() - 2) + ")";
  return true;
}

void vtkPGILightCloudPolyDataMapper::TakeLightsFromLighting()
{
  vtkPGILighting* lighting = this->GetLighting();
  if (!this->Options.GlobalIllumination || !lighting)
  {
    return;
  }
  this->Relight->SetLights(lighting->GetPointLights());
}

void vtkPGILightCloudPolyDataMapper::RenderPieceStart(vtkRenderer* ren, vtkActor* act)
{
  // CurrentInput is set by RenderPiece before this.
  this->TakeLightsFromLighting();
  this->GPU->InShaders = this->UpdateCloudLight(ren);
  this->Superclass::RenderPieceStart(ren, act);
}

void vtkPGILightCloudPolyDataMapper::RenderPieceFinish(vtkRenderer* ren, vtkActor* act)
{
  Internals& g = *this->GPU;
  if (g.DataTexture)
  {
    g.DataTexture->Deactivate();
  }
  if (g.VectorTexture)
  {
    g.VectorTexture->Deactivate();
  }
  this->Superclass::RenderPieceFinish(ren, act);
}

bool vtkPGILightCloudPolyDataMapper::GetNeedToRebuildShaders(
  vtkOpenGLHelper& cellBO, vtkRenderer* ren, vtkActor* act)
{
  return this->Superclass::GetNeedToRebuildShaders(cellBO, ren, act) ||
    cellBO.ShaderSourceTime < this->GPU->ShaderKeyTime;
}

void vtkPGILightCloudPolyDataMapper::ReplaceShaderValues(
  std::map<vtkShader::Type, vtkShader*> shaders, vtkRenderer* ren, vtkActor* act)
{
  const Internals& g = *this->GPU;
  // With the GI in the shaders the cloud's light goes into its radiance
  // (PGI_EXTRA_RADIANCE) and the GI's code writes the colour; else ours.
  const bool underGI = this->GI.InShaders();
  if (g.InShaders)
  {
    std::ostringstream defines;
    defines << "#define PGI_CLOUD_STRIDE " << g.Stride << "\n"
            << "#define PGI_CLOUD_VARYINGS " << g.Varyings << "\n"
            << "#define PGI_SH_ORDER " << g.Order << "\n"
            << "#define PGI_SH_N2 " << g.Order * g.Order << "\n";
    const bool glossy = g.Stride > 3;
    const bool perFragment = g.Varyings > 1;
    std::string vsDec = pgiLightCloudMapperVS;
    vtkShaderProgram::Substitute(vsDec, "//PGI::Cloud::Defines", defines.str());
    vtkShaderProgram::Substitute(
      vsDec, "//PGI::SHBasis", glossy && !perFragment ? pgiSHBasisCloudGLSL : "");
    std::string fsDec = pgiLightCloudMapperFS;
    vtkShaderProgram::Substitute(fsDec, "//PGI::Cloud::Defines", defines.str());
    vtkShaderProgram::Substitute(fsDec, "//PGI::SHBasis", perFragment ? pgiSHBasisCloudGLSL : "");
    // The GI's declarations (sRGB among them) follow ours.
    vtkShaderProgram::Substitute(fsDec, "//PGI::SRGB", underGI ? "" : pgiSRGBCloudGLSL);
    if (underGI)
    {
      // Ours first, then the GI's (its #ifndef PGI_EXTRA_RADIANCE), then VTK's.
      vtkShaderProgram::Substitute(fsDec, "//VTK::Light::Dec\n", "", false);
      vtkShaderProgram::Substitute(fsDec, "//PGI::UnderGI",
        "#define PGI_EXTRA_RADIANCE pgiCloudRadiance()\n//VTK::Light::Dec");
    }
    std::string vs = shaders[vtkShader::Vertex]->GetSource();
    std::string fs = shaders[vtkShader::Fragment]->GetSource();
    vtkShaderProgram::Substitute(vs, "//VTK::Color::Dec", vsDec, false);
    vtkShaderProgram::Substitute(vs, "//VTK::Color::Impl", pgiLightCloudMapperVSImpl, false);
    vtkShaderProgram::Substitute(fs, "//VTK::Light::Dec", fsDec, false);
    if (!underGI)
    {
      // Ours goes after VTK's lighting: a tag of our own that VTK leaves alone.
      vtkShaderProgram::Substitute(
        fs, "//VTK::Light::Impl", "//VTK::Light::Impl\n//PGI::Cloud::Impl\n", false);
    }
    shaders[vtkShader::Vertex]->SetSource(vs);
    shaders[vtkShader::Fragment]->SetSource(fs);
  }
  this->Superclass::ReplaceShaderValues(shaders, ren, act);
  if (g.InShaders && !underGI)
  {
    std::string fs = shaders[vtkShader::Fragment]->GetSource();
    vtkShaderProgram::Substitute(fs, "//PGI::Cloud::Impl", pgiLightCloudMapperFSImpl, false);
    shaders[vtkShader::Fragment]->SetSource(fs);
  }
}

void vtkPGILightCloudPolyDataMapper::SetMapperShaderParameters(
  vtkOpenGLHelper& cellBO, vtkRenderer* ren, vtkActor* act)
{
  this->Superclass::SetMapperShaderParameters(cellBO, ren, act);
  Internals& g = *this->GPU;
  vtkShaderProgram* program = cellBO.Program;
  if (!g.InShaders || !program || !program->IsAttributeUsed("pgiCloudCodeMC"))
  {
    return;
  }
  cellBO.VAO->Bind();
  if (!cellBO.VAO->AddAttributeArray(
        program, g.Codes.GetPointer(), "pgiCloudCodeMC", 0, 16, VTK_FLOAT, 4, false))
  {
    vtkErrorMacro(<< "Could not bind the light cloud's receiver codes.");
  }
  g.DataTexture->Activate();
  g.VectorTexture->Activate();
  program->SetUniformi("pgiCloudData", g.DataTexture->GetTextureUnit());
  program->SetUniformi("pgiCloudVectors", g.VectorTexture->GetTextureUnit());
  program->SetUniformi("pgiCloudCompressed", g.Compressed ? 1 : 0);
  program->SetUniformi("pgiCloudDenseCount", g.DenseCount);
  program->SetUniformi(
    "pgiCloudReceivers", static_cast<int>(this->CurrentInput->GetNumberOfPoints()));
  if (!this->GI.InShaders())
  {
    program->SetUniformf("pgiCloudExposure", static_cast<float>(this->Options.Exposure));
    program->SetUniformi(
      "pgiCloudCombineWithVTKLighting", this->Options.CombineWithVTKLighting ? 1 : 0);
    program->SetUniformi("pgiCloudSRGBOutput", this->Options.SRGBOutput ? 1 : 0);
  }

  // The camera in the VBO's model frame (shifted and scaled), the actor's
  // linear part for directions.
  double shift[3] = { 0.0, 0.0, 0.0 }, scale[3] = { 1.0, 1.0, 1.0 };
  vtkOpenGLVertexBufferObject* positions = this->VBOs->GetVBO("vertexMC");
  if (positions && positions->GetCoordShiftAndScaleEnabled())
  {
    const std::vector<double>& s = positions->GetShift();
    const std::vector<double>& k = positions->GetScale();
    for (int a = 0; a < 3 && a < static_cast<int>(s.size()) && a < static_cast<int>(k.size()); ++a)
    {
      shift[a] = s[a];
      scale[a] = k[a];
    }
  }
  double camera[4] = { 0.0, 0.0, 0.0, 1.0 };
  ren->GetActiveCamera()->GetPosition(camera);
  vtkNew<vtkMatrix4x4> worldToModel;
  vtkMatrix4x4::Invert(act->GetMatrix(), worldToModel);
  double cameraMC[4];
  worldToModel->MultiplyPoint(camera, cameraMC);
  float cameraVBO[3], scaleVBO[3], modelToWorld[9];
  for (int a = 0; a < 3; ++a)
  {
    const double w = cameraMC[3] != 0.0 ? cameraMC[3] : 1.0;
    cameraVBO[a] = static_cast<float>((cameraMC[a] / w - shift[a]) * scale[a]);
    scaleVBO[a] = static_cast<float>(scale[a]);
  }
  // Column-major for GLSL.
  for (int r = 0; r < 3; ++r)
  {
    for (int c = 0; c < 3; ++c)
    {
      modelToWorld[3 * c + r] = static_cast<float>(act->GetMatrix()->GetElement(r, c));
    }
  }
  program->SetUniform3f("pgiCloudCamera", cameraVBO);
  program->SetUniform3f("pgiCloudVBOScale", scaleVBO);
  program->SetUniformMatrix3x3("pgiCloudModelToWorld", modelToWorld);
}

void vtkPGILightCloudPolyDataMapper::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "Cloud: " << this->Cloud << "\n";
  os << indent << "GlossyPerFragment: " << this->GlossyPerFragment << "\n";
  os << indent << "NumberOfLightUpdates: " << this->LightUpdates << "\n";
  os << indent << "Status: " << this->Status << "\n";
  os << indent << "Relight:\n";
  this->Relight->PrintSelf(os, indent.GetNextIndent());
}
