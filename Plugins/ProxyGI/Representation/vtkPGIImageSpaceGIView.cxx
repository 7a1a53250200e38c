#include "vtkPGIImageSpaceGIView.h"

#include "vtkAlgorithm.h"
#include "vtkObjectFactory.h"
#include "vtkPGIGatherProxies.h"
#include "vtkPGIImageSpaceGIPass.h"
#include "vtkPVSynchronizedRenderer.h"

#include <string>

vtkStandardNewMacro(vtkPGIImageSpaceGIView);

vtkPGIImageSpaceGIView::vtkPGIImageSpaceGIView()
  : Pass(vtkPGIImageSpaceGIPass::New())
  , Gather(vtkPGIGatherProxies::New())
{
  this->SynchronizedRenderers->SetRenderPass(this->Pass);
  this->SynchronizedRenderers->SetUseDepthBuffer(true);
}

vtkPGIImageSpaceGIView::~vtkPGIImageSpaceGIView()
{
  this->Pass->Delete();
  this->Gather->Delete();
}

void vtkPGIImageSpaceGIView::SetProxiesAlgorithm(vtkAlgorithm* source)
{
  // Under MPI every rank's pass splats every rank's proxies.
  this->Gather->SetInputConnection(source ? source->GetOutputPort(0) : nullptr);
  this->Pass->SetProxiesConnection(source ? this->Gather->GetOutputPort() : nullptr);
}

void vtkPGIImageSpaceGIView::Update()
{
  if (this->Gather->GetNumberOfInputConnections(0) > 0)
  {
    this->Gather->Update();
  }
  this->Superclass::Update();
}

void vtkPGIImageSpaceGIView::SetRemoteRenderingThreshold(double)
{
  this->Superclass::SetRemoteRenderingThreshold(0.0);
}

void vtkPGIImageSpaceGIView::SetSettings(vtkPGIGISettings* settings)
{
  this->Pass->SetSettings(settings);
}

void vtkPGIImageSpaceGIView::SetLighting(vtkPGILighting* lighting)
{
  this->Pass->SetLighting(lighting);
}

void vtkPGIImageSpaceGIView::SetReceiverScale(int scale)
{
  this->Pass->SetReceiverScale(scale);
}

void vtkPGIImageSpaceGIView::SetUpsampling(int upsampling)
{
  this->Pass->SetUpsampling(upsampling);
}

void vtkPGIImageSpaceGIView::SetExpansionFactor(double factor)
{
  this->Pass->SetExpansionFactor(factor);
}

void vtkPGIImageSpaceGIView::SetExposure(double exposure)
{
  this->Pass->SetExposure(exposure);
}

const char* vtkPGIImageSpaceGIView::GetGIStatus()
{
  this->GIStatus = this->Pass->GetStatus();
  return this->GIStatus.c_str();
}

void vtkPGIImageSpaceGIView::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "Pass:\n";
  this->Pass->PrintSelf(os, indent.GetNextIndent());
}
