/**
 * @file pgiTestingErrors.h
 * @brief Whether updating a filter reports an error (for the bad-input
 * cases of tests that link VTK's execution model and TestingCore).
 */
#ifndef pgiTestingErrors_h
#define pgiTestingErrors_h

#include "vtkAlgorithm.h"
#include "vtkCommand.h"
#include "vtkExecutive.h"
#include "vtkNew.h"
#include "vtkTestErrorObserver.h"

#include <cstdio>
#include <string>

namespace pgitest
{
/// Re-runs `algorithm` and says whether it or its executive reported an error.
inline bool Fails(vtkAlgorithm* algorithm)
{
  vtkNew<vtkTest::ErrorObserver> observer;
  algorithm->AddObserver(vtkCommand::ErrorEvent, observer);
  algorithm->GetExecutive()->AddObserver(vtkCommand::ErrorEvent, observer);
  algorithm->Modified();
  algorithm->Update();
  return observer->GetError();
}

/// Re-runs `algorithm`; true when it reported an error holding `text`
/// (a miss prints what it said instead).
inline bool FailsSaying(vtkAlgorithm* algorithm, const char* text)
{
  vtkNew<vtkTest::ErrorObserver> observer;
  algorithm->AddObserver(vtkCommand::ErrorEvent, observer);
  algorithm->GetExecutive()->AddObserver(vtkCommand::ErrorEvent, observer);
  algorithm->Modified();
  algorithm->Update();
  const std::string said = observer->GetError() ? observer->GetErrorMessage() : "";
  if (said.find(text) == std::string::npos)
  {
    std::printf("expected an error saying \"%s\"; got \"%s\"\n", text, said.c_str());
    return false;
  }
  return true;
}

/// The same for a warning (the update itself succeeds).
inline bool WarnsSaying(vtkAlgorithm* algorithm, const char* text)
{
  vtkNew<vtkTest::ErrorObserver> observer;
  algorithm->AddObserver(vtkCommand::WarningEvent, observer);
  algorithm->Modified();
  algorithm->Update();
  const std::string said = observer->GetWarning() ? observer->GetWarningMessage() : "";
  if (said.find(text) == std::string::npos)
  {
    std::printf("expected a warning saying \"%s\"; got \"%s\"\n", text, said.c_str());
    return false;
  }
  return true;
}
} // namespace pgitest

#endif
