// GlobalIlluminationPipeline: the CPU per-vertex GI as a VTK pipeline.
//
//   mesh -> vtkPGISphereSetApproximation (sphere proxies)
//        -> vtkPGISphereLightSampler     (surface samples for shadowed bounce)
//   mesh + proxies + lighting -> vtkPGIGlobalIllumination -> arrays per vertex
//
// A torus-like knot of spheres stands over a ground plane under a uniform
// sky. The filter writes DirectShadowed, IndirectProxy/IndirectShadowed,
// LocalLights and their sum Radiance; the program prints the plan (which
// effects ran and why), the mean radiance and writes gi.vtp for ParaView.
#include "vtkPGIGlobalIllumination.h"
#include "vtkPGILighting.h"
#include "vtkPGISphereLightSampler.h"
#include "vtkPGISphereSetApproximation.h"

#include <vtkAppendPolyData.h>
#include <vtkDataArray.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkPolyData.h>
#include <vtkSMPTools.h>
#include <vtkSphereSource.h>
#include <vtkTriangleFilter.h>
#include <vtkXMLPolyDataWriter.h>

#include <cmath>
#include <cstdio>

int main()
{
  vtkSMPTools::SetBackend("STDThread"); // all cores (Debian's VTK defaults to one)

  // The receiver and occluder: six overlapping balls in a ring, above z = 0.
  vtkNew<vtkAppendPolyData> ring;
  for (int k = 0; k < 6; ++k)
  {
    vtkNew<vtkSphereSource> ball;
    const double a = 2.0 * 3.14159265358979 * k / 6.0;
    ball->SetCenter(std::cos(a), std::sin(a), 0.6);
    ball->SetRadius(0.5);
    ball->SetThetaResolution(48);
    ball->SetPhiResolution(24);
    ring->AddInputConnection(ball->GetOutputPort());
  }
  vtkNew<vtkTriangleFilter> mesh;
  mesh->SetInputConnection(ring->GetOutputPort());

  // Proxies: 12 spheres bounding the mesh; then their surface samples.
  vtkNew<vtkPGISphereSetApproximation> proxies;
  proxies->SetInputConnection(mesh->GetOutputPort());
  proxies->SetNumberOfSpheres(12);
  vtkNew<vtkPGISphereLightSampler> samples;
  samples->SetInputConnection(mesh->GetOutputPort());
  samples->SetProxiesConnection(proxies->GetOutputPort());

  // Light: a uniform white sky (SetEnvironmentImage takes an HDR map), and
  // one spherical light.
  vtkNew<vtkPGILighting> lighting;
  const double lightCentre[3] = { 0, 0, 3 }, lightRadiance[3] = { 4, 3.5, 3 };
  lighting->AddSphereLight(lightCentre, 0.3, lightRadiance);

  vtkNew<vtkPGIGlobalIllumination> gi;
  gi->SetInputConnection(mesh->GetOutputPort());
  gi->SetProxiesConnection(samples->GetOutputPort());
  gi->SetLighting(lighting);
  gi->GetSettings()->SetIndirectModeToShadowed();
  const double ground[3] = { 0, 0, 0 }, up[3] = { 0, 0, 1 }, grey[3] = { 0.5, 0.5, 0.5 };
  gi->AddBlockerPlane(ground, up, grey);
  gi->Update();

  for (const std::string& line : gi->GetPlan())
  {
    std::printf("plan: %s\n", line.c_str());
  }
  vtkPolyData* out = gi->GetOutput();
  for (const char* name : { "DirectShadowed", "IndirectShadowed", "LocalLights", "Radiance" })
  {
    vtkDataArray* a = out->GetPointData()->GetArray(name);
    double mean = 0.0;
    for (vtkIdType i = 0; i < a->GetNumberOfTuples(); ++i)
    {
      mean += a->GetComponent(i, 1) / a->GetNumberOfTuples();
    }
    std::printf("%-16s mean green %.4f\n", name, mean);
  }
  vtkNew<vtkXMLPolyDataWriter> writer;
  writer->SetFileName("gi.vtp");
  writer->SetInputData(out);
  writer->Write();
  std::printf("wrote gi.vtp (%lld vertices)\n", static_cast<long long>(out->GetNumberOfPoints()));
  return 0;
}
