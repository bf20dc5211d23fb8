/* The C side of parallel_partition: PT-Scotch's distributed graph
   partitioning, called with the communicator's Fortran handle. */
#include <stdint.h>
#include <stdio.h>
#include <mpi.h>
#include <ptscotch.h>

/* Partition the distributed graph (0-based CSR of this rank's vertices,
   vtxdist[r] the first vertex of rank r) into nparts parts of at most
   (1 + imbalance) times the mean. Scotch runs in a context with its
   deterministic option (one thread, fixed random seed), so the same graph on
   the same ranks gives the same partition every time. Returns 0 on success. */
int impact3d_scotch_part(const int32_t *vtxdist, int32_t *xadj, int32_t *adjncy,
                         const int32_t *nparts, const double *imbalance, int32_t *part,
                         const MPI_Fint *fcomm)
{
  MPI_Comm comm = MPI_Comm_f2c(*fcomm);
  SCOTCH_Dgraph graph, bound;
  SCOTCH_Context context;
  SCOTCH_Strat strat;
  int rank, code;
  SCOTCH_Num nvert, nedge;

  MPI_Comm_rank(comm, &rank);
  nvert = vtxdist[rank + 1] - vtxdist[rank];
  nedge = xadj[nvert];
  if (SCOTCH_dgraphInit(&graph, comm) != 0) return 1;
  code = SCOTCH_dgraphBuild(&graph, 0, nvert, nvert, xadj, xadj + 1, NULL, NULL, nedge, nedge,
                            adjncy, NULL, NULL);
  if (code == 0) code = SCOTCH_stratInit(&strat);
  if (code == 0) code = SCOTCH_stratDgraphMapBuild(&strat, SCOTCH_STRATQUALITY, *nparts,
                                                   *nparts, *imbalance);
  if (code == 0) code = SCOTCH_contextInit(&context);
  if (code == 0) code = SCOTCH_contextOptionSetNum(&context, SCOTCH_OPTIONNUMDETERMINISTIC, 1);
  if (code == 0) code = SCOTCH_contextOptionSetNum(&context, SCOTCH_OPTIONNUMRANDOMFIXEDSEED, 1);
  if (code == 0) code = SCOTCH_dgraphInit(&bound, comm);
  if (code == 0) code = SCOTCH_contextBindDgraph(&context, &graph, &bound);
  if (code == 0) code = SCOTCH_dgraphPart(&bound, *nparts, &strat, part);
  SCOTCH_dgraphExit(&bound);
  SCOTCH_contextExit(&context);
  SCOTCH_stratExit(&strat);
  SCOTCH_dgraphExit(&graph);
  return code;
}
