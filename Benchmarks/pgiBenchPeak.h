// The float multiply-add peak the kernels are measured against: the widest
// FMA this CPU has (Highway's dispatch), twelve independent chains.
#ifndef pgiBenchPeak_h
#define pgiBenchPeak_h

namespace proxygi
{
namespace bench
{
/// Runs `iterations` rounds of twelve independent vector FMAs; returns the
/// flops done (2 per lane per FMA) and stores a result the compiler keeps.
double FmaPeak(long iterations, float* sink);
/// Floats per vector of the target FmaPeak dispatches to.
int FmaPeakLanes();
} // namespace bench
} // namespace proxygi

#endif
