/**
 * @class   vtkPGIReferenceIllumination
 * @brief   Ground-truth diffuse illumination per vertex by Monte Carlo path
 *          tracing on Embree.
 *
 * Input 0: the receivers (vtkPolyData; point normals used if present,
 * computed otherwise). They are part of the scene (they shadow themselves).
 * Input 1 (optional, repeatable): other scene objects, which block and
 * reflect light but get no outputs. Input 2 (optional): sphere proxies
 * (points with a "Radius" array); with UseProxies on they replace the
 * input-1 objects, so that an error can be split into proxy geometry and
 * SH approximation. Light: a vtkPGILighting.
 *
 * Output: the receivers with RGB point arrays (exit radiance, albedo/pi E):
 * | array | what |
 * |---|---|
 * | DirectShadowed | environment and local lights, shadowed |
 * | IndirectOneBounce | one diffuse bounce (MaxBounces bounces if > 1) |
 * | Radiance | their sum |
 * | RadianceStdErr | standard error of Radiance (and DirectStdErr, IndirectStdErr) |
 * and field data "Samples", "Rays", "MeanRelativeStdErr" (mean over vertices of
 * stderr/value) and "RelativeRMSStdErr" (sqrt(sum stderr^2 / sum value^2), the
 * normalisation of the project's relative-RMSE error metric).
 *
 * | property | default | cost |
 * |---|---|---|
 * | Samples | 256 | time grows linearly, noise falls as 1/sqrt |
 * | MaxBounces | 1 | 0 = direct only |
 * | Seed | 1 | same seed, same result on any thread count |
 * | DefaultAlbedo | 0.8 0.8 0.8 | where no AlbedoArrayName array exists |
 * | AlbedoArrayName | "Albedo" | 3-component point array, floats in 0..1 or bytes |
 *
 * Distributed (Controller, default the global controller, with more than
 * one process): each rank traces its own receivers against the whole scene.
 * The scene (every rank's receivers and scene objects, ghost cells left out,
 * and the proxies) is all-gathered first, so each rank holds all of it:
 * about 40 bytes per triangle travel to every rank and Embree's BVH takes
 * roughly 100 more per triangle there. Above MaximumGatheredTriangles
 * (default 20 million: some 3 GB per rank) the filter refuses, on every
 * rank, rather than exhaust memory; tracing a larger scene needs rays sent
 * between ranks, which this filter does not do. Under MPI the random
 * sequence of a receiver is seeded by its position (PositionSeeds), not by
 * its index in a piece, so the result of a point does not depend on the
 * partition and equals a serial run with PositionSeeds on. A rank with an
 * empty piece takes part; an error on one rank is an error on every rank.
 * The field data (rays, errors) is the rank's own.
 *
 * Errors: no receivers, NaN/Inf points, an empty scene, a bad environment.
 * Degenerate triangles are skipped (count in field data "SkippedTriangles").
 */
#ifndef vtkPGIReferenceIllumination_h
#define vtkPGIReferenceIllumination_h

#include "ProxyGIReferenceModule.h"
#include "vtkPolyDataAlgorithm.h"

class vtkMultiProcessController;
class vtkPGILighting;

class PROXYGIREFERENCE_EXPORT vtkPGIReferenceIllumination : public vtkPolyDataAlgorithm
{
public:
  static vtkPGIReferenceIllumination* New();
  vtkTypeMacro(vtkPGIReferenceIllumination, vtkPolyDataAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  virtual void SetLighting(vtkPGILighting* lighting);
  vtkGetObjectMacro(Lighting, vtkPGILighting);

  vtkSetClampMacro(Samples, int, 1, 1 << 24);
  vtkGetMacro(Samples, int);
  vtkSetClampMacro(MaxBounces, int, 0, 64);
  vtkGetMacro(MaxBounces, int);
  vtkSetMacro(Seed, unsigned int);
  vtkGetMacro(Seed, unsigned int);
  vtkSetMacro(UseProxies, bool);
  vtkGetMacro(UseProxies, bool);
  vtkBooleanMacro(UseProxies, bool);
  vtkSetVector3Macro(DefaultAlbedo, double);
  vtkGetVector3Macro(DefaultAlbedo, double);
  vtkSetStringMacro(AlbedoArrayName);
  vtkGetStringMacro(AlbedoArrayName);
  /// Seed each receiver's samples by its position instead of its index
  /// (default off; always on under MPI).
  vtkSetMacro(PositionSeeds, bool);
  vtkGetMacro(PositionSeeds, bool);
  vtkBooleanMacro(PositionSeeds, bool);

  /// The ranks the receivers are spread over (null: this process alone).
  virtual void SetController(vtkMultiProcessController* controller);
  vtkGetObjectMacro(Controller, vtkMultiProcessController);
  /// Under MPI, the largest scene (triangles over all ranks) gathered.
  vtkSetClampMacro(MaximumGatheredTriangles, double, 0.0, VTK_DOUBLE_MAX);
  vtkGetMacro(MaximumGatheredTriangles, double);
  /// Bytes this rank received in the last update's gather (0 serially).
  vtkGetMacro(CommunicationBytes, double);

  /// Convenience: the scene objects and proxies ports.
  void AddSceneObjectConnection(vtkAlgorithmOutput* output) { this->AddInputConnection(1, output); }
  void AddSceneObjectData(vtkDataObject* data) { this->AddInputData(1, data); }
  void RemoveAllSceneObjects() { this->SetInputConnection(1, nullptr); }
  void SetProxiesConnection(vtkAlgorithmOutput* output) { this->SetInputConnection(2, output); }
  void SetProxiesData(vtkDataObject* data) { this->SetInputData(2, data); }

  vtkMTimeType GetMTime() override;

protected:
  vtkPGIReferenceIllumination();
  ~vtkPGIReferenceIllumination() override;

  int FillInputPortInformation(int port, vtkInformation* info) override;
  int RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;

  vtkPGILighting* Lighting = nullptr;
  int Samples = 256;
  int MaxBounces = 1;
  unsigned int Seed = 1;
  bool UseProxies = false;
  double DefaultAlbedo[3] = { 0.8, 0.8, 0.8 };
  char* AlbedoArrayName = nullptr;
  bool PositionSeeds = false;
  vtkMultiProcessController* Controller = nullptr;
  double MaximumGatheredTriangles = 2e7;
  double CommunicationBytes = 0.0;

private:
  vtkPGIReferenceIllumination(const vtkPGIReferenceIllumination&) = delete;
  void operator=(const vtkPGIReferenceIllumination&) = delete;
};

#endif
