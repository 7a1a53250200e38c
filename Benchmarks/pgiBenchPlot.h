/**
 * @file pgiBenchPlot.h
 * @brief The benchmarks' one plot: series of points (or a line) on a
 * vtkChartXY, rendered off screen to a PNG.
 */
#ifndef pgiBenchPlot_h
#define pgiBenchPlot_h

#include <string>
#include <vector>

namespace pgibench
{
struct Series
{
  std::string Name;
  std::vector<double> X, Y;
  bool Line = false;
};

struct PlotAxes
{
  std::string Title, X, Y;
  bool LogX = true, LogY = true;
};

/// Writes the series as a PNG of 900 x 600 pixels (needs a GL context).
void WritePlot(const std::string& path, const PlotAxes& axes, const std::vector<Series>& series);
} // namespace pgibench

#endif
