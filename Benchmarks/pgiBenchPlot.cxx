#include "pgiBenchPlot.h"

#include <vtkAxis.h>
#include <vtkChartXY.h>
#include <vtkContextScene.h>
#include <vtkContextView.h>
#include <vtkDoubleArray.h>
#include <vtkNew.h>
#include <vtkPNGWriter.h>
#include <vtkPlot.h>
#include <vtkRenderWindow.h>
#include <vtkRenderer.h>
#include <vtkSmartPointer.h>
#include <vtkTable.h>
#include <vtkWindowToImageFilter.h>

namespace pgibench
{
void WritePlot(const std::string& path, const PlotAxes& axes, const std::vector<Series>& series)
{
  vtkNew<vtkContextView> view;
  view->GetRenderWindow()->SetOffScreenRendering(1);
  view->GetRenderWindow()->SetSize(900, 600);
  view->GetRenderer()->SetBackground(1, 1, 1);
  vtkNew<vtkChartXY> chart;
  view->GetScene()->AddItem(chart);
  chart->SetShowLegend(true);
  chart->GetAxis(vtkAxis::LEFT)->SetTitle(axes.Y);
  chart->GetAxis(vtkAxis::BOTTOM)->SetTitle(axes.X);
  chart->GetAxis(vtkAxis::LEFT)->SetLogScale(axes.LogY);
  chart->GetAxis(vtkAxis::BOTTOM)->SetLogScale(axes.LogX);
  chart->SetTitle(axes.Title);
  const unsigned char palette[12][3] = { { 0, 0, 0 }, { 31, 119, 180 }, { 255, 127, 14 },
    { 44, 160, 44 }, { 214, 39, 40 }, { 148, 103, 189 }, { 140, 86, 75 }, { 227, 119, 194 },
    { 127, 127, 127 }, { 188, 189, 34 }, { 23, 190, 207 }, { 255, 187, 120 } };
  std::vector<vtkSmartPointer<vtkTable>> tables;
  for (std::size_t k = 0; k < series.size(); ++k)
  {
    auto table = vtkSmartPointer<vtkTable>::New();
    vtkNew<vtkDoubleArray> x, y;
    x->SetName("x");
    y->SetName(series[k].Name.c_str());
    for (std::size_t i = 0; i < series[k].X.size() && i < series[k].Y.size(); ++i)
    {
      x->InsertNextValue(series[k].X[i]);
      y->InsertNextValue(series[k].Y[i]);
    }
    table->AddColumn(x);
    table->AddColumn(y);
    tables.push_back(table);
    vtkPlot* plot = chart->AddPlot(series[k].Line ? vtkChart::LINE : vtkChart::POINTS);
    plot->SetInputData(table, 0, 1);
    const unsigned char* rgb = palette[k % 12];
    plot->SetColor(rgb[0], rgb[1], rgb[2], 255);
    plot->SetWidth(2.0);
  }
  view->GetRenderWindow()->Render();
  vtkNew<vtkWindowToImageFilter> grab;
  grab->SetInput(view->GetRenderWindow());
  vtkNew<vtkPNGWriter> png;
  png->SetFileName(path.c_str());
  png->SetInputConnection(grab->GetOutputPort());
  png->Write();
}
} // namespace pgibench
