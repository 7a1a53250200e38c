/**
 * @file pgiVolumeRows.h
 * @brief An object's interior as exact intervals along parallel rows.
 *
 * Rows run along x, spaced h apart in y and z; each holds the intervals
 * where it is inside the mesh (from the ray crossings, so exact along x).
 * Volumes are integrals over the rows: a 2-D midpoint rule of exact lengths,
 * error O(h^2) for smooth boundaries. The outside volume of a sphere computed
 * this way is exactly zero for a sphere wholly inside, which keeps the
 * clustering costs free of sampling noise. Private to the Proxies module.
 */
#ifndef pgiVolumeRows_h
#define pgiVolumeRows_h

#include <vector>

namespace proxygi
{
class MeshQueries;
struct Sphere;

class VolumeRows
{
public:
  /**
   * Rows over `region` (y and z extents; x is unbounded) spaced h apart;
   * only rows crossing `meshBounds` are traced. A row with an odd number of
   * crossings (a hole, a grazing ray) is resolved point by point with the
   * majority test. When more than a quarter of the traced rows need that,
   * the mesh is taken not to enclose a volume: no interior at all.
   */
  void Build(
    const MeshQueries& queries, const double region[6], const double meshBounds[6], double h);

  double Spacing() const { return this->H; }
  int RowsY() const { return this->NY; }
  int RowsZ() const { return this->NZ; }
  double RowY(int j) const { return this->Y0 + (j + 0.5 + JitterY) * this->H; }
  double RowZ(int k) const { return this->Z0 + (k + 0.5 + JitterZ) * this->H; }
  /// Row index nearest to a coordinate (may be out of range).
  int IndexY(double y) const;
  int IndexZ(double z) const;
  bool Solid() const { return this->IsSolid; }
  int ResolvedRows() const { return this->Resolved; }
  int TracedRows() const { return this->Traced; }

  /// Inside length of row (j, k) within [a, b].
  double InsideLength(int j, int k, double a, double b) const
  {
    int n;
    const double* e = this->Intervals(j, k, n);
    double length = 0.0;
    for (int i = 0; i < n && e[2 * i] < b; ++i)
    {
      const double lo = a > e[2 * i] ? a : e[2 * i];
      const double hi = b < e[2 * i + 1] ? b : e[2 * i + 1];
      length += hi > lo ? hi - lo : 0.0;
    }
    return length;
  }
  /// Whether x on row (j, k) is inside.
  bool Inside(int j, int k, double x) const;
  /// Intervals of row (j, k): pointer to pairs (begin, end) and their count.
  const double* Intervals(int j, int k, int& count) const
  {
    if (j < 0 || k < 0 || j >= this->NY || k >= this->NZ)
    {
      count = 0;
      return nullptr;
    }
    const int r = j * this->NZ + k;
    count = this->Start[r + 1] - this->Start[r];
    return this->Ends.data() + 2 * this->Start[r];
  }

  /// Enclosed volume.
  double Volume() const;
  /// Volume of the sphere inside the object, and outside it (the row
  /// quadrature of the sphere minus the former: zero for a sphere inside).
  double InsideVolume(const double center[3], double radius) const;
  /// With stride s > 1 only every s-th row in y and z counts (weight s^2):
  /// cost bounded for large spheres, still exactly zero inside.
  double OutsideVolume(const double center[3], double radius, int stride = 1) const;
  /// The stride that keeps about `rows` rows across a sphere's radius.
  int StrideFor(double radius, double rows = 16.0) const;
  /**
   * Outside volume of the spheres of radius b * step about `center`, for
   * b = 0 .. bins (bins + 1 values), over every stride-th row.
   */
  void OutsideProfile(const double center[3], double step, int bins, std::vector<double>& table,
    int stride = 1) const;

private:
  // Keeps rows off the exact coordinates of axis-aligned meshes; does not
  // bias the midpoint rule, whose integrand vanishes at the region's edges.
  static constexpr double JitterY = 0.0137;
  static constexpr double JitterZ = 0.0291;
  double H = 1.0, Y0 = 0.0, Z0 = 0.0;
  int NY = 0, NZ = 0;
  int Resolved = 0, Traced = 0;
  bool IsSolid = true;
  std::vector<int> Start;   // NY * NZ + 1 offsets (in intervals)
  std::vector<double> Ends; // begin, end per interval
};
} // namespace proxygi

#endif
