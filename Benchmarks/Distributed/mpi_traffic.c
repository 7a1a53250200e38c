/* Counts the bytes each MPI rank sends (LD_PRELOAD, through the PMPI
 * profiling interface) and prints them at MPI_Finalize:
 *   mpi-traffic: rank R sent B bytes in M messages (point-to-point P, collectives C)
 * Point-to-point: the message size. Collectives: the bytes this rank puts in
 * (an all-gather's send buffer counts once, however the library forwards it;
 * a broadcast counts at the root). Used by frame_traffic.sh to measure the
 * bytes of one frame as the difference of two runs. */
#include <mpi.h>
#include <stdio.h>

static double p2p, coll;
static long long messages;

static double Bytes(int count, MPI_Datatype type)
{
  int size = 0;
  PMPI_Type_size(type, &size);
  return (double)count * size;
}

int MPI_Send(const void* b, int n, MPI_Datatype t, int d, int tag, MPI_Comm c)
{
  p2p += Bytes(n, t);
  ++messages;
  return PMPI_Send(b, n, t, d, tag, c);
}

int MPI_Ssend(const void* b, int n, MPI_Datatype t, int d, int tag, MPI_Comm c)
{
  p2p += Bytes(n, t);
  ++messages;
  return PMPI_Ssend(b, n, t, d, tag, c);
}

int MPI_Isend(const void* b, int n, MPI_Datatype t, int d, int tag, MPI_Comm c, MPI_Request* r)
{
  p2p += Bytes(n, t);
  ++messages;
  return PMPI_Isend(b, n, t, d, tag, c, r);
}

int MPI_Sendrecv(const void* sb, int sn, MPI_Datatype st, int d, int stag, void* rb, int rn,
  MPI_Datatype rt, int s, int rtag, MPI_Comm c, MPI_Status* status)
{
  p2p += Bytes(sn, st);
  ++messages;
  return PMPI_Sendrecv(sb, sn, st, d, stag, rb, rn, rt, s, rtag, c, status);
}

int MPI_Bcast(void* b, int n, MPI_Datatype t, int root, MPI_Comm c)
{
  int rank = 0, size = 1;
  PMPI_Comm_rank(c, &rank);
  PMPI_Comm_size(c, &size);
  if (rank == root)
  {
    coll += Bytes(n, t) * (size - 1);
    ++messages;
  }
  return PMPI_Bcast(b, n, t, root, c);
}

int MPI_Allgather(
  const void* sb, int sn, MPI_Datatype st, void* rb, int rn, MPI_Datatype rt, MPI_Comm c)
{
  coll += Bytes(sn, st);
  ++messages;
  return PMPI_Allgather(sb, sn, st, rb, rn, rt, c);
}

int MPI_Allgatherv(const void* sb, int sn, MPI_Datatype st, void* rb, const int* rn,
  const int* displs, MPI_Datatype rt, MPI_Comm c)
{
  coll += Bytes(sn, st);
  ++messages;
  return PMPI_Allgatherv(sb, sn, st, rb, rn, displs, rt, c);
}

int MPI_Gather(
  const void* sb, int sn, MPI_Datatype st, void* rb, int rn, MPI_Datatype rt, int root, MPI_Comm c)
{
  coll += Bytes(sn, st);
  ++messages;
  return PMPI_Gather(sb, sn, st, rb, rn, rt, root, c);
}

int MPI_Gatherv(const void* sb, int sn, MPI_Datatype st, void* rb, const int* rn, const int* displs,
  MPI_Datatype rt, int root, MPI_Comm c)
{
  coll += Bytes(sn, st);
  ++messages;
  return PMPI_Gatherv(sb, sn, st, rb, rn, displs, rt, root, c);
}

int MPI_Allreduce(const void* sb, void* rb, int n, MPI_Datatype t, MPI_Op op, MPI_Comm c)
{
  coll += Bytes(n, t);
  ++messages;
  return PMPI_Allreduce(sb, rb, n, t, op, c);
}

int MPI_Reduce(const void* sb, void* rb, int n, MPI_Datatype t, MPI_Op op, int root, MPI_Comm c)
{
  coll += Bytes(n, t);
  ++messages;
  return PMPI_Reduce(sb, rb, n, t, op, root, c);
}

int MPI_Finalize(void)
{
  int rank = 0;
  PMPI_Comm_rank(MPI_COMM_WORLD, &rank);
  fprintf(stderr,
    "mpi-traffic: rank %d sent %.0f bytes in %lld messages (point-to-point %.0f, collectives "
    "%.0f)\n",
    rank, p2p + coll, messages, p2p, coll);
  return PMPI_Finalize();
}
