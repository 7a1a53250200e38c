#include "vtkPGIContextRenderWindow.h"

#include "pgiOffscreenWindow.h"
#include "vtkRenderer.h"
#include "vtkRendererCollection.h"
#include "vtk_glew.h"

vtkPGIContextRenderWindow::vtkPGIContextRenderWindow()
{
  this->SetReadyForRendering(true);
  // Offscreen by nature: nothing to show, VTK keeps the image in its buffers.
  this->SetShowWindow(false);
  this->SetUseOffScreenBuffers(true);
  this->SetScreenSize(4096, 4096);
}

vtkPGIContextRenderWindow::~vtkPGIContextRenderWindow()
{
  vtkRenderer* ren;
  vtkCollectionSimpleIterator rit;
  this->Renderers->InitTraversal(rit);
  while ((ren = this->Renderers->GetNextRenderer(rit)))
  {
    ren->SetRenderWindow(nullptr);
  }
}

void vtkPGIContextRenderWindow::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "Renderer: " << this->RendererDescription << "\n";
  os << indent << "ContextError: " << this->ContextError << "\n";
}

bool vtkPGIContextRenderWindow::CreateContext()
{
  if (this->HasContext())
  {
    return true;
  }
  if (this->Failed)
  {
    return false;
  }
  this->Failed = true; // until proven otherwise; no retry storms on every Render
  if (!proxygi::GlewShimActive())
  {
    this->ContextError = "the glewInit shim (libProxyGIGlewShim) is not in effect: link it "
                         "before VTK's libraries with -Wl,--no-as-needed";
    return false;
  }
  if (!this->MakeContext())
  {
    return false;
  }
  const char* renderer = reinterpret_cast<const char*>(glGetString(GL_RENDERER));
  const char* version = reinterpret_cast<const char*>(glGetString(GL_VERSION));
  this->RendererDescription =
    std::string(renderer ? renderer : "?") + ", OpenGL " + (version ? version : "?");
  this->Failed = false;
  this->ContextError.clear();
  return true;
}

void vtkPGIContextRenderWindow::Initialize()
{
  if (this->VTKInitialized)
  {
    return;
  }
  if (!this->CreateContext())
  {
    vtkErrorMacro("No " << this->GetContextKind() << " context: " << this->ContextError);
    return;
  }
  this->MakeCurrent();
  // VTK reads the GL version and sets up its state from the current context.
  this->VTKInitialized = this->InitializeFromCurrentContext();
  this->Mapped = 1;
}

void vtkPGIContextRenderWindow::Start()
{
  this->Initialize();
  this->MakeCurrent();
  this->Superclass::Start();
}

void vtkPGIContextRenderWindow::Finalize()
{
  if (this->HasContext())
  {
    this->MakeCurrent();
    if (this->VTKInitialized)
    {
      this->ReleaseGraphicsResources(this);
    }
  }
  this->VTKInitialized = false;
  this->Mapped = 0;
  this->DestroyContext();
  this->Failed = false;
}

int vtkPGIContextRenderWindow::SupportsOpenGL()
{
  return this->CreateContext() ? 1 : 0;
}

vtkTypeBool vtkPGIContextRenderWindow::IsDirect()
{
  return this->HasContext() ? 1 : 0;
}
