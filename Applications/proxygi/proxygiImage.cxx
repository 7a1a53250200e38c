#include "proxygiImage.h"

#include <vtkDataArray.h>
#include <vtkImageData.h>
#include <vtkNew.h>
#include <vtkPNGWriter.h>
#include <vtkPointData.h>

#include <algorithm>
#include <cmath>
#include <vector>

namespace proxygi
{
namespace cli
{

unsigned char ToSRGB8(double v)
{
  v = v < 0.0 ? 0.0 : (v > 1.0 ? 1.0 : v);
  const double s = v <= 0.0031308 ? 12.92 * v : 1.055 * std::pow(v, 1.0 / 2.4) - 0.055;
  return static_cast<unsigned char>(std::lround(255.0 * s));
}

double FromSRGB8(unsigned char v)
{
  const double s = v / 255.0;
  return s <= 0.04045 ? s / 12.92 : std::pow((s + 0.055) / 1.055, 2.4);
}

double AutoExposure(vtkImageData* radiance)
{
  vtkDataArray* rgb = radiance->GetPointData()->GetScalars();
  std::vector<double> lum(rgb->GetNumberOfTuples());
  for (vtkIdType i = 0; i < rgb->GetNumberOfTuples(); ++i)
  {
    lum[i] = 0.2126 * rgb->GetComponent(i, 0) + 0.7152 * rgb->GetComponent(i, 1) +
      0.0722 * rgb->GetComponent(i, 2);
  }
  if (lum.empty())
  {
    return 1.0;
  }
  const std::size_t k = std::min(lum.size() - 1, lum.size() * 99 / 100);
  std::nth_element(lum.begin(), lum.begin() + k, lum.end());
  return lum[k] > 0.0 ? 1.0 / lum[k] : 1.0;
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
  vtkNew<vtkPNGWriter> writer;
  writer->SetFileName(path.c_str());
  writer->SetInputData(image);
  writer->Write();
  return writer->GetErrorCode() == 0;
}

} // namespace cli
} // namespace proxygi
