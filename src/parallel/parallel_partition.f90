!> Zone partitions of the dual graph (zones joined across faces): in
!> parallel by PT-Scotch (its native distributed-graph interface, in a
!> deterministic context; its ParMETIS-compatible interface is neither
!> reproducible nor safe without MPI thread support), each rank
!> giving its contiguous range of zones and their neighbours; or by serial
!> METIS on rank 0 (the whole graph on one rank: an opt-in for small meshes).
module parallel_partition
  use, intrinsic :: iso_c_binding, only: c_int32_t, c_double, c_int, c_ptr, c_null_ptr
  use mpi_f08, only: MPI_Comm
  use core_kinds, only: ik, i8
  use parallel_env, only: par_rank, par_size, par_abort, par_comm, par_allgather
  use parallel_route, only: par_route
  implicit none
  private
  public :: partition_graph

  integer, parameter :: METIS_NOPTIONS = 40
  integer(c_int32_t), parameter :: METIS_OK = 1
  !> Largest part over the mean, minus one, asked of PT-Scotch.
  real(c_double), parameter :: IMBALANCE = 0.02_c_double

  interface
    function metis_set_default_options(options) bind(c, name='METIS_SetDefaultOptions') &
        result(code)
      import :: c_int32_t
      integer(c_int32_t), intent(inout) :: options(*)
      integer(c_int32_t) :: code
    end function metis_set_default_options

    function metis_part_graph_kway(nvtxs, ncon, xadj, adjncy, vwgt, vsize, adjwgt, nparts, &
        tpwgts, ubvec, options, objval, part) bind(c, name='METIS_PartGraphKway') result(code)
      import :: c_int32_t, c_ptr
      integer(c_int32_t), intent(in) :: nvtxs, ncon, nparts
      integer(c_int32_t), intent(in) :: xadj(*), adjncy(*)
      type(c_ptr), value :: vwgt, vsize, adjwgt, tpwgts, ubvec
      integer(c_int32_t), intent(in) :: options(*)
      integer(c_int32_t), intent(out) :: objval
      integer(c_int32_t), intent(out) :: part(*)
      integer(c_int32_t) :: code
    end function metis_part_graph_kway

    ! parallel_scotch.c: PT-Scotch's distributed graph partition, with the
    ! communicator's Fortran handle.
    function impact3d_scotch_part(vtxdist, xadj, adjncy, nparts, imbalance, part, comm) &
        bind(c, name='impact3d_scotch_part') result(code)
      import :: c_int32_t, c_double, c_int
      integer(c_int32_t), intent(in) :: vtxdist(*), xadj(*), adjncy(*)
      integer(c_int32_t), intent(in) :: nparts
      real(c_double), intent(in) :: imbalance
      integer(c_int32_t), intent(out) :: part(*)
      integer(c_int32_t), intent(in) :: comm
      integer(c_int) :: code
    end function impact3d_scotch_part
  end interface

contains

  !> The serial METIS partition of the same graph: every rank's zones and
  !> neighbours go to rank 0, which partitions the whole graph (memory there
  !> grows with the whole mesh: an opt-in for small meshes), and the parts
  !> come back in each rank's order.
  subroutine partition_graph_metis(nbr, part)
    integer(i8), intent(in) :: nbr(:, :) !< (6, n) face neighbours' global ids, 0 = none
    integer(ik), intent(out) :: part(:) !< (n) owner rank of each zone
    integer(i8), allocatable :: send(:, :), recv(:, :), back(:, :)
    integer(c_int32_t), allocatable :: xadj(:), adjncy(:), cpart(:)
    integer(c_int32_t) :: options(METIS_NOPTIONS), objval, code, nv
    integer, allocatable :: dest(:), source(:)
    integer :: n, i, r, k
    n = size(nbr, 2)
    allocate(send(6, n), dest(n))
    send = nbr
    dest = 0
    call par_route(send, dest, recv, source)
    nv = int(size(recv, 2), c_int32_t)
    allocate(xadj(nv + 1), adjncy(max(1, count(recv > 0))), cpart(max(1_c_int32_t, nv)))
    ! Records arrive by source rank, each rank's range in order: global order.
    xadj(1) = 0
    k = 0
    do i = 1, nv
      do r = 1, 6
        if (recv(r, i) <= 0) cycle
        k = k + 1
        adjncy(k) = int(recv(r, i) - 1, c_int32_t)
      end do
      xadj(i + 1) = int(k, c_int32_t)
    end do
    if (nv > 0) then
      code = metis_set_default_options(options)
      code = metis_part_graph_kway(nv, 1_c_int32_t, xadj, adjncy, c_null_ptr, c_null_ptr, &
          c_null_ptr, int(par_size(), c_int32_t), c_null_ptr, c_null_ptr, options, objval, cpart)
      if (code /= METIS_OK) call par_abort('partition: METIS_PartGraphKway failed', 3)
    end if
    deallocate(send)
    allocate(send(1, nv))
    send(1, :) = int(cpart(:nv), i8)
    call par_route(send, source, back)
    part = int(back(1, :), ik)
  end subroutine partition_graph_metis

  !> part(i) in 0..nranks-1 for each of this rank's zones (a contiguous
  !> range of global ids, the ranges in rank order), from its neighbours'
  !> global ids (0 = none) in parallel by PT-Scotch. With fewer zones than
  !> ranks anywhere, the ranges themselves are the parts.
  subroutine partition_graph(nbr, part, method)
    integer(i8), intent(in) :: nbr(:, :) !< (6, n) face neighbours' global ids, 0 = none
    integer(ik), intent(out) :: part(:) !< (n) owner rank of each zone
    character(len=*), intent(in) :: method !< 'scotch' (parallel) or 'metis' (rank 0)
    integer(c_int32_t), allocatable :: vtxdist(:), xadj(:), adjncy(:), cpart(:)
    integer(ik), allocatable :: counts(:, :)
    integer(c_int) :: code
    integer :: nrank, n, i, k, r
    type(MPI_Comm) :: comm
    nrank = par_size()
    n = size(nbr, 2)
    if (nrank == 1) then
      part = 0
      return
    end if
    if (method == 'metis') then
      call partition_graph_metis(nbr, part)
      return
    end if
    allocate(counts(1, nrank))
    call par_allgather([int(n, ik)], counts)
    if (any(counts(1, :) == 0)) then
      ! Too few zones for a graph partition on every rank: keep the ranges.
      part = int(par_rank(), ik)
      return
    end if
    allocate(vtxdist(nrank + 1))
    vtxdist(1) = 0
    do r = 1, nrank
      vtxdist(r + 1) = vtxdist(r) + int(counts(1, r), c_int32_t)
    end do
    allocate(xadj(n + 1), adjncy(max(1, count(nbr > 0))), cpart(max(1, n)))
    xadj(1) = 0
    k = 0
    do i = 1, n
      do r = 1, 6
        if (nbr(r, i) <= 0) cycle
        k = k + 1
        adjncy(k) = int(nbr(r, i) - 1, c_int32_t)
      end do
      xadj(i + 1) = int(k, c_int32_t)
    end do
    comm = par_comm()
    code = impact3d_scotch_part(vtxdist, xadj, adjncy, int(nrank, c_int32_t), IMBALANCE, cpart, &
        int(comm%MPI_VAL, c_int32_t))
    if (code /= 0) call par_abort('partition: PT-Scotch failed to partition the zones', 3)
    part = int(cpart(:n), ik)
  end subroutine partition_graph

end module parallel_partition
