#include "pgiParallel.h"

#include "vtkAppendPolyData.h"
#include "vtkCellData.h"
#include "vtkCharArray.h"
#include "vtkCommunicator.h"
#include "vtkFieldData.h"
#include "vtkIdTypeArray.h"
#include "vtkIntArray.h"
#include "vtkMultiProcessController.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkPolyData.h"

#include <algorithm>
#include <chrono>
#include <sstream>

namespace proxygi
{
namespace parallel
{
namespace
{
using Clock = std::chrono::steady_clock;

double SecondsSince(Clock::time_point start)
{
  return std::chrono::duration<double>(Clock::now() - start).count();
}

// Lengths and offsets of a variable-length all-gather.
struct Layout
{
  std::vector<vtkIdType> Lengths, Offsets;
  vtkIdType Total = 0;
};

Layout LayoutOf(vtkMultiProcessController* c, vtkIdType length, Traffic* traffic)
{
  const int ranks = c->GetNumberOfProcesses();
  Layout layout;
  layout.Lengths.resize(ranks);
  layout.Offsets.resize(ranks);
  const long long mine = length;
  std::vector<long long> all(ranks);
  c->AllGather(&mine, all.data(), 1);
  for (int r = 0; r < ranks; ++r)
  {
    layout.Lengths[r] = static_cast<vtkIdType>(all[r]);
    layout.Offsets[r] = layout.Total;
    layout.Total += layout.Lengths[r];
  }
  if (traffic)
  {
    traffic->BytesSent += sizeof(long long) * static_cast<std::size_t>(ranks - 1);
    traffic->BytesReceived += sizeof(long long) * static_cast<std::size_t>(ranks - 1);
  }
  return layout;
}

// Every rank's bytes, in rank order.
std::vector<std::string> AllGatherBytes(
  vtkMultiProcessController* c, const std::string& mine, Traffic* traffic)
{
  const Layout layout = LayoutOf(c, static_cast<vtkIdType>(mine.size()), traffic);
  std::string all(static_cast<std::size_t>(layout.Total), '\0');
  // AllGatherV wants a writable receive buffer even for zero bytes.
  char dummy = 0;
  c->AllGatherV(mine.data(), layout.Total ? &all[0] : &dummy, static_cast<vtkIdType>(mine.size()),
    const_cast<vtkIdType*>(layout.Lengths.data()), const_cast<vtkIdType*>(layout.Offsets.data()));
  std::vector<std::string> parts(layout.Lengths.size());
  for (std::size_t r = 0; r < parts.size(); ++r)
  {
    parts[r] = all.substr(
      static_cast<std::size_t>(layout.Offsets[r]), static_cast<std::size_t>(layout.Lengths[r]));
  }
  if (traffic)
  {
    const std::size_t others = parts.size() - 1;
    traffic->BytesSent += mine.size() * others;
    traffic->BytesReceived += static_cast<std::size_t>(layout.Total) - mine.size();
  }
  return parts;
}
} // namespace

void Traffic::Add(const Traffic& other)
{
  this->BytesSent += other.BytesSent;
  this->BytesReceived += other.BytesReceived;
  this->Seconds += other.Seconds;
}

vtkMultiProcessController* Active(vtkMultiProcessController* controller)
{
  return controller && controller->GetNumberOfProcesses() > 1 ? controller : nullptr;
}

int Rank(vtkMultiProcessController* controller)
{
  return Active(controller) ? controller->GetLocalProcessId() : 0;
}

int Ranks(vtkMultiProcessController* controller)
{
  return Active(controller) ? controller->GetNumberOfProcesses() : 1;
}

bool AllOk(vtkMultiProcessController* controller, bool ok, const std::string& localError,
  std::string& error, Traffic* traffic)
{
  error.clear();
  vtkMultiProcessController* c = Active(controller);
  if (!c)
  {
    error = ok ? std::string() : localError;
    return ok;
  }
  const auto start = Clock::now();
  const int mine = ok ? 0 : 1;
  int failing = 0;
  c->AllReduce(&mine, &failing, 1, vtkCommunicator::SUM_OP);
  if (failing > 0)
  {
    // Only now do the reasons travel (the usual case moves one int).
    const std::vector<std::string> reasons =
      AllGatherBytes(c, ok ? std::string() : localError, traffic);
    std::ostringstream all;
    bool first = true;
    for (std::size_t r = 0; r < reasons.size(); ++r)
    {
      if (!reasons[r].empty())
      {
        all << (first ? "" : "; ") << "rank " << r << ": " << reasons[r];
        first = false;
      }
    }
    error = all.str();
    if (error.empty())
    {
      error = "a rank failed without saying why";
    }
  }
  if (traffic)
  {
    const std::size_t others = static_cast<std::size_t>(c->GetNumberOfProcesses() - 1);
    traffic->BytesSent += sizeof(int) * others;
    traffic->BytesReceived += sizeof(int) * others;
    traffic->Seconds += SecondsSince(start);
  }
  return failing == 0;
}

namespace
{
// Values reduced over the ranks in place (serial: the values themselves).
void ReduceEach(vtkMultiProcessController* controller, double* values, int count, int operation)
{
  vtkMultiProcessController* c = Active(controller);
  if (!c || count <= 0)
  {
    return;
  }
  std::vector<double> result(static_cast<std::size_t>(count));
  c->AllReduce(values, result.data(), count, operation);
  std::copy(result.begin(), result.end(), values);
}

double ReduceOne(vtkMultiProcessController* controller, double value, int operation)
{
  ReduceEach(controller, &value, 1, operation);
  return value;
}
} // namespace

void SumEach(vtkMultiProcessController* controller, double* values, int count)
{
  ReduceEach(controller, values, count, vtkCommunicator::SUM_OP);
}

void MaxEach(vtkMultiProcessController* controller, double* values, int count)
{
  ReduceEach(controller, values, count, vtkCommunicator::MAX_OP);
}

void GlobalBox(vtkMultiProcessController* controller, double lo[3], double hi[3])
{
  double extent[6] = { -lo[0], -lo[1], -lo[2], hi[0], hi[1], hi[2] };
  MaxEach(controller, extent, 6);
  for (int c = 0; c < 3; ++c)
  {
    lo[c] = -extent[c];
    hi[c] = extent[3 + c];
  }
}

bool AnyTrue(vtkMultiProcessController* controller, bool value)
{
  return ReduceOne(controller, value ? 1.0 : 0.0, vtkCommunicator::MAX_OP) > 0.0;
}

double Sum(vtkMultiProcessController* controller, double value)
{
  return ReduceOne(controller, value, vtkCommunicator::SUM_OP);
}

double Max(vtkMultiProcessController* controller, double value)
{
  return ReduceOne(controller, value, vtkCommunicator::MAX_OP);
}

std::vector<long long> AllGatherCounts(
  vtkMultiProcessController* controller, long long value, Traffic* traffic)
{
  vtkMultiProcessController* c = Active(controller);
  if (!c)
  {
    return { value };
  }
  std::vector<long long> all(static_cast<std::size_t>(c->GetNumberOfProcesses()));
  c->AllGather(&value, all.data(), 1);
  if (traffic)
  {
    traffic->BytesSent += sizeof(long long) * (all.size() - 1);
    traffic->BytesReceived += sizeof(long long) * (all.size() - 1);
  }
  return all;
}

vtkSmartPointer<vtkPolyData> AllGatherPolyData(
  vtkMultiProcessController* controller, vtkPolyData* local, Traffic* traffic)
{
  auto result = vtkSmartPointer<vtkPolyData>::New();
  vtkMultiProcessController* c = Active(controller);
  if (!c)
  {
    if (local)
    {
      result->ShallowCopy(local);
    }
    return result;
  }
  const auto start = Clock::now();
  // Field data stays local: only the geometry and point arrays travel.
  vtkNew<vtkPolyData> outgoing;
  if (local)
  {
    outgoing->ShallowCopy(local);
    outgoing->GetFieldData()->Initialize();
    outgoing->GetCellData()->Initialize();
  }
  std::string bytes;
  if (outgoing->GetNumberOfPoints() > 0)
  {
    vtkNew<vtkCharArray> buffer;
    vtkCommunicator::MarshalDataObject(outgoing, buffer);
    bytes.assign(buffer->GetPointer(0), static_cast<std::size_t>(buffer->GetNumberOfValues()));
  }
  const std::vector<std::string> parts = AllGatherBytes(c, bytes, traffic);
  vtkNew<vtkAppendPolyData> append;
  std::vector<vtkIdType> pointOffsets;
  vtkIdType points = 0;
  std::vector<vtkSmartPointer<vtkPolyData>> pieces;
  for (const std::string& part : parts)
  {
    if (part.empty())
    {
      continue;
    }
    vtkNew<vtkCharArray> buffer;
    buffer->SetArray(const_cast<char*>(part.data()), static_cast<vtkIdType>(part.size()), 1);
    auto piece = vtkSmartPointer<vtkPolyData>::New();
    vtkCommunicator::UnMarshalDataObject(buffer, piece);
    if (piece->GetNumberOfPoints() == 0)
    {
      continue;
    }
    pointOffsets.push_back(points);
    points += piece->GetNumberOfPoints();
    pieces.push_back(piece);
  }
  if (pieces.size() == 1)
  {
    result->ShallowCopy(pieces[0]);
  }
  else if (pieces.size() > 1)
  {
    for (auto& piece : pieces)
    {
      append->AddInputData(piece);
    }
    append->Update();
    result->ShallowCopy(append->GetOutput());
    // Hierarchy parents are indices into their own rank's set.
    auto* parent = vtkIdTypeArray::SafeDownCast(result->GetPointData()->GetArray("Parent"));
    if (parent)
    {
      for (std::size_t k = 0; k < pieces.size(); ++k)
      {
        const vtkIdType end =
          k + 1 < pieces.size() ? pointOffsets[k + 1] : result->GetNumberOfPoints();
        for (vtkIdType i = pointOffsets[k]; i < end; ++i)
        {
          const vtkIdType p = parent->GetValue(i);
          if (p >= 0)
          {
            parent->SetValue(i, p + pointOffsets[k]);
          }
        }
      }
    }
  }
  if (local)
  {
    result->GetFieldData()->ShallowCopy(local->GetFieldData());
  }
  if (traffic)
  {
    traffic->Seconds += SecondsSince(start);
  }
  return result;
}

const char* GlobalProxiesMarkName()
{
  return "ProxyGIGlobalProxies";
}

bool IsGlobal(vtkPolyData* proxies)
{
  return proxies && proxies->GetFieldData()->GetAbstractArray(GlobalProxiesMarkName()) != nullptr;
}

vtkSmartPointer<vtkPolyData> GatherProxies(
  vtkMultiProcessController* controller, vtkPolyData* local, std::string& error, Traffic* traffic)
{
  error.clear();
  vtkMultiProcessController* c = Active(controller);
  if (!c)
  {
    return local;
  }
  const auto start = Clock::now();
  const std::vector<long long> marked = AllGatherCounts(c, IsGlobal(local) ? 1 : 0, traffic);
  const auto globalRanks = std::count(marked.begin(), marked.end(), 1LL);
  if (globalRanks == static_cast<long long>(marked.size()))
  {
    if (traffic)
    {
      traffic->Seconds += SecondsSince(start);
    }
    return local;
  }
  if (globalRanks > 0)
  {
    error = "the ranks disagree on their proxies: " + std::to_string(globalRanks) + " of " +
      std::to_string(marked.size()) + " hold a gathered (global) set, the others a local one";
    return nullptr;
  }
  Traffic gather;
  vtkSmartPointer<vtkPolyData> global = AllGatherPolyData(c, local, &gather);
  vtkNew<vtkIntArray> mark;
  mark->SetName(GlobalProxiesMarkName());
  mark->InsertNextValue(c->GetNumberOfProcesses());
  global->GetFieldData()->AddArray(mark);
  if (traffic)
  {
    gather.Seconds = 0.0;
    traffic->Add(gather);
    traffic->Seconds += SecondsSince(start);
  }
  return global;
}
} // namespace parallel
} // namespace proxygi
