#include "proxygiImage.h"
#include "proxygiProgress.h"

#include <vtkDataArray.h>
#include <vtkImageData.h>
#include <vtkNew.h>
#include <vtkPNGWriter.h>
#include <vtkPointData.h>
#include <vtkPolyData.h>
#include <vtkXMLPolyDataWriter.h>

#include <algorithm>
#include <cmath>
#include <vector>

namespace proxygi
{
namespace cli
{

double AutoExposure(std::vector<double>& luminance)
{
  if (luminance.empty())
  {
    return 1.0;
  }
  const std::size_t k = std::min(luminance.size() - 1, luminance.size() * 95 / 100);
  std::nth_element(luminance.begin(), luminance.begin() + k, luminance.end());
  return luminance[k] > 0.0 ? 0.8 / luminance[k] : 1.0;
}

double AutoExposure(vtkImageData* radiance)
{
  vtkDataArray* rgb = radiance->GetPointData()->GetScalars();
  std::vector<double> luminance(rgb->GetNumberOfTuples());
  for (vtkIdType i = 0; i < rgb->GetNumberOfTuples(); ++i)
  {
    luminance[i] =
      Luminance(rgb->GetComponent(i, 0), rgb->GetComponent(i, 1), rgb->GetComponent(i, 2));
  }
  return AutoExposure(luminance);
}

bool WriteTonemappedPNG(vtkImageData* radiance, double exposure, const std::string& path)
{
  int dims[3];
  radiance->GetDimensions(dims);
  vtkDataArray* rgb = radiance->GetPointData()->GetScalars();
  vtkNew<vtkImageData> image;
  image->SetDimensions(dims[0], dims[1], 1);
  image->AllocateScalars(VTK_UNSIGNED_CHAR, 3);
  auto* out = static_cast<unsigned char*>(image->GetScalarPointer());
  for (vtkIdType i = 0; i < static_cast<vtkIdType>(dims[0]) * dims[1]; ++i)
  {
    for (int c = 0; c < 3; ++c)
    {
      out[3 * i + c] = ToSRGB8(exposure * rgb->GetComponent(i, c));
    }
  }
  return WritePNG(image, path);
}

bool WritePNG(vtkImageData* image, const std::string& path)
{
  return WriteThenRename(path,
    [&](const std::string& temporary)
    {
      vtkNew<vtkPNGWriter> writer;
      writer->SetFileName(temporary.c_str());
      writer->SetInputData(image);
      writer->Write();
      return writer->GetErrorCode() == 0;
    });
}

bool WritePolyData(vtkPolyData* data, const std::string& path)
{
  return WriteThenRename(path,
    [&](const std::string& temporary)
    {
      vtkNew<vtkXMLPolyDataWriter> writer;
      writer->SetFileName(temporary.c_str());
      writer->SetInputData(data);
      writer->SetDataModeToAppended();
      return writer->Write() == 1;
    });
}

} // namespace cli
} // namespace proxygi
