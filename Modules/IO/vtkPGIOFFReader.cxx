#include "vtkPGIOFFReader.h"

#include "vtkCellArray.h"
#include "vtkCellData.h"
#include "vtkFloatArray.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkNew.h"
#include "vtkObjectFactory.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkUnsignedCharArray.h"
#include "vtksys/SystemTools.hxx"

#include <cmath>
#include <fstream>
#include <new>
#include <sstream>
#include <vector>

vtkStandardNewMacro(vtkPGIOFFReader);

vtkPGIOFFReader::vtkPGIOFFReader()
{
  this->SetNumberOfInputPorts(0);
}

vtkPGIOFFReader::~vtkPGIOFFReader()
{
  this->SetFileName(nullptr);
}

void vtkPGIOFFReader::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "FileName: " << (this->FileName ? this->FileName : "(none)") << "\n";
  os << indent << "ReadFromInputString: " << this->ReadFromInputString << "\n";
  os << indent << "InputString: " << this->InputString.size() << " bytes\n";
}

void vtkPGIOFFReader::SetInputString(const std::string& text)
{
  if (text != this->InputString)
  {
    this->InputString = text;
    this->Modified();
  }
}

namespace
{
// Token stream over an OFF file: skips '#' comments and blank lines, and
// keeps line structure available for the optional per-element colours.
class OFFTokens
{
public:
  explicit OFFTokens(std::istream& in)
    : In(in)
  {
  }
  // Next non-empty, comment-stripped line.
  bool NextLine(std::string& line)
  {
    while (std::getline(this->In, line))
    {
      const std::size_t hash = line.find('#');
      if (hash != std::string::npos)
      {
        line.erase(hash);
      }
      if (line.find_first_not_of(" \t\r") != std::string::npos)
      {
        return true;
      }
    }
    return false;
  }

private:
  std::istream& In;
};

unsigned char ToByte(double v)
{
  // Colours come as 0..255 integers or 0..1 floats.
  if (v <= 1.0 && v >= 0.0 && std::floor(v) != v)
  {
    v *= 255.0;
  }
  return static_cast<unsigned char>(std::max(0.0, std::min(255.0, std::round(v))));
}
} // namespace

int vtkPGIOFFReader::RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector* out)
{
  vtkPolyData* output = vtkPolyData::GetData(out);
  std::ifstream file;
  std::istringstream text;
  std::istream* in = &text;
  unsigned long long bytes = 0;
  if (this->ReadFromInputString)
  {
    text.str(this->InputString);
    bytes = this->InputString.size();
  }
  else
  {
    if (!this->FileName || !*this->FileName)
    {
      vtkErrorMacro("No FileName set.");
      return 0;
    }
    file.open(this->FileName);
    if (!file)
    {
      vtkErrorMacro("Cannot open OFF file '" << this->FileName << "'.");
      return 0;
    }
    in = &file;
    bytes = vtksys::SystemTools::FileLength(this->FileName);
  }
  try
  {
    return this->ReadOFF(*in, bytes, output);
  }
  catch (const std::bad_alloc&)
  {
    vtkErrorMacro("'" << this->InputName() << "': out of memory for a mesh this size.");
    output->Initialize();
    return 0;
  }
}

std::string vtkPGIOFFReader::InputName() const
{
  return this->ReadFromInputString ? "(input string)" : (this->FileName ? this->FileName : "");
}

int vtkPGIOFFReader::ReadOFF(std::istream& in, unsigned long long bytes, vtkPolyData* output)
{
  const std::string name = this->InputName();
  OFFTokens tokens(in);
  std::string line;
  if (!tokens.NextLine(line))
  {
    vtkErrorMacro("'" << name << "' is empty.");
    return 0;
  }
  std::istringstream header(line);
  std::string word;
  header >> word;
  bool hasNormals = false, hasColors = false;
  if (word.size() >= 3 && word.compare(word.size() - 3, 3, "OFF") == 0)
  {
    const std::string prefix = word.substr(0, word.size() - 3);
    hasColors = prefix.find('C') != std::string::npos;
    hasNormals = prefix.find('N') != std::string::npos;
    std::string rest;
    std::getline(header, rest);
    if (rest.find_first_not_of(" \t\r") == std::string::npos && !tokens.NextLine(line))
    {
      vtkErrorMacro("'" << name << "' ends after its header.");
      return 0;
    }
    if (rest.find_first_not_of(" \t\r") != std::string::npos)
    {
      line = rest;
    }
  }
  long long nv = -1, nf = -1, ne = 0;
  {
    std::istringstream counts(line);
    counts >> nv >> nf >> ne;
    if (nv < 0 || nf < 0)
    {
      vtkErrorMacro("'" << name << "': bad counts line '" << line << "'.");
      return 0;
    }
  }
  // A vertex line takes at least 6 bytes ("0 0 0\n"), a face 4 ("1 0\n"):
  // counts the file cannot hold are refused before anything is allocated.
  if (static_cast<unsigned long long>(nv) > bytes / 6 ||
    static_cast<unsigned long long>(nf) > bytes / 4)
  {
    vtkErrorMacro("'" << name << "': the header claims " << nv << " vertices and " << nf
                      << " faces, more than a file of " << bytes << " bytes can hold.");
    return 0;
  }

  vtkNew<vtkPoints> points;
  points->SetDataTypeToFloat();
  points->SetNumberOfPoints(nv);
  vtkNew<vtkFloatArray> normals;
  normals->SetName("Normals");
  normals->SetNumberOfComponents(3);
  vtkNew<vtkUnsignedCharArray> colors;
  colors->SetName("Colors");
  colors->SetNumberOfComponents(3);
  if (hasNormals)
  {
    normals->SetNumberOfTuples(nv);
  }
  if (hasColors)
  {
    colors->SetNumberOfTuples(nv);
  }
  bool nonFinite = false;
  for (long long i = 0; i < nv; ++i)
  {
    if (!tokens.NextLine(line))
    {
      vtkErrorMacro("'" << name << "': truncated at vertex " << i << " of " << nv);
      return 0;
    }
    std::istringstream v(line);
    double p[3];
    v >> p[0] >> p[1] >> p[2];
    if (v.fail())
    {
      vtkErrorMacro("'" << name << "': vertex " << i << " is not three numbers: '" << line << "'");
      return 0;
    }
    nonFinite = nonFinite || !std::isfinite(p[0]) || !std::isfinite(p[1]) || !std::isfinite(p[2]);
    points->SetPoint(i, p);
    if (hasNormals)
    {
      double n[3] = { 0, 0, 0 };
      v >> n[0] >> n[1] >> n[2];
      normals->SetTuple(i, n);
    }
    if (hasColors)
    {
      double c[3] = { 255, 255, 255 };
      v >> c[0] >> c[1] >> c[2];
      const unsigned char rgb[3] = { ToByte(c[0]), ToByte(c[1]), ToByte(c[2]) };
      colors->SetTypedTuple(i, rgb);
    }
    if (i % 4096 == 0)
    {
      this->UpdateProgress(0.5 * i / std::max<long long>(1, nv));
    }
  }
  if (nonFinite)
  {
    vtkWarningMacro("'" << name << "' holds NaN or Inf coordinates.");
  }

  vtkNew<vtkCellArray> polys;
  vtkNew<vtkUnsignedCharArray> faceColors;
  faceColors->SetName("Colors");
  faceColors->SetNumberOfComponents(3);
  bool anyFaceColor = false;
  std::vector<vtkIdType> ids;
  for (long long f = 0; f < nf; ++f)
  {
    if (!tokens.NextLine(line))
    {
      vtkErrorMacro("'" << name << "': truncated at face " << f << " of " << nf);
      return 0;
    }
    std::istringstream fs(line);
    long long k = 0;
    fs >> k;
    if (fs.fail() || k < 1)
    {
      vtkErrorMacro("'" << name << "': face " << f << " has no vertex count.");
      return 0;
    }
    if (k > nv || static_cast<unsigned long long>(k) > bytes / 2)
    {
      vtkErrorMacro("'" << name << "': face " << f << " claims " << k
                        << " vertices, more than the mesh (" << nv << ") or the file holds.");
      return 0;
    }
    ids.resize(k);
    for (long long j = 0; j < k; ++j)
    {
      long long id = -1;
      fs >> id;
      if (fs.fail() || id < 0 || id >= nv)
      {
        vtkErrorMacro("'" << name << "': face " << f << " has a bad vertex index.");
        return 0;
      }
      ids[j] = static_cast<vtkIdType>(id);
    }
    polys->InsertNextCell(static_cast<vtkIdType>(k), ids.data());
    double c[3] = { 255, 255, 255 };
    fs >> c[0] >> c[1] >> c[2];
    const unsigned char rgb[3] = { ToByte(c[0]), ToByte(c[1]), ToByte(c[2]) };
    if (!fs.fail())
    {
      anyFaceColor = true;
    }
    const unsigned char white[3] = { 255, 255, 255 };
    faceColors->InsertNextTypedTuple(fs.fail() ? white : rgb);
    if (f % 4096 == 0)
    {
      this->UpdateProgress(0.5 + 0.5 * f / std::max<long long>(1, nf));
      if (this->GetAbortExecute())
      {
        break;
      }
    }
  }
  output->SetPoints(points);
  output->SetPolys(polys);
  if (hasNormals)
  {
    output->GetPointData()->SetNormals(normals);
  }
  if (hasColors)
  {
    output->GetPointData()->SetScalars(colors);
  }
  if (anyFaceColor)
  {
    output->GetCellData()->SetScalars(faceColors);
  }
  return 1;
}
