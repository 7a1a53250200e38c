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
} // namespace pgitest

#endif
