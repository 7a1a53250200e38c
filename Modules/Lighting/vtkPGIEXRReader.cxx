#include "vtkPGIEXRReader.h"

#include "vtkFieldData.h"
#include "vtkFloatArray.h"
#include "vtkIdTypeArray.h"
#include "vtkImageData.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkLogger.h"
#include "vtkNew.h"
#include "vtkObjectFactory.h"
#include "vtkPointData.h"
#include "vtkStreamingDemandDrivenPipeline.h"

#include <ImfChannelList.h>
#include <ImfFrameBuffer.h>
#include <ImfHeader.h>
#include <ImfInputFile.h>

#include <cmath>
#include <mutex>
#include <set>
#include <string>
#include <vector>

vtkStandardNewMacro(vtkPGIEXRReader);

vtkPGIEXRReader::vtkPGIEXRReader()
{
  this->SetNumberOfInputPorts(0);
}

vtkPGIEXRReader::~vtkPGIEXRReader()
{
  this->SetFileName(nullptr);
}

void vtkPGIEXRReader::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "FileName: " << (this->FileName ? this->FileName : "(none)") << "\n";
  os << indent << "LatLong: " << this->LatLong << "\n";
  os << indent << "ClampValue: " << this->ClampValue << "\n";
  os << indent << "MaximumNumberOfPixels: " << this->MaximumNumberOfPixels << "\n";
  os << indent << "NumberOfClampedValues: " << this->NumberOfClampedValues << "\n";
}

bool vtkPGIEXRReader::ReadHeader(int& width, int& height)
{
  if (!this->FileName || !*this->FileName)
  {
    vtkErrorMacro("No FileName set.");
    return false;
  }
  try
  {
    Imf::InputFile file(this->FileName);
    const Imath::Box2i window = file.header().dataWindow();
    // In 64 bits: a hostile window's corners are any two ints.
    const long long w = static_cast<long long>(window.max.x) - window.min.x + 1;
    const long long h = static_cast<long long>(window.max.y) - window.min.y + 1;
    if (w < 1 || h < 1 || w * h > this->MaximumNumberOfPixels)
    {
      vtkErrorMacro("'" << this->FileName << "' claims a " << w << " x " << h
                        << " image; the reader takes 1 to " << this->MaximumNumberOfPixels
                        << " pixels (MaximumNumberOfPixels).");
      return false;
    }
    width = static_cast<int>(w);
    height = static_cast<int>(h);
    const Imf::ChannelList& channels = file.header().channels();
    if (!channels.findChannel("R") || !channels.findChannel("G") || !channels.findChannel("B"))
    {
      std::string names;
      for (auto it = channels.begin(); it != channels.end(); ++it)
      {
        names += std::string(names.empty() ? "" : ", ") + it.name();
      }
      vtkErrorMacro(
        "'" << this->FileName << "' has no R, G, B channels (it has: " << names << ").");
      return false;
    }
  }
  catch (const std::exception& e)
  {
    vtkErrorMacro("Cannot read OpenEXR file '" << this->FileName << "': " << e.what());
    return false;
  }
  if (this->LatLong && width != 2 * height)
  {
    vtkErrorMacro("'" << this->FileName << "' is " << width << " x " << height
                      << "; a lat-long environment map must be twice as wide as high.");
    return false;
  }
  return true;
}

int vtkPGIEXRReader::RequestInformation(
  vtkInformation*, vtkInformationVector**, vtkInformationVector* out)
{
  int width = 0, height = 0;
  if (!this->ReadHeader(width, height))
  {
    return 0;
  }
  const int extent[6] = { 0, width - 1, 0, height - 1, 0, 0 };
  vtkInformation* info = out->GetInformationObject(0);
  info->Set(vtkStreamingDemandDrivenPipeline::WHOLE_EXTENT(), extent, 6);
  vtkDataObject::SetPointDataActiveScalarInfo(info, VTK_FLOAT, 3);
  return 1;
}

int vtkPGIEXRReader::RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector* out)
{
  vtkImageData* output = vtkImageData::GetData(out);
  this->NumberOfClampedValues = 0;
  int width = 0, height = 0;
  if (!this->ReadHeader(width, height))
  {
    return 0;
  }
  std::vector<float> rgb;
  try
  {
    rgb.resize(static_cast<std::size_t>(width) * height * 3);
    Imf::InputFile file(this->FileName);
    const Imath::Box2i window = file.header().dataWindow();
    Imf::FrameBuffer frame;
    const std::size_t xStride = 3 * sizeof(float), yStride = xStride * width;
    // The data window's corner lands on rgb[0]. Slice::Make offsets the
    // base in integers: a pointer moved outside rgb is undefined (fuzzing).
    const char* names[3] = { "R", "G", "B" };
    for (int c = 0; c < 3; ++c)
    {
      frame.insert(
        names[c], Imf::Slice::Make(Imf::FLOAT, rgb.data() + c, window, xStride, yStride));
    }
    file.setFrameBuffer(frame);
    file.readPixels(window.min.y, window.max.y);
  }
  catch (const std::bad_alloc&)
  {
    vtkErrorMacro(
      "'" << this->FileName << "': out of memory for " << width << " x " << height << " pixels.");
    return 0;
  }
  catch (const std::exception& e)
  {
    vtkErrorMacro("Cannot read OpenEXR pixels of '" << this->FileName << "': " << e.what());
    return 0;
  }
  for (float& v : rgb)
  {
    if (!std::isfinite(v) || v < 0.0f)
    {
      v = (std::isinf(v) && v > 0.0f) ? static_cast<float>(this->ClampValue) : 0.0f;
      ++this->NumberOfClampedValues;
    }
  }
  if (this->NumberOfClampedValues > 0)
  {
    // A data-quality notice, not a fault: said once per file and process
    // (several readers of one map, or re-reads, repeat nothing).
    static std::mutex mutex;
    static std::set<std::string> said;
    std::lock_guard<std::mutex> lock(mutex);
    if (said.insert(this->FileName).second)
    {
      vtkLog(INFO,
        "'" << this->FileName << "': " << this->NumberOfClampedValues
            << " NaN, Inf or negative channel values clamped (GetNumberOfClampedValues).");
    }
  }
  vtkNew<vtkFloatArray> radiance;
  radiance->SetName("Radiance");
  radiance->SetNumberOfComponents(3);
  radiance->SetNumberOfTuples(static_cast<vtkIdType>(width) * height);
  if (radiance->GetNumberOfTuples() != static_cast<vtkIdType>(width) * height)
  {
    vtkErrorMacro(
      "'" << this->FileName << "': out of memory for " << width << " x " << height << " pixels.");
    return 0;
  }
  float* dst = radiance->GetPointer(0);
  for (int j = 0; j < height; ++j)
  {
    // EXR rows top-down, VTK rows bottom-up.
    std::copy(&rgb[3 * static_cast<std::size_t>(j) * width],
      &rgb[3 * static_cast<std::size_t>(j + 1) * width],
      dst + 3 * static_cast<std::size_t>(height - 1 - j) * width);
  }
  output->SetExtent(0, width - 1, 0, height - 1, 0, 0);
  output->GetPointData()->SetScalars(radiance);
  vtkNew<vtkIdTypeArray> clamped;
  clamped->SetName("ClampedValues");
  clamped->InsertNextValue(this->NumberOfClampedValues);
  output->GetFieldData()->AddArray(clamped);
  return 1;
}
