/**
 * @class   vtkPGISphereHierarchy
 * @brief   Adds a bounding sphere hierarchy above leaf proxies.
 *
 * Input: proxies (points with "Radius"; "ObjectId" groups them into
 * objects; with a "Level" array only level-0 points are leaves, the rest is
 * rebuilt). Output: the leaves first (same order, their point data passed
 * on), then per object the levels above them up to one root, built bottom-up
 * as in the SHEXP paper (Section 6.3): Lloyd clustering of the level's
 * sphere centres into about n / Branching clusters (evened out to 2 to
 * 2 x Branching children each), each parent the near-minimal sphere
 * bounding its children. "Level" is 0 for leaves and
 * counts up to the root; "Parent" holds the parent's point id (-1 for roots);
 * parents carry their object's "ObjectId". Field data "HierarchyDepth" and
 * "MeanBranching" per object.
 *
 * After the leaves move (vtkPGIProxyDeformation does this itself), Refit()
 * restores the bounding property bottom-up by pairwise sphere bounds.
 * Cost: milliseconds for hundreds of leaves.
 */
#ifndef vtkPGISphereHierarchy_h
#define vtkPGISphereHierarchy_h

#include "ProxyGIProxiesModule.h"
#include "vtkPolyDataAlgorithm.h"

class PROXYGIPROXIES_EXPORT vtkPGISphereHierarchy : public vtkPolyDataAlgorithm
{
public:
  static vtkPGISphereHierarchy* New();
  vtkTypeMacro(vtkPGISphereHierarchy, vtkPolyDataAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  /// Children per parent aimed at (>= 2); default 4.
  vtkSetClampMacro(Branching, int, 2, 64);
  vtkGetMacro(Branching, int);

  vtkSetMacro(Seed, unsigned int);
  vtkGetMacro(Seed, unsigned int);

  /**
   * Refits every parent of `proxies` in place, lowest levels first, as the
   * running pairwise bound of its children. False (nothing changed) without
   * the arrays.
   */
  static bool Refit(vtkPolyData* proxies);

  /**
   * Largest amount by which a node pokes out of one of its ancestors
   * (<= 0: every parent bounds its subtree). NaN without the arrays.
   */
  static double GetMaximumBoundingViolation(vtkPolyData* proxies);

protected:
  vtkPGISphereHierarchy();
  ~vtkPGISphereHierarchy() override;

  int RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;

  int Branching = 4;
  unsigned int Seed = 1;

private:
  vtkPGISphereHierarchy(const vtkPGISphereHierarchy&) = delete;
  void operator=(const vtkPGISphereHierarchy&) = delete;
};

#endif
