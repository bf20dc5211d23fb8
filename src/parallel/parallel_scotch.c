/* The C side of parallel_partition: PT-Scotch's ParMETIS_V3_PartKway takes a
   C MPI communicator, which Fortran hands over as its integer handle. */
#include <stdint.h>
#include <stddef.h>
#include <mpi.h>

int ParMETIS_V3_PartKway(const int32_t *vtxdist, int32_t *xadj, int32_t *adjncy,
                         int32_t *vwgt, int32_t *adjwgt, const int32_t *wgtflag,
                         const int32_t *numflag, const int32_t *ncon, const int32_t *nparts,
                         const float *tpwgts, const float *ubvec, const int32_t *options,
                         int32_t *edgecut, int32_t *part, MPI_Comm *comm);

/* Partition the distributed graph (0-based, no weights) into nparts parts;
   returns ParMETIS's code (1 = METIS_OK). */
int impact3d_part_kway(const int32_t *vtxdist, int32_t *xadj, int32_t *adjncy,
                       const int32_t *nparts, const float *tpwgts, const float *ubvec,
                       int32_t *edgecut, int32_t *part, const MPI_Fint *fcomm)
{
  MPI_Comm comm = MPI_Comm_f2c(*fcomm);
  const int32_t wgtflag = 0, numflag = 0, ncon = 1;
  const int32_t options[3] = {0, 0, 0};
  return ParMETIS_V3_PartKway(vtxdist, xadj, adjncy, NULL, NULL, &wgtflag, &numflag, &ncon,
                              nparts, tpwgts, ubvec, options, edgecut, part, &comm);
}
