#include "vtkPGIGICompositePolyDataMapper.h"

// VTK 9.1's vtkCompositeMapperHelper2.h uses GLenum without including it.
#include "vtk_glew.h"

#include "vtkCompositeMapperHelper2.h"
#include "vtkDataObject.h"
#include "vtkInformation.h"
#include "vtkObjectFactory.h"
#include "vtkOpenGLHelper.h"
#include "vtkOpenGLRenderWindow.h"
#include "vtkPolyData.h"
#include "vtkRenderer.h"

#include <algorithm>
#include <vector>

// Draws its blocks as vtkCompositeMapperHelper2 does, with the GI of the
// blocks in its vertex buffer computed first.
class vtkPGIGICompositeMapperHelper : public vtkCompositeMapperHelper2
{
public:
  static vtkPGIGICompositeMapperHelper* New();
  vtkTypeMacro(vtkPGIGICompositeMapperHelper, vtkCompositeMapperHelper2);

  proxygi::gpu::VertexGI GI;

  bool GetBlockResults(vtkPolyData* block, vtkFloatArray* radiance, vtkFloatArray* visibility)
  {
    auto found = this->Data.find(block);
    if (found == this->Data.end())
    {
      return false;
    }
    return this->GI.GetResults(
      found->second->StartVertex, block->GetNumberOfPoints(), radiance, visibility);
  }

  void ReleaseGraphicsResources(vtkWindow* window) override
  {
    this->GI.ReleaseGraphicsResources(window);
    this->Superclass::ReleaseGraphicsResources(window);
  }

protected:
  vtkPGIGICompositeMapperHelper() = default;
  ~vtkPGIGICompositeMapperHelper() override = default;

  vtkPGIGICompositePolyDataMapper* GIParent() const
  {
    return static_cast<vtkPGIGICompositePolyDataMapper*>(this->Parent);
  }

  // After the superclass: it lays the blocks out in the vertex buffer.
  void RenderPieceStart(vtkRenderer* ren, vtkActor* act) override
  {
    this->Superclass::RenderPieceStart(ren, act);
    vtkPGIGICompositePolyDataMapper* parent = this->GIParent();
    std::vector<proxygi::gpu::ReceiverBlock> blocks;
    vtkIdType vertices = 0;
    for (const auto& entry : this->Data)
    {
      vtkCompositeMapperHelperData* hdata = entry.second;
      if (hdata->Data && hdata->Data->GetNumberOfPoints() > 0)
      {
        blocks.push_back({ hdata->Data, static_cast<vtkIdType>(hdata->StartVertex) });
        vertices = std::max(vertices, static_cast<vtkIdType>(hdata->NextVertex));
      }
    }
    bool gi = false;
    if (!parent->Options.GlobalIllumination)
    {
      this->GI.SetStatus("GI off: VTK lighting");
    }
    else if (parent->BakeReady)
    {
      const int before = this->GI.GetNumberOfUpdates();
      gi = this->GI.Update(parent, vtkOpenGLRenderWindow::SafeDownCast(ren->GetRenderWindow()), act,
        blocks, vertices, parent->Scene.Bake, parent->Scene.Notes, parent->Options);
      // Counted by the parent: helpers come and go with the blocks' arrays.
      parent->NumberOfGIUpdates += this->GI.GetNumberOfUpdates() - before;
    }
    this->GI.SetInShaders(gi);
  }

  bool GetNeedToRebuildShaders(vtkOpenGLHelper& cellBO, vtkRenderer* ren, vtkActor* act) override
  {
    return this->Superclass::GetNeedToRebuildShaders(cellBO, ren, act) ||
      cellBO.ShaderSourceTime < this->GI.GetShaderModeTime();
  }

  void ReplaceShaderValues(
    std::map<vtkShader::Type, vtkShader*> shaders, vtkRenderer* ren, vtkActor* act) override
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

  void SetMapperShaderParameters(vtkOpenGLHelper& cellBO, vtkRenderer* ren, vtkActor* act) override
  {
    this->Superclass::SetMapperShaderParameters(cellBO, ren, act);
    this->GI.SetShaderParameters(this->Parent, cellBO, this->GIParent()->Options);
  }

private:
  vtkPGIGICompositeMapperHelper(const vtkPGIGICompositeMapperHelper&) = delete;
  void operator=(const vtkPGIGICompositeMapperHelper&) = delete;
};

vtkStandardNewMacro(vtkPGIGICompositeMapperHelper);

vtkStandardNewMacro(vtkPGIGICompositePolyDataMapper);

vtkPGIGICompositePolyDataMapper::vtkPGIGICompositePolyDataMapper()
  : Scene(this)
{
  this->SetNumberOfInputPorts(2);
}

vtkPGIGICompositePolyDataMapper::~vtkPGIGICompositePolyDataMapper() = default;

pgiGIMapperCommonMembers(vtkPGIGICompositePolyDataMapper)

  int vtkPGIGICompositePolyDataMapper::FillInputPortInformation(int port, vtkInformation* info)
{
  if (port == 1)
  {
    info->Set(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), "vtkPolyData");
    info->Set(vtkAlgorithm::INPUT_IS_OPTIONAL(), 1);
    return 1;
  }
  return this->Superclass::FillInputPortInformation(port, info);
}

vtkCompositeMapperHelper2* vtkPGIGICompositePolyDataMapper::CreateHelper()
{
  return vtkPGIGICompositeMapperHelper::New();
}

void vtkPGIGICompositePolyDataMapper::Render(vtkRenderer* ren, vtkActor* act)
{
  // One bake for every helper, brought up to date once per render.
  vtkDataObject* input = this->GetInputDataObject(0, 0);
  const double points =
    input ? static_cast<double>(input->GetNumberOfElements(vtkDataObject::POINT)) : 0.0;
  this->BakeReady =
    this->Options.GlobalIllumination && this->Scene.PrepareBake(this->GetProxies(), points);
  this->Superclass::Render(ren, act);
}

bool vtkPGIGICompositePolyDataMapper::GetPerVertexResults(
  vtkPolyData* block, vtkFloatArray* radiance, vtkFloatArray* visibility)
{
  for (const auto& entry : this->Helpers)
  {
    auto* helper = static_cast<vtkPGIGICompositeMapperHelper*>(entry.second);
    if (helper->GetBlockResults(block, radiance, visibility))
    {
      return true;
    }
  }
  return false;
}

std::string vtkPGIGICompositePolyDataMapper::GetGIStatus()
{
  std::string status;
  for (const auto& entry : this->Helpers)
  {
    const std::string& one =
      static_cast<vtkPGIGICompositeMapperHelper*>(entry.second)->GI.GetStatus();
    status += (status.empty() ? "" : " | ") + one;
  }
  return status.empty() ? std::string("GI: nothing drawn yet") : this->Scene.WithBudget(status);
}

void vtkPGIGICompositePolyDataMapper::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "Proxies: " << this->GetProxies() << "\n";
  this->Scene.PrintSelf(os, indent, this->Options);
  os << indent << "NumberOfGIUpdates: " << this->GetNumberOfGIUpdates() << "\n";
  os << indent << "GIStatus: " << this->GetGIStatus() << "\n";
}
