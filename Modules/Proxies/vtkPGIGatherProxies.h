/**
 * @class   vtkPGIGatherProxies
 * @brief   Makes a proxy set global under MPI: every rank's sphere proxies,
 *          all-gathered in rank order, on every rank.
 *
 * Global illumination is global: a sphere on one rank shadows receivers on
 * another. vtkPGISphereSetApproximation, vtkPGIGlobalIllumination and the
 * ParaView representation gather by themselves; this filter is for the
 * other sources of proxies (a reader of a .vtp set, which ParaView runs on
 * rank 0 only; a programmable source) in front of consumers that do not,
 * such as the image-space pass, whose render-time update must not wait on
 * ranks. The output carries the field array ProxyGIGlobalProxies, so a set
 * gathered once is not gathered again (the ranks only compare a header).
 * The points keep every point array; a hierarchy's Parent indices are
 * re-based. With a null controller or one process it passes its input on.
 *
 * Errors: ranks that disagree (some sets already global, some not).
 */
#ifndef vtkPGIGatherProxies_h
#define vtkPGIGatherProxies_h

#include "ProxyGIProxiesModule.h"
#include "vtkPolyDataAlgorithm.h"

class vtkMultiProcessController;

class PROXYGIPROXIES_EXPORT vtkPGIGatherProxies : public vtkPolyDataAlgorithm
{
public:
  static vtkPGIGatherProxies* New();
  vtkTypeMacro(vtkPGIGatherProxies, vtkPolyDataAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  /// The ranks (default: the global controller; null: pass the input on).
  virtual void SetController(vtkMultiProcessController* controller);
  vtkGetObjectMacro(Controller, vtkMultiProcessController);
  /// Bytes received and seconds in the last update's collectives.
  vtkGetMacro(ReceivedBytes, double);
  vtkGetMacro(GatherTime, double);

protected:
  vtkPGIGatherProxies();
  ~vtkPGIGatherProxies() override;

  int RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;

  vtkMultiProcessController* Controller = nullptr;
  double ReceivedBytes = 0.0, GatherTime = 0.0;

private:
  vtkPGIGatherProxies(const vtkPGIGatherProxies&) = delete;
  void operator=(const vtkPGIGatherProxies&) = delete;
};

#endif
