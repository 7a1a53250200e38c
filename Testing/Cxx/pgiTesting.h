/**
 * @file pgiTesting.h
 * @brief Small checks for ProxyGI's VTK-style tests: each failed check prints
 * what it compared and marks the test failed; the test returns Result().
 */
#ifndef pgiTesting_h
#define pgiTesting_h

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <vector>

namespace pgitest
{
inline int& Failures()
{
  static int count = 0;
  return count;
}
inline int Result()
{
  if (Failures() != 0)
  {
    std::printf("%d check(s) failed\n", Failures());
    return EXIT_FAILURE;
  }
  return EXIT_SUCCESS;
}
inline bool Check(bool ok, const char* what, const char* file, int line)
{
  if (!ok)
  {
    std::printf("FAILED %s:%d: %s\n", file, line, what);
    ++Failures();
  }
  return ok;
}
inline bool Near(double a, double b, double tol, const char* what, const char* file, int line)
{
  const bool ok = std::fabs(a - b) <= tol; // false for NaN
  if (!ok)
  {
    std::printf("FAILED %s:%d: %s: %.12g vs %.12g (tolerance %.3g)\n", file, line, what, a, b, tol);
    ++Failures();
  }
  return ok;
}
inline bool Below(double a, double bound, const char* what, const char* file, int line)
{
  const bool ok = a <= bound;
  if (!ok)
  {
    std::printf("FAILED %s:%d: %s: %.6g exceeds %.6g\n", file, line, what, a, bound);
    ++Failures();
  }
  return ok;
}
/// How many values of a VTK data array (any with GetNumberOfTuples,
/// GetNumberOfComponents and GetComponent) are NaN or infinite.
template <class Array>
long NonFiniteValues(Array* array)
{
  long bad = 0;
  for (long t = 0; t < static_cast<long>(array->GetNumberOfTuples()); ++t)
  {
    for (int c = 0; c < array->GetNumberOfComponents(); ++c)
    {
      bad += std::isfinite(array->GetComponent(t, c)) ? 0 : 1;
    }
  }
  return bad;
}

/// The tests' one relative RMSE: sqrt(sum (a - b)^2 / sum b^2) over
/// component 0 of a's tuples (b may hold more: a receiver patch first), or
/// of those with mask[i]. Arrays as for NonFiniteValues.
template <class ArrayA, class ArrayB>
double RelativeRMSE(ArrayA* a, ArrayB* b, const std::vector<char>* mask = nullptr)
{
  double sq = 0.0, ref = 0.0;
  for (long i = 0; i < static_cast<long>(a->GetNumberOfTuples()); ++i)
  {
    if (mask && !(*mask)[i])
    {
      continue;
    }
    const double d = a->GetComponent(i, 0) - b->GetComponent(i, 0);
    sq += d * d;
    ref += b->GetComponent(i, 0) * b->GetComponent(i, 0);
  }
  return std::sqrt(sq / ref);
}
} // namespace pgitest

#define PGI_CHECK(cond) pgitest::Check((cond), #cond, __FILE__, __LINE__)
#define PGI_NEAR(a, b, tol) pgitest::Near((a), (b), (tol), #a " vs " #b, __FILE__, __LINE__)
#define PGI_BELOW(a, bound) pgitest::Below((a), (bound), #a, __FILE__, __LINE__)

#endif
