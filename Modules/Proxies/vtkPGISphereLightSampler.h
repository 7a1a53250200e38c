/**
 * @class   vtkPGISphereLightSampler
 * @brief   Surface sample points and albedo SH of spherical lights
 *          (Guerrero et al. 2008, section 4.2), found by Embree rays.
 *
 * Input 0: the scene mesh (vtkPolyData, closed, outward-oriented polygons;
 * an optional "ObjectId" point array says which object each triangle
 * belongs to, by its first point; an optional 3-component albedo array,
 * AlbedoArrayName, gives per-vertex colour, else DefaultAlbedo is the
 * per-object colour). Input 1: the proxies (points with "Radius"; optional
 * "ObjectId" and "Level": each level of each object is sampled on its own,
 * so hierarchy parents get samples too).
 *
 * Each sphere S_i of an object gets the segment of that object's surface
 * nearest to it by d(p, S_i) = |p - x_i| / r_i. From its centre a ray is shot
 * along each of the m geodesic directions w_j (frequency 3: 92); only hits
 * whose surface faces w_j (n . w_j > 0, the "back side" seen from the
 * centre) count, and the paper's three rules apply:
 *  1. hits in the segment: the farthest one is the sample;
 *  2. hits, none in the segment: no sample (another sphere covers that
 *     direction; S_i emits nothing there, which precomputes the occlusion of
 *     intersecting spheres of one object);
 *  3. no hit (centre outside the object): the first hit in the segment along
 *     -w_j, if any, is the sample; else none.
 * The albedo is sampled by the same rules on a denser Gauss product set of
 * rays (AlbedoResolution x 2 AlbedoResolution) and projected to SH; rays
 * that find no sample take the sphere's mean albedo.
 *
 * Output: the proxies with point arrays
 * | array | components | what |
 * |---|---|---|
 * | SampleOffset | 3m | (p_j - x_i) / r_i, invariant to translation and uniform scale |
 * | SampleNormal | 3m | unit outward normal at p_j; (0, 0, 0): no sample in w_j |
 * | SampleCount | 1 | samples found |
 * | AlbedoSH | 3 k^2 | albedo SH of order k = AlbedoOrder, R then G then B |
 * and field data "SampleDirections" (m x 3, the w_j) and "SampleRules"
 * (how many directions took rule 1, rule 2, rule 3, and found nothing).
 *
 * | property | default | cost |
 * |---|---|---|
 * | GeodesicFrequency | 3 (92 directions) | 10 f^2 + 2 rays per sphere, and per sample in the first
 * pass | | AlbedoOrder | 4 | SH order of AlbedoSH | | AlbedoResolution | 16 | 2 r^2 albedo rays per
 * sphere | | DefaultAlbedo | 0.8 0.8 0.8 | per-object colour without an albedo array |
 *
 * Distributed (Controller, default the global controller, with more than
 * one process): each rank holds a piece of the mesh and the same global
 * proxies (Sphere Proxies' output). Each rank casts every sphere's rays
 * against its own piece and keeps, per ray, what the rules need: the
 * farthest in-segment forward hit, whether any forward hit exists, and
 * (without one) the nearest in-segment backward hit. These are all-gathered
 * (88 bytes per ray per rank) and combined as the rules would be on the
 * whole mesh, so every rank outputs the serial result; a rank with an empty
 * piece takes part. GetCommunicationBytes: what this rank received.
 *
 * Errors: empty or NaN/Inf mesh or proxies, proxies without Radius; under
 * MPI, ranks whose proxy sets differ in size (an error on every rank).
 */
#ifndef vtkPGISphereLightSampler_h
#define vtkPGISphereLightSampler_h

#include "ProxyGIProxiesModule.h"
#include "vtkPolyDataAlgorithm.h"

class vtkMultiProcessController;

class PROXYGIPROXIES_EXPORT vtkPGISphereLightSampler : public vtkPolyDataAlgorithm
{
public:
  static vtkPGISphereLightSampler* New();
  vtkTypeMacro(vtkPGISphereLightSampler, vtkPolyDataAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  void SetProxiesConnection(vtkAlgorithmOutput* output) { this->SetInputConnection(1, output); }
  void SetProxiesData(vtkDataObject* data) { this->SetInputData(1, data); }

  vtkSetClampMacro(GeodesicFrequency, int, 1, 16);
  vtkGetMacro(GeodesicFrequency, int);
  vtkSetClampMacro(AlbedoOrder, int, 1, 8);
  vtkGetMacro(AlbedoOrder, int);
  vtkSetClampMacro(AlbedoResolution, int, 2, 256);
  vtkGetMacro(AlbedoResolution, int);
  vtkSetVector3Macro(DefaultAlbedo, double);
  vtkGetVector3Macro(DefaultAlbedo, double);
  vtkSetStringMacro(AlbedoArrayName);
  vtkGetStringMacro(AlbedoArrayName);

  /// The ranks the mesh is spread over (null: this process alone).
  virtual void SetController(vtkMultiProcessController* controller);
  vtkGetObjectMacro(Controller, vtkMultiProcessController);
  /// Bytes this rank received in the last update (0 serially).
  vtkGetMacro(CommunicationBytes, double);
  /// Rays this rank cast at its piece in the last update (every sphere's).
  vtkGetMacro(NumberOfRays, double);

protected:
  vtkPGISphereLightSampler();
  ~vtkPGISphereLightSampler() override;

  int FillInputPortInformation(int port, vtkInformation* info) override;
  int RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;

  int GeodesicFrequency = 3;
  int AlbedoOrder = 4;
  int AlbedoResolution = 16;
  double DefaultAlbedo[3] = { 0.8, 0.8, 0.8 };
  char* AlbedoArrayName = nullptr;
  vtkMultiProcessController* Controller = nullptr;
  double NumberOfRays = 0;
  double CommunicationBytes = 0.0;

private:
  vtkPGISphereLightSampler(const vtkPGISphereLightSampler&) = delete;
  void operator=(const vtkPGISphereLightSampler&) = delete;
};

#endif
