#include "vtkPGIEXRWriter.h"

#include "vtkDataArray.h"
#include "vtkImageData.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkObjectFactory.h"
#include "vtkPointData.h"

#include <ImfChannelList.h>
#include <ImfFrameBuffer.h>
#include <ImfHeader.h>
#include <ImfOutputFile.h>

#include <vector>

vtkStandardNewMacro(vtkPGIEXRWriter);

vtkPGIEXRWriter::vtkPGIEXRWriter()
{
  this->SetNumberOfOutputPorts(0);
}

vtkPGIEXRWriter::~vtkPGIEXRWriter()
{
  this->SetFileName(nullptr);
}

void vtkPGIEXRWriter::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "FileName: " << (this->FileName ? this->FileName : "(none)") << "\n";
}

int vtkPGIEXRWriter::FillOutputPortInformation(int, vtkInformation*)
{
  return 1;
}

bool vtkPGIEXRWriter::Write()
{
  this->Modified();
  this->Update();
  return this->GetErrorCode() == 0;
}

int vtkPGIEXRWriter::RequestData(vtkInformation*, vtkInformationVector** in, vtkInformationVector*)
{
  this->SetErrorCode(0);
  vtkImageData* image = vtkImageData::GetData(in[0]);
  if (!this->FileName || !*this->FileName)
  {
    vtkErrorMacro("No FileName set.");
    this->SetErrorCode(1);
    return 0;
  }
  vtkDataArray* scalars = image ? image->GetPointData()->GetScalars() : nullptr;
  int dims[3] = { 0, 0, 0 };
  if (image)
  {
    image->GetDimensions(dims);
  }
  if (!scalars || scalars->GetNumberOfComponents() < 3 || dims[2] != 1 || dims[0] < 1)
  {
    vtkErrorMacro("Input must be a 2-D image with RGB point scalars.");
    this->SetErrorCode(1);
    return 0;
  }
  const int width = dims[0], height = dims[1];
  std::vector<float> rgb(static_cast<std::size_t>(width) * height * 3);
  for (int j = 0; j < height; ++j)
  {
    const int row = height - 1 - j; // EXR rows top-down
    for (int i = 0; i < width; ++i)
    {
      for (int c = 0; c < 3; ++c)
      {
        rgb[3 * (static_cast<std::size_t>(j) * width + i) + c] =
          static_cast<float>(scalars->GetComponent(static_cast<vtkIdType>(row) * width + i, c));
      }
    }
  }
  try
  {
    Imf::Header header(width, height);
    header.compression() = Imf::ZIP_COMPRESSION;
    const char* names[3] = { "R", "G", "B" };
    Imf::FrameBuffer frame;
    for (int c = 0; c < 3; ++c)
    {
      header.channels().insert(names[c], Imf::Channel(Imf::FLOAT));
      frame.insert(names[c],
        Imf::Slice(Imf::FLOAT, reinterpret_cast<char*>(rgb.data() + c), 3 * sizeof(float),
          3 * sizeof(float) * width));
    }
    Imf::OutputFile file(this->FileName, header);
    file.setFrameBuffer(frame);
    file.writePixels(height);
  }
  catch (const std::exception& e)
  {
    vtkErrorMacro("Cannot write OpenEXR file '" << this->FileName << "': " << e.what());
    this->SetErrorCode(1);
    return 0;
  }
  return 1;
}
