/**
 * @class   vtkPGISphereSetApproximation
 * @brief   Bounding sphere proxies of closed triangle meshes with minimal
 *          outside volume.
 *
 * Input: one vtkPolyData, or a composite dataset (each vtkPolyData leaf of a
 * multiblock is an object; each partitioned dataset is one object, its
 * partitions merged), optionally split further into connected components.
 * Output: one vtkPolyData whose points are the sphere centres, with point
 * arrays
 *
 * | array | type | meaning |
 * |---|---|---|
 * | Radius | double | sphere radius (the active scalars) |
 * | ObjectId | int | object the sphere bounds, 0.. in input order |
 * | Level | int | 0 (leaves; vtkPGISphereHierarchy adds levels above) |
 * | Parent | vtkIdType | -1 (set by vtkPGISphereHierarchy) |
 * | OutsideVolume | double | V(S_i - mesh), absolute (with ComputeOutsideVolume) |
 *
 * and one vertex cell per sphere. To see them in ParaView: Glyph filter,
 * glyph type Sphere (radius 1 in ParaView's sphere source is 0.5: set the
 * glyph's scale factor to 2), Scale Array = Radius.
 * Field data: OutsideVolumeRatio (E per object: volume inside the spheres
 * but outside the mesh over the mesh volume), OutsideVolumeRatioSum (the
 * paper's sum over spheres, overlaps counted again), MeshVolume, and
 * SphereCount per object.
 *
 * Every vertex, every triangle (its three corners, hence all of it) and every
 * interior grid sample lies in at least one sphere, whatever the method.
 * Triangles longer than the interior sample spacing are split first (for
 * the clustering only), so that a long triangle does not force a big sphere.
 *
 * | Method | what it does | cost |
 * |---|---|---|
 * | Variational (default) | Lloyd-style clustering of triangles and interior samples in flood-fill
 * order (each element joins the sphere whose outside volume grows least), per-sphere centre update
 * minimising outside volume while bounding the cluster (Nelder-Mead), teleportation of clusters
 * when progress stalls | ~1-20 s for 64 spheres on 10k-75k triangles | | Octree | circumspheres of
 * occupied octree cells, splitting the cell of largest outside volume while the count fits | fast |
 * | KMeans | k-means of the elements, near-minimal bounding sphere of each | fast |
 *
 * Parameters: NumberOfSpheres per object (default 64), or with
 * TargetOutsideVolumeRatio > 0 the smallest count (growing by 1.5x from
 * NumberOfSpheres up to MaximumNumberOfSpheres) whose E meets it; Seed
 * (same seed, same spheres, whatever the thread count); VolumeResolution
 * (rows of the inside/outside integration along the longest side: 128; cost
 * grows with its square); InteriorResolution (interior sample grid, and the
 * longest triangle edge clustered, as a fraction of the longest side: 32;
 * finer bounds the interior more finely but clusters more elements);
 * MaximumIterations (100) and MaximumTeleportFailures (8) bound the
 * variational search; MetricResolution (256) for the reported E.
 *
 * Input handling: polygons with more than three points and triangle strips
 * are triangulated (vtkTriangleFilter); vertex and line cells are ignored
 * with a warning; points no polygon uses are not bounded. Errors (empty
 * output): no input, no points, no polygons, NaN/Inf coordinates. Warnings
 * (the spheres still bound the whole surface): open or non-manifold meshes
 * (their inside is decided by a three-ray majority vote; a mesh with no
 * consistent inside gets surface-only spheres and E = NaN), zero-area
 * triangles, more spheres asked than the object has elements (the count is
 * lowered to that).
 *
 * Progress is reported per iteration; AbortExecute stops the build and
 * leaves the output empty.
 *
 * Distributed (Controller, default the global controller, with more than
 * one process): each rank builds spheres of its own piece, cells marked as
 * ghosts (vtkGhostType DUPLICATECELL) left out so that no occluder counts
 * twice; an object's NumberOfSpheres is shared between the ranks holding
 * pieces of it by their triangle counts (at least one sphere per non-empty
 * piece); a rank with an empty piece builds none. A piece is open along
 * the cut: with CapDistributedPieces (default on) each hole is closed by a
 * fan of triangles to its centroid before the build, so that the piece
 * encloses its share of the volume and gets interior samples (uncapped,
 * a cut bunny's pieces are bounded on their surface only, and their spheres
 * shadow too little). The spheres are then
 * all-gathered in rank order, so every rank outputs the same global set
 * (marked by the field array ProxyGIGlobalProxies) and the GI filters
 * downstream shade against all of it. The field data (E, volumes) stays the
 * rank's own piece's. A failure on one rank (bad input) fails every rank
 * with the rank's reason, never a hang. Set the controller to null for
 * per-rank sets.
 */
#ifndef vtkPGISphereSetApproximation_h
#define vtkPGISphereSetApproximation_h

#include "ProxyGIProxiesModule.h"
#include "vtkPolyDataAlgorithm.h"

class vtkMultiProcessController;

class PROXYGIPROXIES_EXPORT vtkPGISphereSetApproximation : public vtkPolyDataAlgorithm
{
public:
  static vtkPGISphereSetApproximation* New();
  vtkTypeMacro(vtkPGISphereSetApproximation, vtkPolyDataAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  enum Methods
  {
    VARIATIONAL = 0,
    OCTREE = 1,
    KMEANS = 2
  };
  vtkSetClampMacro(Method, int, VARIATIONAL, KMEANS);
  vtkGetMacro(Method, int);
  void SetMethodToVariational() { this->SetMethod(VARIATIONAL); }
  void SetMethodToOctree() { this->SetMethod(OCTREE); }
  void SetMethodToKMeans() { this->SetMethod(KMEANS); }
  static const char* GetMethodName(int method);

  vtkSetClampMacro(NumberOfSpheres, int, 1, VTK_INT_MAX);
  vtkGetMacro(NumberOfSpheres, int);

  /// With a value > 0, NumberOfSpheres is where the search for the smallest
  /// count meeting this E starts.
  vtkSetClampMacro(TargetOutsideVolumeRatio, double, 0.0, VTK_DOUBLE_MAX);
  vtkGetMacro(TargetOutsideVolumeRatio, double);
  vtkSetClampMacro(MaximumNumberOfSpheres, int, 1, VTK_INT_MAX);
  vtkGetMacro(MaximumNumberOfSpheres, int);

  vtkSetMacro(Seed, unsigned int);
  vtkGetMacro(Seed, unsigned int);

  vtkSetMacro(SplitConnectedComponents, bool);
  vtkGetMacro(SplitConnectedComponents, bool);
  vtkBooleanMacro(SplitConnectedComponents, bool);

  vtkSetClampMacro(VolumeResolution, int, 8, 4096);
  vtkGetMacro(VolumeResolution, int);
  vtkSetClampMacro(InteriorResolution, int, 1, 1024);
  vtkGetMacro(InteriorResolution, int);
  vtkSetClampMacro(MaximumIterations, int, 1, VTK_INT_MAX);
  vtkGetMacro(MaximumIterations, int);
  vtkSetClampMacro(MaximumTeleportFailures, int, 0, VTK_INT_MAX);
  vtkGetMacro(MaximumTeleportFailures, int);

  vtkSetMacro(ComputeOutsideVolume, bool);
  vtkGetMacro(ComputeOutsideVolume, bool);
  vtkBooleanMacro(ComputeOutsideVolume, bool);
  vtkSetClampMacro(MetricResolution, int, 8, 4096);
  vtkGetMacro(MetricResolution, int);

  /// Results of the last update, per object.
  int GetNumberOfObjects() const;
  double GetOutsideVolumeRatio(int object) const;
  double GetOutsideVolumeRatioSum(int object) const;
  /// Wall-clock seconds of the sphere construction (not the metric).
  double GetBuildTime(int object) const;
  double GetTotalBuildTime() const;

  /// The ranks the spheres are built and gathered over (null: this process alone).
  virtual void SetController(vtkMultiProcessController* controller);
  vtkGetObjectMacro(Controller, vtkMultiProcessController);
  /// Under MPI, close each piece's holes before the build (default on).
  vtkSetMacro(CapDistributedPieces, bool);
  vtkGetMacro(CapDistributedPieces, bool);
  vtkBooleanMacro(CapDistributedPieces, bool);
  /// Seconds and bytes received in the last update's collectives (0 serially).
  double GetGatherTime() const;
  double GetGatheredBytes() const;

protected:
  vtkPGISphereSetApproximation();
  ~vtkPGISphereSetApproximation() override;

  int FillInputPortInformation(int port, vtkInformation* info) override;
  int RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;

  int Method = VARIATIONAL;
  int NumberOfSpheres = 64;
  double TargetOutsideVolumeRatio = 0.0;
  int MaximumNumberOfSpheres = 1024;
  unsigned int Seed = 1;
  bool SplitConnectedComponents = false;
  int VolumeResolution = 128;
  int InteriorResolution = 32;
  int MaximumIterations = 100;
  int MaximumTeleportFailures = 8;
  bool ComputeOutsideVolume = true;
  int MetricResolution = 256;
  vtkMultiProcessController* Controller = nullptr;
  bool CapDistributedPieces = true;

private:
  vtkPGISphereSetApproximation(const vtkPGISphereSetApproximation&) = delete;
  void operator=(const vtkPGISphereSetApproximation&) = delete;

  struct Internal;
  Internal* Impl;
};

#endif
