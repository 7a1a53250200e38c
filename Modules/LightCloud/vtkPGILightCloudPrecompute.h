/**
 * @class   vtkPGILightCloudPrecompute
 * @brief   Builds a light cloud (Kristensen et al. 2005) on Embree: for each
 *          cloud light, the exit radiance at every receiver vertex.
 *
 * Input 0: the receivers (vtkPolyData; point normals used if present,
 * computed otherwise; "Albedo" RGB point array or DefaultAlbedo). They are
 * part of the scene. Input 1 (optional, repeatable): other scene objects,
 * which block and reflect light but get no response. Output: a
 * vtkPGILightCloud.
 *
 * Cloud lights: the centres of a GridResolution grid of cells over
 * RegionOfInterest (by default the scene's bounding box), or the points the
 * user gives (SetLightPositions). Each is an isotropic point light of unit
 * intensity. Per receiver x (normal n, albedo a) and light at p the
 * response is a/pi (E_direct + E_indirect):
 *  - E_direct = cos / d^2 when p is visible from x (with IncludeDirect on;
 *    off by default, as the paper stores the indirect light only);
 *  - E_indirect = 1/Samples sum over gather hits y of a(y) cos_y / d_y^2
 *    when p is visible from y: Samples cosine-distributed rays per receiver
 *    are traced once and their hits lit by every cloud light (the paper's
 *    photon map with a final gather replaced by the final gather alone).
 *
 * Glossy receivers (SpecularAlbedo ks > 0): the BRDF is a/pi plus the
 * normalised Phong lobe ks (e+2)/(2 pi) cos^e of PhongExponent e, and the
 * response is the exit radiance as a function of the view direction,
 * projected on SH of GlossyOrder (16 coefficients per colour at order 4,
 * the paper's "third order") by least squares over the hemisphere. The
 * other scene objects and the gather hits stay diffuse (one bounce of
 * glossy-to-glossy light is not carried).
 *
 * Distances below ClampDistance (default: 1e-3 of the scene size) count as
 * it, so a light almost on a surface stays finite.
 *
 * The receivers run in parallel (vtkSMPTools); progress and abort between
 * blocks of cloud lights. With CacheFileName set the cloud is written there
 * as lights finish, keyed by everything it depends on (geometry, albedo,
 * normals, lights, settings): a later run with the same key reads it
 * instead of tracing, and one that was stopped resumes from the lights
 * already there. A cache for something else is replaced; a corrupted one is
 * an error (delete it). With Compress on, the compressed cloud is cached
 * too, in CacheFileName + ".compressed" (keyed by the dense cloud and the
 * compression's knobs): a later run reads it instead of compressing again.
 *
 * Errors: no receivers, NaN/Inf points or light positions, an empty grid,
 * a corrupted cache file.
 */
#ifndef vtkPGILightCloudPrecompute_h
#define vtkPGILightCloudPrecompute_h

#include "ProxyGILightCloudModule.h"
#include "vtkAlgorithm.h"

#include <functional>
#include <vector>

class vtkPGILightCloud;
class vtkPoints;
class vtkPolyData;
namespace proxygi
{
class ReferenceTracer;
}

class PROXYGILIGHTCLOUD_EXPORT vtkPGILightCloudPrecompute : public vtkAlgorithm
{
public:
  static vtkPGILightCloudPrecompute* New();
  vtkTypeMacro(vtkPGILightCloudPrecompute, vtkAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  /// The grid's box; an empty box (xmin >= xmax, the default) is the scene's.
  vtkSetVector6Macro(RegionOfInterest, double);
  vtkGetVector6Macro(RegionOfInterest, double);
  vtkSetVector3Macro(GridResolution, int);
  vtkGetVector3Macro(GridResolution, int);
  /// Cloud lights where the user wants them (null: the grid).
  virtual void SetLightPositions(vtkPoints* points);
  vtkGetObjectMacro(LightPositions, vtkPoints);

  /// Gather rays per receiver (indirect light).
  vtkSetClampMacro(Samples, int, 1, 1 << 16);
  vtkGetMacro(Samples, int);
  vtkSetMacro(IncludeDirect, bool);
  vtkGetMacro(IncludeDirect, bool);
  vtkBooleanMacro(IncludeDirect, bool);
  /// Phong coefficient ks of the receivers (0: diffuse, one coefficient).
  vtkSetClampMacro(SpecularAlbedo, double, 0.0, 1.0);
  vtkGetMacro(SpecularAlbedo, double);
  /// Phong exponent e (the paper's glossy bunny: 12).
  vtkSetClampMacro(PhongExponent, double, 0.0, 1e4);
  vtkGetMacro(PhongExponent, double);
  /// SH order of glossy responses (order^2 coefficients per colour).
  vtkSetClampMacro(GlossyOrder, int, 1, 8);
  vtkGetMacro(GlossyOrder, int);
  vtkSetMacro(Seed, unsigned int);
  vtkGetMacro(Seed, unsigned int);
  vtkSetVector3Macro(DefaultAlbedo, double);
  vtkGetVector3Macro(DefaultAlbedo, double);
  vtkSetStringMacro(AlbedoArrayName);
  vtkGetStringMacro(AlbedoArrayName);
  /**
   * Cloud lights inside a solid (PlacePoint: every ray hits, most from
   * behind) are left out: they light nothing. Lights nearer a surface than
   * SurfaceMargin have responses too peaked (1/d^2) to interpolate between:
   * each is moved along its nearest ray, back to the margin and across the
   * surface to the margin on the other side, keeping each place that is
   * not inside a solid and at least half the margin from every surface (a
   * thin wall gets a light on each side; a place with none is left out).
   * Negative (the default): a quarter of the grid's cell (or of the given
   * lights' spacing); 0: keep every light where it is.
   */
  vtkSetMacro(SurfaceMargin, double);
  vtkGetMacro(SurfaceMargin, double);
  /// Lights the last update left out, and lights it moved off surfaces.
  vtkGetMacro(LightsDropped, vtkIdType);
  vtkGetMacro(LightsMoved, vtkIdType);
  /// 0: 1e-3 of the scene's bounding-box diagonal.
  vtkSetClampMacro(ClampDistance, double, 0.0, VTK_DOUBLE_MAX);
  vtkGetMacro(ClampDistance, double);
  vtkSetStringMacro(CacheFileName);
  vtkGetStringMacro(CacheFileName);

  /// Compression (off: the output holds the dense responses).
  vtkSetMacro(Compress, bool);
  vtkGetMacro(Compress, bool);
  vtkBooleanMacro(Compress, bool);
  /// Zoning: a zone is split while it holds more receivers, up to MaximumZones.
  vtkSetClampMacro(ZoneSize, vtkIdType, 1, VTK_ID_MAX);
  vtkGetMacro(ZoneSize, vtkIdType);
  vtkSetClampMacro(MaximumZones, int, 1, 4096);
  vtkGetMacro(MaximumZones, int);
  /// Light clustering: w1 = 1 / MergeDistance (0: twice the cloud's
  /// spacing), w2 = 1 / (MergeTolerance x the zone's largest response).
  vtkSetClampMacro(MergeDistance, double, 0.0, VTK_DOUBLE_MAX);
  vtkGetMacro(MergeDistance, double);
  vtkSetClampMacro(MergeTolerance, double, 1e-9, VTK_DOUBLE_MAX);
  vtkGetMacro(MergeTolerance, double);
  enum MergedResponses
  {
    AVERAGED_RESPONSE = 0,
    RECOMPUTED_RESPONSE = 1
  };
  /// A merged light's response: its members' mean, or traced anew at its
  /// mean position (the paper's higher-quality option).
  vtkSetClampMacro(MergedResponse, int, AVERAGED_RESPONSE, RECOMPUTED_RESPONSE);
  vtkGetMacro(MergedResponse, int);
  /// Clustered PCA per zone: clusters, the mean number of PCA vectors per
  /// receiver, reclustering passes.
  vtkSetClampMacro(PCAClusters, int, 1, 4096);
  vtkGetMacro(PCAClusters, int);
  vtkSetClampMacro(VectorsPerReceiver, double, 0.0, 4096.0);
  vtkGetMacro(VectorsPerReceiver, double);
  vtkSetClampMacro(PCAIterations, int, 0, 1000);
  vtkGetMacro(PCAIterations, int);
  /// The last compression: cluster lights per zone (weighted by the zone's
  /// receivers), the CPCA's relative RMS error against the clustered
  /// responses, seconds.
  vtkGetMacro(CompressedLights, double);
  vtkGetMacro(PCARelativeError, double);
  vtkGetMacro(CompressionSeconds, double);
  /// Whether the last compression was read from the compressed cache (then
  /// CompressionSeconds is 0 and PCARelativeError is not known: 0).
  vtkGetMacro(CompressedFromCache, bool);

  /// The last update: lights traced, lights read from the cache, rays, seconds.
  vtkGetMacro(LightsTraced, vtkIdType);
  vtkGetMacro(LightsFromCache, vtkIdType);
  vtkGetMacro(RayCount, double);
  vtkGetMacro(Seconds, double);

  vtkPGILightCloud* GetOutput();
  void SetInputData(vtkDataObject* receivers) { this->SetInputDataInternal(0, receivers); }
  void AddSceneObjectData(vtkDataObject* data) { this->AddInputDataInternal(1, data); }
  void AddSceneObjectConnection(vtkAlgorithmOutput* output) { this->AddInputConnection(1, output); }
  void RemoveAllSceneObjects() { this->SetInputConnection(1, nullptr); }

  vtkTypeBool ProcessRequest(
    vtkInformation* request, vtkInformationVector** in, vtkInformationVector* out) override;
  vtkMTimeType GetMTime() override;

protected:
  vtkPGILightCloudPrecompute();
  ~vtkPGILightCloudPrecompute() override;

  int FillInputPortInformation(int port, vtkInformation* info) override;
  int FillOutputPortInformation(int port, vtkInformation* info) override;
  int RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector*);
  void CompressCloud(vtkPGILightCloud* cloud, vtkPolyData* receivers,
    const std::vector<double>& lights, const proxygi::ReferenceTracer& tracer,
    const std::function<void(const double*, vtkIdType, float*)>& response);

  double RegionOfInterest[6] = { 0, -1, 0, -1, 0, -1 };
  int GridResolution[3] = { 6, 6, 6 };
  vtkPoints* LightPositions = nullptr;
  int Samples = 64;
  bool IncludeDirect = false;
  double SpecularAlbedo = 0.0;
  double PhongExponent = 12.0;
  int GlossyOrder = 4;
  unsigned int Seed = 1;
  double DefaultAlbedo[3] = { 0.8, 0.8, 0.8 };
  char* AlbedoArrayName = nullptr;
  double ClampDistance = 0.0;
  double SurfaceMargin = -1.0;
  vtkIdType LightsDropped = 0, LightsMoved = 0;
  char* CacheFileName = nullptr;
  bool Compress = false;
  vtkIdType ZoneSize = 1000;
  int MaximumZones = 64;
  double MergeDistance = 0.0;
  double MergeTolerance = 0.1;
  int MergedResponse = AVERAGED_RESPONSE;
  int PCAClusters = 8;
  double VectorsPerReceiver = 8.0;
  int PCAIterations = 25;
  double CompressedLights = 0.0, PCARelativeError = 0.0, CompressionSeconds = 0.0;
  bool CompressedFromCache = false;
  vtkIdType LightsTraced = 0, LightsFromCache = 0;
  double RayCount = 0.0, Seconds = 0.0;

private:
  vtkPGILightCloudPrecompute(const vtkPGILightCloudPrecompute&) = delete;
  void operator=(const vtkPGILightCloudPrecompute&) = delete;
};

#endif
