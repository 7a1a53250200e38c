/**
 * @file pgiParallel.h
 * @brief The collectives ProxyGI's filters share under MPI (or any
 *        vtkMultiProcessController): global illumination is global, so every
 *        rank shades its own piece against the proxies of all ranks.
 *
 * Every function here is collective: all ranks of the controller call it, in
 * the same order, even a rank whose piece is empty or whose input is bad
 * (it passes ok = false). With a null controller or one process each is a
 * serial pass-through that communicates nothing, so a filter calls them
 * unconditionally.
 *
 * Order is deterministic: gathered sets are in rank order, each rank's
 * points in their own order, so every rank (and every run) sees the same
 * global proxies and builds the same precompute from them.
 */
#ifndef pgiParallel_h
#define pgiParallel_h

#include "ProxyGIParallelModule.h"

#include "vtkSmartPointer.h"

#include <cstddef>
#include <string>
#include <vector>

class vtkMultiProcessController;
class vtkPolyData;

namespace proxygi
{
namespace parallel
{
/// `controller` when it has more than one process, else null (run serially).
PROXYGIPARALLEL_EXPORT vtkMultiProcessController* Active(vtkMultiProcessController* controller);
/// This rank (0 without an active controller) and the number of ranks (1).
PROXYGIPARALLEL_EXPORT int Rank(vtkMultiProcessController* controller);
PROXYGIPARALLEL_EXPORT int Ranks(vtkMultiProcessController* controller);

/// What a rank sent and received in the collectives of one call.
struct PROXYGIPARALLEL_EXPORT Traffic
{
  std::size_t BytesSent = 0, BytesReceived = 0;
  double Seconds = 0.0;
  void Add(const Traffic& other);
};

/**
 * Collective status agreement. Each rank passes whether it can go on and,
 * if not, why. True on every rank when all are ok; otherwise false on every
 * rank, with `error` naming each failing rank and its reason
 * ("rank 1: Receiver 0 has a NaN or Inf coordinate"). A rank that stops
 * early therefore never leaves the others waiting in a later collective.
 */
PROXYGIPARALLEL_EXPORT bool AllOk(vtkMultiProcessController* controller, bool ok,
  const std::string& localError, std::string& error, Traffic* traffic = nullptr);

/// Collective logical or / sum / max of one value per rank.
PROXYGIPARALLEL_EXPORT bool AnyTrue(vtkMultiProcessController* controller, bool value);
PROXYGIPARALLEL_EXPORT double Sum(vtkMultiProcessController* controller, double value);
PROXYGIPARALLEL_EXPORT double Max(vtkMultiProcessController* controller, double value);
/// The same for `count` values at once, in place (one collective).
PROXYGIPARALLEL_EXPORT void SumEach(
  vtkMultiProcessController* controller, double* values, int count);
PROXYGIPARALLEL_EXPORT void MaxEach(
  vtkMultiProcessController* controller, double* values, int count);
/// Collective: the box lo..hi becomes the union of every rank's (one
/// collective; a rank with nothing gives lo = +max, hi = -max).
PROXYGIPARALLEL_EXPORT void GlobalBox(
  vtkMultiProcessController* controller, double lo[3], double hi[3]);

/// Collective: one integer per rank, gathered on every rank in rank order.
PROXYGIPARALLEL_EXPORT std::vector<long long> AllGatherCounts(
  vtkMultiProcessController* controller, long long value, Traffic* traffic = nullptr);

/**
 * Collective: every rank's polydata (null counts as empty), appended in rank
 * order on every rank: points, verts, lines, polys and strips, and the point
 * arrays every non-empty piece has (by name). The local field data is kept.
 * A "Parent" vtkIdType point array (a sphere hierarchy) is re-based so that
 * its indices stay right in the appended set.
 */
PROXYGIPARALLEL_EXPORT vtkSmartPointer<vtkPolyData> AllGatherPolyData(
  vtkMultiProcessController* controller, vtkPolyData* local, Traffic* traffic = nullptr);

/// The field array that marks a proxy set as the global one (its value: the ranks).
PROXYGIPARALLEL_EXPORT const char* GlobalProxiesMarkName();
/// True when `proxies` carry the mark of a global set.
PROXYGIPARALLEL_EXPORT bool IsGlobal(vtkPolyData* proxies);

/**
 * Collective: the global proxy set from every rank's local one. When every
 * rank's set already carries the global mark (an upstream filter gathered
 * them) each rank keeps its own and nothing but a header moves; otherwise
 * the sets are all-gathered in rank order and the result is marked. Ranks
 * that disagree (some marked, some not) get null and `error`. Serial: the
 * input itself.
 */
PROXYGIPARALLEL_EXPORT vtkSmartPointer<vtkPolyData> GatherProxies(
  vtkMultiProcessController* controller, vtkPolyData* local, std::string& error,
  Traffic* traffic = nullptr);
} // namespace parallel
} // namespace proxygi

#endif
