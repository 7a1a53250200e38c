#include "vtkPGIGISettings.h"

#include "vtkNew.h"
#include "vtkObjectFactory.h"
#include "vtkSmartPointer.h"

#include <cstdlib>
#include <sstream>

vtkStandardNewMacro(vtkPGIGISettings);

vtkPGIGISettings::vtkPGIGISettings()
{
  this->SetAlbedoArrayName("Albedo");
}

vtkPGIGISettings::~vtkPGIGISettings()
{
  this->SetAlbedoArrayName(nullptr);
}

const char* vtkPGIGISettings::ExpMethodName(int method)
{
  static const char* names[] = { "PS", "PS*", "OL", "HYB" };
  return method >= 0 && method < 4 ? names[method] : "?";
}

const char* vtkPGIGISettings::IndirectModeName(int mode)
{
  return mode == INDIRECT_MODE_SHADOWED ? "shadowed" : "unshadowed";
}

const char* vtkPGIGISettings::IndirectOperatorName(int op)
{
  static const char* names[] = { "point-sampled", "averaged", "exact" };
  return op >= 0 && op < 3 ? names[op] : "?";
}

const char* vtkPGIGISettings::PlaneBlockingName(int blocking)
{
  return blocking == PLANES_IN_LOG_SPACE ? "planes in log space" : "planes in the light";
}

const char* vtkPGIGISettings::SphericalLightBlockingName(int blocking)
{
  return blocking == BLOCKING_PER_OBJECT ? "per object" : "per sphere";
}

const char* vtkPGIGISettings::ShadingPathName(int path)
{
  return path == SHADING_PRODUCT_MATRIX ? "product matrix" : "table";
}

bool vtkPGIGISettings::Share(vtkObject* owner, vtkPGIGISettings*& slot, vtkPGIGISettings* next)
{
  vtkSmartPointer<vtkPGIGISettings> chosen = next;
  if (!chosen)
  {
    chosen = vtkSmartPointer<vtkPGIGISettings>::New();
  }
  if (chosen == slot)
  {
    return false;
  }
  if (slot)
  {
    slot->UnRegister(owner);
  }
  slot = chosen;
  slot->Register(owner);
  return true;
}

void vtkPGIGISettings::DeepCopy(vtkPGIGISettings* o)
{
  if (!o || o == this)
  {
    return;
  }
  this->SetShadows(o->Shadows);
  this->SetOrder(o->Order);
  this->SetExpMethod(o->ExpMethod);
  this->SetExpDegree(o->ExpDegree);
  this->SetAccumulationOrder(o->AccumulationOrder);
  this->SetWindowSize(o->WindowSize);
  this->SetSelfShadowRules(o->SelfShadowRules);
  this->SetSelfVisibility(o->SelfVisibility);
  this->SetMinBlockerAngle(o->MinBlockerAngle);
  this->SetHybridMaxNorm(o->HybridMaxNorm);
  this->SetRangeTolerance(o->RangeTolerance);
  this->SetShadingPath(o->ShadingPath);
  this->SetHierarchyAngle(o->HierarchyAngle);
  this->SetReceiversPerCluster(o->ReceiversPerCluster);
  this->SetIndirect(o->Indirect);
  this->SetIndirectMode(o->IndirectMode);
  this->SetIndirectOperator(o->IndirectOperator);
  this->SetSphericalLightBlocking(o->SphericalLightBlocking);
  this->SetIndirectOrder(o->IndirectOrder);
  this->SetPlaneBounceShadows(o->PlaneBounceShadows);
  this->SetPlaneBounceDirections(o->PlaneBounceDirections);
  this->SetPlaneBlocking(o->PlaneBlocking);
  this->SetLocalLights(o->LocalLights);
  this->SetLightCloud(o->LightCloud);
  this->SetBrightLights(o->BrightLights);
  this->SetBrightLightFraction(o->BrightLightFraction);
  this->SetBrightLightCount(o->BrightLightCount);
  this->SetBrightLightRays(o->BrightLightRays);
  this->SetDefaultAlbedo(o->DefaultAlbedo);
  this->SetDefaultProxyAlbedo(o->DefaultProxyAlbedo);
  this->SetAlbedoArrayName(o->AlbedoArrayName);
}

namespace
{
// The lowest set bit of `set` nearest to `value` (ties: the lower value).
int NearestIn(unsigned set, int value, int count)
{
  int best = -1;
  for (int v = 0; v < count; ++v)
  {
    if ((set >> v) & 1u)
    {
      if (best < 0 || std::abs(v - value) < std::abs(best - value))
      {
        best = v;
      }
    }
  }
  return best < 0 ? value : best;
}
}

bool vtkPGIGISettings::Resolve(const Support& s, int planes, vtkPGIGISettings* effective,
  std::vector<std::string>& notes, int localLights) const
{
  if (!effective)
  {
    return false;
  }
  // Resolved on a scratch copy, then copied: `effective` changes (and its
  // MTime with it) only when what runs changes.
  vtkNew<vtkPGIGISettings> scratch;
  vtkPGIGISettings* e = scratch;
  e->DeepCopy(const_cast<vtkPGIGISettings*>(this));
  const std::size_t before = notes.size();
  auto note = [&](const std::string& knob, const std::string& what)
  { notes.push_back(knob + ": " + what + " in the " + s.Backend); };

  if (this->Order < s.MinOrder || this->Order > s.MaxOrder)
  {
    const int used = this->Order < s.MinOrder ? s.MinOrder : s.MaxOrder;
    std::ostringstream m;
    m << "order " << this->Order << " is outside " << s.MinOrder << ".." << s.MaxOrder << "; order "
      << used << " runs";
    note("Order", m.str());
    e->SetOrder(used);
  }
  if (!((s.ExpMethods >> this->ExpMethod) & 1u))
  {
    const int used = NearestIn(s.ExpMethods, this->ExpMethod, 4);
    note("ExpMethod",
      std::string(ExpMethodName(this->ExpMethod)) + " is not available; " + ExpMethodName(used) +
        " runs");
    e->SetExpMethod(used);
  }
  const bool seriesMethod = e->ExpMethod == EXP_PS || e->ExpMethod == EXP_PS_STAR;
  if (!s.ExpDegree && seriesMethod && this->ExpDegree != 2)
  {
    note("ExpDegree", "the series degree is fixed at 2");
    e->SetExpDegree(2);
  }
  if (!s.AccumulationOrder && this->AccumulationOrder != 0 && this->AccumulationOrder != e->Order)
  {
    note("AccumulationOrder", "accumulation runs at the shading order");
    e->SetAccumulationOrder(0);
  }
  if (!s.WindowSize && this->WindowSize != 0.0)
  {
    note("WindowSize", "no window is applied");
    e->SetWindowSize(0.0);
  }
  if (!s.ExpGuards && (this->HybridMaxNorm != 0.0 || this->RangeTolerance != 0.5))
  {
    note("HybridMaxNorm/RangeTolerance", "the defaults run");
    e->SetHybridMaxNorm(0.0);
    e->SetRangeTolerance(0.5);
  }
  if (!((s.ShadingPaths >> this->ShadingPath) & 1u))
  {
    const int used = NearestIn(s.ShadingPaths, this->ShadingPath, 2);
    // Both paths evaluate the same L*H(N); only their speed differs, so the
    // change is said only when the user asked for the one that is missing.
    if (this->ShadingPath != SHADING_TABLE)
    {
      note("ShadingPath",
        std::string(ShadingPathName(this->ShadingPath)) + " is not available; the " +
          ShadingPathName(used) + " runs");
    }
    e->SetShadingPath(used);
  }
  if (!s.Hierarchy && this->HierarchyAngle > 0.0)
  {
    note("HierarchyAngle", "hierarchy cuts are not available; every leaf proxy is used");
    e->SetHierarchyAngle(0.0);
  }
  if (this->Indirect && !((s.IndirectModes >> this->IndirectMode) & 1u))
  {
    if (s.IndirectModes == 0)
    {
      note("Indirect", "indirect light is not available; none runs");
      e->SetIndirect(false);
    }
    else
    {
      const int used = NearestIn(s.IndirectModes, this->IndirectMode, 2);
      note("IndirectMode",
        std::string(IndirectModeName(this->IndirectMode)) + " indirect light is not available; " +
          IndirectModeName(used) + " runs");
      e->SetIndirectMode(used);
    }
  }
  const bool unshadowed = e->Indirect && e->IndirectMode == INDIRECT_MODE_UNSHADOWED;
  if (!((s.IndirectOperators >> this->IndirectOperator) & 1u))
  {
    const int used = NearestIn(s.IndirectOperators, this->IndirectOperator, 3);
    if (unshadowed)
    {
      note("IndirectOperator",
        std::string(IndirectOperatorName(this->IndirectOperator)) + " is not available; the " +
          IndirectOperatorName(used) + " operator runs");
    }
    e->SetIndirectOperator(used);
  }
  const bool shadowed = e->Indirect && e->IndirectMode == INDIRECT_MODE_SHADOWED;
  if (!s.SphericalLightBlocking && shadowed && this->SphericalLightBlocking != BLOCKING_PER_SPHERE)
  {
    note("SphericalLightBlocking", "the spherical lights block per sphere");
    e->SetSphericalLightBlocking(BLOCKING_PER_SPHERE);
  }
  if (!s.IndirectOrder && e->GetEffectiveIndirectOrder() != e->Order)
  {
    if (shadowed)
    {
      note("IndirectOrder", "the bounce runs at the shading order " + std::to_string(e->Order));
    }
    e->SetIndirectOrder(0);
  }
  if (!s.PlaneBounceShadows && e->Indirect && planes > 0 && this->PlaneBounceShadows)
  {
    note("PlaneBounceShadows", "the planes' bounce is not dimmed by the proxies' shadows");
    e->SetPlaneBounceShadows(false);
  }
  if (!s.PlaneBounceDirections && e->PlaneBounceDirections != 0)
  {
    // Noted only when set away from its default: the backend's plan says
    // it samples one plane point.
    if (e->Indirect && e->PlaneBounceShadows && planes > 0 && this->PlaneBounceDirections != 64)
    {
      note("PlaneBounceDirections", "the planes' shadowed light is sampled at one point");
    }
    e->SetPlaneBounceDirections(0);
  }
  if (!((s.PlaneBlockings >> this->PlaneBlocking) & 1u))
  {
    const int used = NearestIn(s.PlaneBlockings, this->PlaneBlocking, 2);
    if (planes > 0)
    {
      note("PlaneBlocking",
        std::string(PlaneBlockingName(this->PlaneBlocking)) + " is not available; " +
          PlaneBlockingName(used) + " run");
    }
    e->SetPlaneBlocking(used);
  }
  if (!s.LocalLights && this->LocalLights)
  {
    if (localLights > 0)
    {
      note("LocalLights", "the " + std::to_string(localLights) + " local lights are not drawn");
    }
    e->SetLocalLights(false);
  }
  if (!s.LightCloud)
  {
    // Not read here: noted only when set away from its default.
    if (!this->LightCloud)
    {
      note("LightCloud",
        "this backend has no light cloud (vtkPGILightCloudPolyDataMapper relights "
        "one on the GPU)");
    }
    e->SetLightCloud(true);
  }
  if (!s.BrightLights)
  {
    // On by default: the backend keeps the whole map in the SH, and its
    // plan says how much of the light was in peaks.
    e->SetBrightLights(false);
  }
  if (!s.SelfVisibility)
  {
    // On by default and only meaningful with the arrays, which the backend
    // does not read: it runs the rules, as its documentation says.
    e->SetSelfVisibility(false);
  }
  if (!s.ReceiverAlbedo)
  {
    const bool defaultAlbedo = this->DefaultAlbedo[0] == 0.8 && this->DefaultAlbedo[1] == 0.8 &&
      this->DefaultAlbedo[2] == 0.8;
    if (!defaultAlbedo)
    {
      note("DefaultAlbedo", "receivers take their own colour instead");
    }
  }
  effective->DeepCopy(e);
  return notes.size() == before;
}

void vtkPGIGISettings::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "Shadows: " << this->Shadows << "\n";
  os << indent << "Order: " << this->Order << "\n";
  os << indent << "ExpMethod: " << ExpMethodName(this->ExpMethod) << " (degree " << this->ExpDegree
     << ")\n";
  os << indent << "AccumulationOrder: " << this->AccumulationOrder << "\n";
  os << indent << "WindowSize: " << this->WindowSize << "\n";
  os << indent << "SelfShadowRules: " << this->SelfShadowRules << "\n";
  os << indent << "SelfVisibility: " << this->SelfVisibility << "\n";
  os << indent << "MinBlockerAngle: " << this->MinBlockerAngle << "\n";
  os << indent << "HybridMaxNorm: " << this->HybridMaxNorm << "\n";
  os << indent << "RangeTolerance: " << this->RangeTolerance << "\n";
  os << indent << "ShadingPath: " << ShadingPathName(this->ShadingPath) << "\n";
  os << indent << "HierarchyAngle: " << this->HierarchyAngle << "\n";
  os << indent << "ReceiversPerCluster: " << this->ReceiversPerCluster << "\n";
  os << indent << "Indirect: " << this->Indirect << " (" << IndirectModeName(this->IndirectMode)
     << ", " << IndirectOperatorName(this->IndirectOperator) << " operator)\n";
  os << indent
     << "SphericalLightBlocking: " << SphericalLightBlockingName(this->SphericalLightBlocking)
     << "\n";
  os << indent << "IndirectOrder: " << this->IndirectOrder << " (runs at "
     << this->GetEffectiveIndirectOrder() << ")\n";
  os << indent << "PlaneBounceShadows: " << this->PlaneBounceShadows << " ("
     << this->PlaneBounceDirections << " directions)\n";
  os << indent << "PlaneBlocking: " << PlaneBlockingName(this->PlaneBlocking) << "\n";
  os << indent << "LocalLights: " << this->LocalLights << "\n";
  os << indent << "LightCloud: " << this->LightCloud << "\n";
  os << indent << "BrightLights: " << this->BrightLights << " (fraction "
     << this->BrightLightFraction << ", at most " << this->BrightLightCount << ", "
     << this->BrightLightRays << " rays)\n";
  os << indent << "DefaultAlbedo: " << this->DefaultAlbedo[0] << " " << this->DefaultAlbedo[1]
     << " " << this->DefaultAlbedo[2] << "\n";
  os << indent << "DefaultProxyAlbedo: " << this->DefaultProxyAlbedo[0] << " "
     << this->DefaultProxyAlbedo[1] << " " << this->DefaultProxyAlbedo[2] << "\n";
  os << indent << "AlbedoArrayName: " << (this->AlbedoArrayName ? this->AlbedoArrayName : "(none)")
     << "\n";
}
