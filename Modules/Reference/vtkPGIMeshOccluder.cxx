#include "vtkPGIMeshOccluder.h"

#include "pgiReferenceScene.h"
#include "pgiReferenceTracer.h"

#include "vtkCellArray.h"
#include "vtkObjectFactory.h"
#include "vtkPolyData.h"

#include <algorithm>
#include <sstream>

vtkStandardNewMacro(vtkPGIMeshOccluder);

vtkPGIMeshOccluder::vtkPGIMeshOccluder() = default;
vtkPGIMeshOccluder::~vtkPGIMeshOccluder() = default;

void vtkPGIMeshOccluder::AddMesh(vtkPolyData* mesh)
{
  if (mesh)
  {
    this->Meshes.emplace_back(mesh);
    this->Modified();
  }
}

void vtkPGIMeshOccluder::RemoveAllMeshes()
{
  if (!this->Meshes.empty())
  {
    this->Meshes.clear();
    this->Modified();
  }
}

vtkMTimeType vtkPGIMeshOccluder::GetMTime()
{
  vtkMTimeType t = this->Superclass::GetMTime();
  for (const auto& mesh : this->Meshes)
  {
    t = std::max(t, mesh->GetMTime());
  }
  return t;
}

bool vtkPGIMeshOccluder::Prepare(std::string& error)
{
  const vtkMTimeType now = this->GetMTime();
  if (this->Tracer && now <= this->BuiltTime)
  {
    return true;
  }
  this->Tracer.reset();
  this->Triangles = 0;
  if (this->Meshes.empty())
  {
    error = "the occluder holds no meshes";
    return false;
  }
  auto tracer = std::make_unique<proxygi::ReferenceTracer>();
  const double albedo[3] = { 0, 0, 0 };
  for (const auto& mesh : this->Meshes)
  {
    if (!proxygi::AddPolyData(*tracer, mesh, albedo, nullptr, error))
    {
      error.insert(0, "occluder mesh: ");
      return false;
    }
    this->Triangles += mesh->GetNumberOfPolys();
  }
  if (!tracer->Commit(error))
  {
    error.insert(0, "occluder: ");
    return false;
  }
  this->Tracer = std::move(tracer);
  this->BuiltTime = now;
  ++this->NumberOfBuilds;
  return true;
}

void vtkPGIMeshOccluder::Occluded(int count, const float* origins, const float* directions,
  float tnear, unsigned char* blocked) const
{
  if (!this->Tracer)
  {
    std::fill_n(blocked, count, 0);
    return;
  }
  this->Tracer->OccludedRays(count, origins, directions, tnear, nullptr, blocked);
}

void vtkPGIMeshOccluder::OccludedSegments(int count, const float* origins, const float* directions,
  const float* lengths, float tnear, unsigned char* blocked) const
{
  if (!this->Tracer)
  {
    std::fill_n(blocked, count, 0);
    return;
  }
  this->Tracer->OccludedRays(count, origins, directions, tnear, lengths, blocked);
}

double vtkPGIMeshOccluder::GetSceneSize() const
{
  return this->Tracer ? this->Tracer->GetSceneSize() : 1.0;
}

std::string vtkPGIMeshOccluder::Describe() const
{
  std::ostringstream s;
  s << "Embree, " << this->Meshes.size() << (this->Meshes.size() == 1 ? " mesh, " : " meshes, ")
    << this->Triangles << " polygons";
  return s.str();
}

void vtkPGIMeshOccluder::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "Meshes: " << this->Meshes.size() << "\n";
  os << indent << "NumberOfBuilds: " << this->NumberOfBuilds << "\n";
}
