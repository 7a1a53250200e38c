// What the fuzz harnesses share: silence for the messages bad input is
// meant to produce, and the checks that turn a wrong result into a crash the
// fuzzer keeps (a NaN that reaches an output array is a finding, like a
// segfault).
#ifndef pgiFuzz_h
#define pgiFuzz_h

#include "vtkDataArray.h"
#include "vtkDataSetAttributes.h"
#include "vtkLogger.h"
#include "vtkObject.h"
#include "vtkPoints.h"

#include <cmath>
#include <cstdio>
#include <cstdlib>

namespace pgiFuzz
{
// Refusals print vtkErrorMacro messages; thousands a second would drown
// the fuzzer's own report.
inline bool Quiet()
{
  vtkObject::GlobalWarningDisplayOff();
  vtkLogger::SetStderrVerbosity(vtkLogger::VERBOSITY_OFF);
  return true;
}

[[noreturn]] inline void Finding(const char* what)
{
  std::fprintf(stderr, "pgiFuzz finding: %s\n", what);
  std::abort();
}

inline bool Finite(vtkDataArray* a)
{
  if (!a)
  {
    return true;
  }
  const vtkIdType n = a->GetNumberOfValues();
  for (vtkIdType i = 0; i < n; ++i)
  {
    if (!std::isfinite(a->GetVariantValue(i).ToDouble()))
    {
      return false;
    }
  }
  return true;
}

inline bool Finite(vtkDataSetAttributes* attributes)
{
  for (int i = 0; attributes && i < attributes->GetNumberOfArrays(); ++i)
  {
    if (!Finite(attributes->GetArray(i)))
    {
      return false;
    }
  }
  return true;
}

inline bool Finite(vtkPoints* points)
{
  return !points || Finite(points->GetData());
}
} // namespace pgiFuzz

#endif
