// OpenEXR in and out: exact round trip, and clear errors for missing files,
// wrong channel layouts, non-2:1 sizes; NaN/Inf texels are clamped and counted.
#include "vtkPGIEXRReader.h"
#include "vtkPGIEXRWriter.h"
#include "vtkPGILighting.h"

#include "pgiEnvironmentMap.h"

#include "pgiTesting.h"
#include "vtkExecutive.h"
#include "vtkFloatArray.h"
#include "vtkImageData.h"
#include "vtkLogger.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkTestErrorObserver.h"

#include <ImfChannelList.h>
#include <ImfFrameBuffer.h>
#include <ImfHeader.h>
#include <ImfOutputFile.h>

#include <cstdio>
#include <cstring>
#include <limits>
#include <random>

namespace
{
vtkSmartPointer<vtkImageData> MakeImage(int w, int h, unsigned seed)
{
  auto image = vtkSmartPointer<vtkImageData>::New();
  image->SetDimensions(w, h, 1);
  vtkNew<vtkFloatArray> a;
  a->SetNumberOfComponents(3);
  a->SetNumberOfTuples(w * h);
  std::mt19937 rng(seed);
  std::lognormal_distribution<float> dist(0.0f, 3.0f);
  for (vtkIdType i = 0; i < 3 * w * h; ++i)
  {
    a->SetValue(i, dist(rng));
  }
  image->GetPointData()->SetScalars(a);
  return image;
}

bool ReadFails(vtkPGIEXRReader* reader)
{
  vtkNew<vtkTest::ErrorObserver> observer;
  reader->AddObserver(vtkCommand::ErrorEvent, observer);
  reader->GetExecutive()->AddObserver(vtkCommand::ErrorEvent, observer);
  reader->Modified();
  reader->Update();
  return observer->GetError();
}
} // namespace

int TestEXRFiles(int, char*[])
{
  // Round trip: bit-exact floats, rows in the same order.
  auto image = MakeImage(64, 32, 1);
  vtkNew<vtkPGIEXRWriter> writer;
  writer->SetFileName("/tmp/pgi-roundtrip.exr");
  writer->SetInputData(image);
  PGI_CHECK(writer->Write());
  vtkNew<vtkPGIEXRReader> reader;
  reader->SetFileName("/tmp/pgi-roundtrip.exr");
  reader->Update();
  vtkDataArray* back = reader->GetOutput()->GetPointData()->GetScalars();
  PGI_CHECK(back && back->GetNumberOfTuples() == 64 * 32);
  if (back)
  {
    double worst = 0.0;
    vtkDataArray* orig = image->GetPointData()->GetScalars();
    for (vtkIdType i = 0; i < 64 * 32; ++i)
    {
      for (int c = 0; c < 3; ++c)
      {
        worst = std::max(worst, std::fabs(back->GetComponent(i, c) - orig->GetComponent(i, c)));
      }
    }
    PGI_CHECK(worst == 0.0);
  }

  // vtkPGILighting's EnvironmentFileName reads the same file; the scale
  // multiplies its SH; a missing file is an error with the name, no crash.
  {
    vtkNew<vtkPGILighting> fromFile, fromImage;
    fromFile->SetEnvironmentFileName("/tmp/pgi-roundtrip.exr");
    fromImage->SetEnvironmentImage(image);
    const proxygi::EnvironmentMap *a = nullptr, *b = nullptr;
    std::string error;
    PGI_CHECK(fromFile->GetEnvironment(a, error) && fromImage->GetEnvironment(b, error));
    double ra[9], ga[9], ba[9], rb[9], gb[9], bb[9];
    if (a && b)
    {
      a->ProjectSH(3, ra, ga, ba);
      b->ProjectSH(3, rb, gb, bb);
      PGI_NEAR(ra[0], rb[0], 1e-12);
      PGI_NEAR(ba[4], bb[4], 1e-12);
    }
    fromFile->SetEnvironmentScale(2.0);
    PGI_CHECK(fromFile->GetEnvironment(a, error));
    if (a)
    {
      double r2[9], g2[9], b2[9];
      a->ProjectSH(3, r2, g2, b2);
      PGI_NEAR(r2[0], 2.0 * rb[0], 1e-9 * std::fabs(rb[0]));
    }
    fromFile->SetEnvironmentFileName("/nonexistent/sky.exr");
    PGI_CHECK(!fromFile->GetEnvironment(a, error));
    PGI_CHECK(error.find("/nonexistent/sky.exr") != std::string::npos);
  }

  // Missing file.
  reader->SetFileName("/nonexistent/sky.exr");
  PGI_CHECK(ReadFails(reader));

  // Not 2:1: an error for a lat-long map, fine as a plain image.
  auto plain = MakeImage(30, 20, 2);
  writer->SetFileName("/tmp/pgi-3x2.exr");
  writer->SetInputData(plain);
  PGI_CHECK(writer->Write());
  reader->SetFileName("/tmp/pgi-3x2.exr");
  PGI_CHECK(ReadFails(reader));
  reader->LatLongOff();
  PGI_CHECK(!ReadFails(reader));
  {
    // Read as written: 30 x 20, every texel bit-exact (first and last named).
    int dims[3];
    reader->GetOutput()->GetDimensions(dims);
    PGI_CHECK(dims[0] == 30 && dims[1] == 20 && dims[2] == 1);
    vtkDataArray* read = reader->GetOutput()->GetPointData()->GetScalars();
    vtkDataArray* written = plain->GetPointData()->GetScalars();
    PGI_CHECK(read && read->GetNumberOfTuples() == 30 * 20 && read->GetNumberOfComponents() == 3);
    if (read && read->GetNumberOfTuples() == 30 * 20)
    {
      PGI_NEAR(read->GetComponent(0, 0), written->GetComponent(0, 0), 0.0);
      PGI_NEAR(read->GetComponent(599, 2), written->GetComponent(599, 2), 0.0);
      double worst = 0.0;
      for (vtkIdType i = 0; i < 30 * 20; ++i)
      {
        for (int c = 0; c < 3; ++c)
        {
          worst =
            std::max(worst, std::fabs(read->GetComponent(i, c) - written->GetComponent(i, c)));
        }
      }
      PGI_CHECK(worst == 0.0);
    }
  }
  reader->LatLongOn();

  // No R, G, B channels (a luminance-only file).
  {
    Imf::Header header(8, 4);
    header.channels().insert("Y", Imf::Channel(Imf::FLOAT));
    std::vector<float> y(32, 1.0f);
    Imf::FrameBuffer frame;
    frame.insert("Y",
      Imf::Slice(Imf::FLOAT, reinterpret_cast<char*>(y.data()), sizeof(float), 8 * sizeof(float)));
    Imf::OutputFile file("/tmp/pgi-y.exr", header);
    file.setFrameBuffer(frame);
    file.writePixels(4);
  }
  reader->SetFileName("/tmp/pgi-y.exr");
  PGI_CHECK(ReadFails(reader));

  // NaN, Inf and negative texels: clamped, counted, said once per file at
  // INFO level (not a warning), however often the file is read.
  {
    auto bad = MakeImage(16, 8, 3);
    vtkDataArray* a = bad->GetPointData()->GetScalars();
    a->SetComponent(0, 0, std::numeric_limits<double>::quiet_NaN());
    a->SetComponent(5, 1, std::numeric_limits<double>::infinity());
    a->SetComponent(9, 2, -3.0);
    writer->SetFileName("/tmp/pgi-bad.exr");
    writer->SetInputData(bad);
    PGI_CHECK(writer->Write());
    vtkNew<vtkTest::ErrorObserver> observer;
    reader->AddObserver(vtkCommand::WarningEvent, observer);
    static int notices = 0;
    vtkLogger::AddCallback(
      "pgi-clamp-notices",
      [](void*, const vtkLogger::Message& message)
      {
        if (std::strstr(message.message, "pgi-bad.exr") && std::strstr(message.message, "clamped"))
        {
          ++notices;
        }
      },
      nullptr, vtkLogger::VERBOSITY_INFO);
    reader->SetFileName("/tmp/pgi-bad.exr");
    reader->Update();
    PGI_CHECK(reader->GetNumberOfClampedValues() == 3);
    reader->Modified();
    reader->Update(); // read again: counted again, not said again
    PGI_CHECK(reader->GetNumberOfClampedValues() == 3);
    vtkLogger::RemoveCallback("pgi-clamp-notices");
    std::printf("clamped texels: %d notice(s) for two reads, warning %s\n", notices,
      observer->GetWarning() ? "given" : "not given");
    PGI_CHECK(notices == 1);
    PGI_CHECK(!observer->GetWarning());
    vtkDataArray* r = reader->GetOutput()->GetPointData()->GetScalars();
    PGI_NEAR(r->GetComponent(0, 0), 0.0, 0.0);
    PGI_NEAR(r->GetComponent(5, 1), 65504.0, 0.0);
    PGI_NEAR(r->GetComponent(9, 2), 0.0, 0.0);
  }

  // The writer refuses what is not an RGB image.
  {
    vtkNew<vtkImageData> empty;
    vtkNew<vtkTest::ErrorObserver> observer;
    vtkNew<vtkPGIEXRWriter> w;
    w->AddObserver(vtkCommand::ErrorEvent, observer);
    w->GetExecutive()->AddObserver(vtkCommand::ErrorEvent, observer);
    w->SetFileName("/tmp/pgi-empty.exr");
    w->SetInputData(empty);
    PGI_CHECK(!w->Write());
  }
  return pgitest::Result();
}
