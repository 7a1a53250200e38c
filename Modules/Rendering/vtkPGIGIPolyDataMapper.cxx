#include "vtkPGIGIPolyDataMapper.h"

#include "vtkInformation.h"
#include "vtkObjectFactory.h"
#include "vtkOpenGLHelper.h"
#include "vtkOpenGLRenderWindow.h"
#include "vtkPolyData.h"
#include "vtkRenderer.h"

#include <algorithm>

vtkStandardNewMacro(vtkPGIGIPolyDataMapper);

vtkPGIGIPolyDataMapper::vtkPGIGIPolyDataMapper()
  : Scene(this)
{
  this->SetNumberOfInputPorts(2);
}

vtkPGIGIPolyDataMapper::~vtkPGIGIPolyDataMapper() = default;

int vtkPGIGIPolyDataMapper::FillInputPortInformation(int port, vtkInformation* info)
{
  if (port == 1)
  {
    info->Set(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), "vtkPolyData");
    info->Set(vtkAlgorithm::INPUT_IS_OPTIONAL(), 1);
    return 1;
  }
  return this->Superclass::FillInputPortInformation(port, info);
}

pgiGIMapperCommonMembers(vtkPGIGIPolyDataMapper)

  void vtkPGIGIPolyDataMapper::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "Proxies: " << this->GetProxies() << "\n";
  this->Scene.PrintSelf(os, indent, this->Options);
  os << indent << "NumberOfGIUpdates: " << this->GetNumberOfGIUpdates() << "\n";
  os << indent << "GIStatus: " << this->GetGIStatus() << "\n";
}

void vtkPGIGIPolyDataMapper::ReleaseGraphicsResources(vtkWindow* window)
{
  this->GI.ReleaseGraphicsResources(window);
  this->Superclass::ReleaseGraphicsResources(window);
}

bool vtkPGIGIPolyDataMapper::UpdateGI(vtkRenderer* ren, vtkActor* act)
{
  vtkPolyData* input = this->CurrentInput;
  if (!this->Options.GlobalIllumination || !input || input->GetNumberOfPoints() == 0)
  {
    this->GI.SetStatus(
      !this->Options.GlobalIllumination ? "GI off: VTK lighting" : "GI: nothing to draw");
    return false;
  }
  if (!this->Scene.PrepareBake(this->GetProxies(), static_cast<double>(input->GetNumberOfPoints())))
  {
    return false;
  }
  const bool gi = this->GI.Update(this, vtkOpenGLRenderWindow::SafeDownCast(ren->GetRenderWindow()),
    act, { { input, 0 } }, input->GetNumberOfPoints(), this->Scene.Bake, this->Scene.Notes,
    this->Options);
  this->GI.SetStatus(this->Scene.WithBudget(this->GI.GetStatus()));
  return gi;
}

void vtkPGIGIPolyDataMapper::RenderPieceStart(vtkRenderer* ren, vtkActor* act)
{
  this->GI.SetInShaders(this->UpdateGI(ren, act));
  this->Superclass::RenderPieceStart(ren, act);
}

bool vtkPGIGIPolyDataMapper::GetNeedToRebuildShaders(
  vtkOpenGLHelper& cellBO, vtkRenderer* ren, vtkActor* act)
{
  return this->Superclass::GetNeedToRebuildShaders(cellBO, ren, act) ||
    cellBO.ShaderSourceTime < this->GI.GetShaderModeTime();
}

void vtkPGIGIPolyDataMapper::ReplaceShaderValues(
  std::map<vtkShader::Type, vtkShader*> shaders, vtkRenderer* ren, vtkActor* act)
{
  if (this->GI.InShaders())
  {
    this->GI.ReplaceShaderValuesBefore(shaders);
  }
  this->Superclass::ReplaceShaderValues(shaders, ren, act);
  if (this->GI.InShaders())
  {
    this->GI.ReplaceShaderValuesAfter(shaders);
  }
}

void vtkPGIGIPolyDataMapper::SetMapperShaderParameters(
  vtkOpenGLHelper& cellBO, vtkRenderer* ren, vtkActor* act)
{
  this->Superclass::SetMapperShaderParameters(cellBO, ren, act);
  this->GI.SetShaderParameters(this, cellBO, this->Options);
}

bool vtkPGIGIPolyDataMapper::GetPerVertexResults(vtkFloatArray* radiance, vtkFloatArray* visibility)
{
  return this->GI.GetResults(0, this->GI.GetNumberOfVertices(), radiance, visibility);
}
