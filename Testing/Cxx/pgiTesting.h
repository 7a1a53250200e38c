/**
 * @file pgiTesting.h
 * @brief Small checks for ProxyGI's VTK-style tests: each failed check prints
 * what it compared and marks the test failed; the test returns Result().
 */
#ifndef pgiTesting_h
#define pgiTesting_h

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

namespace pgitest
{
/// Whether some line holds `text` (a filter's plan); with `report`, a miss
/// prints the lines.
inline bool Says(
  const std::vector<std::string>& lines, const std::string& text, bool report = false)
{
  for (const std::string& line : lines)
  {
    if (line.find(text) != std::string::npos)
    {
      return true;
    }
  }
  if (report)
  {
    std::printf("plan lacks \"%s\"; it says:\n", text.c_str());
    for (const std::string& line : lines)
    {
      std::printf("  %s\n", line.c_str());
    }
  }
  return false;
}

/// The test's temporary directory: the value of "-T" (vtk_add_test_cxx
/// passes it), else ".".
inline std::string TempDirectory(int argc, char* argv[])
{
  std::string dir = ".";
  for (int i = 0; i + 1 < argc; ++i)
  {
    if (std::string(argv[i]) == "-T")
    {
      dir = argv[i + 1];
    }
  }
  return dir;
}

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

/**
 * The tests' one relative RMSE, as a running sum: Add(value, reference)
 * per component compared; RelativeRMSE() is sqrt(sum (a - b)^2 / sum b^2)
 * (0 when both sums are 0, +inf for an error against an all-zero
 * reference, NaN when a value was NaN), Worst the largest |a - b|.
 */
struct ErrorSum
{
  double Squared = 0.0, Reference = 0.0, Worst = 0.0;
  long Count = 0;
  void Add(double value, double reference)
  {
    const double e = value - reference;
    this->Squared += e * e;
    this->Reference += reference * reference;
    this->Worst = std::isnan(e) ? e : std::max(this->Worst, std::fabs(e));
    ++this->Count;
  }
  double RelativeRMSE() const
  {
    if (this->Reference > 0.0)
    {
      return std::sqrt(this->Squared / this->Reference);
    }
    return this->Squared > 0.0 ? HUGE_VAL : (this->Squared == 0.0 ? 0.0 : this->Squared);
  }
  double RMS() const { return this->Count ? std::sqrt(this->Squared / this->Count) : 0.0; }
};

/// The tests' one relative RMSE (ErrorSum) over
/// component 0 of a's tuples (b may hold more: a receiver patch first), or
/// of those with mask[i]. Arrays as for NonFiniteValues.
template <class ArrayA, class ArrayB>
double RelativeRMSE(ArrayA* a, ArrayB* b, const std::vector<char>* mask = nullptr)
{
  ErrorSum errors;
  for (long i = 0; i < static_cast<long>(a->GetNumberOfTuples()); ++i)
  {
    if (!mask || (*mask)[i])
    {
      errors.Add(a->GetComponent(i, 0), b->GetComponent(i, 0));
    }
  }
  return errors.RelativeRMSE();
}
} // namespace pgitest

#define PGI_CHECK(cond) pgitest::Check((cond), #cond, __FILE__, __LINE__)
#define PGI_NEAR(a, b, tol) pgitest::Near((a), (b), (tol), #a " vs " #b, __FILE__, __LINE__)
#define PGI_BELOW(a, bound) pgitest::Below((a), (bound), #a, __FILE__, __LINE__)

#endif
