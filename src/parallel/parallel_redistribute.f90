!> Moves item data between the owner layout (each rank its owned items, any
!> order) and the block layout (rank r holds global ids first..last, a contiguous
!> range), so that dumps are written and read as one hyperslab per rank.
module parallel_redistribute
  use mpi_f08
  use core_kinds, only: rk, ik, i8
  use parallel_env, only: par_comm, par_size, par_rank, par_abort
  use parallel_route, only: par_block_range, par_block_owner
  implicit none
  private

  !> Plan of one owner <-> block mapping.
  type, public :: redistribute_t
    integer(i8) :: nglobal = 0 !< items in all
    integer(i8) :: first = 1 !< first global id of this rank's block
    integer :: nblock = 0 !< items in this rank's block
    integer :: nlocal = 0 !< owned items
    integer, allocatable :: send_count(:), send_displ(:) !< per rank, owner -> block
    integer, allocatable :: recv_count(:), recv_displ(:)
    integer, allocatable :: send_order(:) !< local item for each send slot
    integer, allocatable :: recv_slot(:) !< block position (1-based) for each receive slot
  contains
    procedure :: init => redistribute_init
    procedure :: free => redistribute_free
    procedure :: to_block => redistribute_to_block
    procedure :: from_block => redistribute_from_block
    procedure :: to_block_int => redistribute_to_block_int
  end type redistribute_t

contains

  !> Plan for the owned items with global ids gid(1:nlocal) (1-based ids).
  subroutine redistribute_init(this, gid, nglobal)
    class(redistribute_t), intent(inout) :: this
    integer(i8), intent(in) :: gid(:) !< global ids of the owned items
    integer(i8), intent(in) :: nglobal !< total number of items
    integer :: nrank, r, i, nrecv
    integer, allocatable :: dest(:), fill(:)
    integer(i8), allocatable :: send_gid(:), recv_gid(:)
    type(MPI_Comm) :: comm

    call this%free()
    comm = par_comm()
    nrank = par_size()
    this%nglobal = nglobal
    this%nlocal = size(gid)
    call par_block_range(nglobal, nrank, par_rank(), this%first, this%nblock)
    allocate(this%send_count(0:nrank - 1), this%send_displ(0:nrank - 1))
    allocate(this%recv_count(0:nrank - 1), this%recv_displ(0:nrank - 1))
    allocate(dest(this%nlocal))
    this%send_count = 0
    do i = 1, this%nlocal
      dest(i) = par_block_owner(nglobal, nrank, gid(i))
      this%send_count(dest(i)) = this%send_count(dest(i)) + 1
    end do
    call MPI_Alltoall(this%send_count, 1, MPI_INTEGER, this%recv_count, 1, MPI_INTEGER, comm)
    this%send_displ(0) = 0
    this%recv_displ(0) = 0
    do r = 1, nrank - 1
      this%send_displ(r) = this%send_displ(r - 1) + this%send_count(r - 1)
      this%recv_displ(r) = this%recv_displ(r - 1) + this%recv_count(r - 1)
    end do
    allocate(this%send_order(max(1, this%nlocal)), send_gid(max(1, this%nlocal)))
    allocate(fill(0:nrank - 1))
    fill = this%send_displ
    do i = 1, this%nlocal
      r = dest(i)
      fill(r) = fill(r) + 1
      this%send_order(fill(r)) = i
      send_gid(fill(r)) = gid(i)
    end do
    nrecv = sum(this%recv_count)
    if (nrecv /= this%nblock) call par_abort('redistribute: owned items do not cover the ids', 2)
    allocate(recv_gid(max(1, nrecv)), this%recv_slot(max(1, nrecv)))
    call MPI_Alltoallv(send_gid, this%send_count, this%send_displ, MPI_INTEGER8, recv_gid, &
        this%recv_count, this%recv_displ, MPI_INTEGER8, comm)
    do i = 1, nrecv
      this%recv_slot(i) = int(recv_gid(i) - this%first) + 1
    end do
  end subroutine redistribute_init

  !> Release the plan.
  subroutine redistribute_free(this)
    class(redistribute_t), intent(inout) :: this
    if (allocated(this%send_count)) deallocate(this%send_count)
    if (allocated(this%send_displ)) deallocate(this%send_displ)
    if (allocated(this%recv_count)) deallocate(this%recv_count)
    if (allocated(this%recv_displ)) deallocate(this%recv_displ)
    if (allocated(this%send_order)) deallocate(this%send_order)
    if (allocated(this%recv_slot)) deallocate(this%recv_slot)
    this%nlocal = 0
    this%nblock = 0
  end subroutine redistribute_free

  !> block(:, j) = local(:, i) for the item whose global id is first + j - 1.
  subroutine redistribute_to_block(this, local, block)
    class(redistribute_t), intent(in) :: this
    real(rk), intent(in) :: local(:, :) !< (ncomp, nlocal)
    real(rk), intent(out) :: block(:, :) !< (ncomp, nblock)
    real(rk), allocatable :: sbuf(:, :), rbuf(:, :)
    integer :: ncomp, i
    ncomp = size(local, 1)
    allocate(sbuf(ncomp, max(1, this%nlocal)), rbuf(ncomp, max(1, this%nblock)))
    do i = 1, this%nlocal
      sbuf(:, i) = local(:, this%send_order(i))
    end do
    call MPI_Alltoallv(sbuf, ncomp * this%send_count, ncomp * this%send_displ, &
        MPI_DOUBLE_PRECISION, rbuf, ncomp * this%recv_count, ncomp * this%recv_displ, &
        MPI_DOUBLE_PRECISION, par_comm())
    do i = 1, this%nblock
      block(:, this%recv_slot(i)) = rbuf(:, i)
    end do
  end subroutine redistribute_to_block

  !> Integer variant of to_block.
  subroutine redistribute_to_block_int(this, local, block)
    class(redistribute_t), intent(in) :: this
    integer(ik), intent(in) :: local(:, :) !< (ncomp, nlocal)
    integer(ik), intent(out) :: block(:, :) !< (ncomp, nblock)
    integer(ik), allocatable :: sbuf(:, :), rbuf(:, :)
    integer :: ncomp, i
    ncomp = size(local, 1)
    allocate(sbuf(ncomp, max(1, this%nlocal)), rbuf(ncomp, max(1, this%nblock)))
    do i = 1, this%nlocal
      sbuf(:, i) = local(:, this%send_order(i))
    end do
    call MPI_Alltoallv(sbuf, ncomp * this%send_count, ncomp * this%send_displ, &
        MPI_INTEGER, rbuf, ncomp * this%recv_count, ncomp * this%recv_displ, &
        MPI_INTEGER, par_comm())
    do i = 1, this%nblock
      block(:, this%recv_slot(i)) = rbuf(:, i)
    end do
  end subroutine redistribute_to_block_int

  !> The reverse of to_block: local(:, i) from the block holding its global id.
  subroutine redistribute_from_block(this, block, local)
    class(redistribute_t), intent(in) :: this
    real(rk), intent(in) :: block(:, :) !< (ncomp, nblock)
    real(rk), intent(inout) :: local(:, :) !< (ncomp, nlocal)
    real(rk), allocatable :: sbuf(:, :), rbuf(:, :)
    integer :: ncomp, i
    ncomp = size(block, 1)
    allocate(sbuf(ncomp, max(1, this%nblock)), rbuf(ncomp, max(1, this%nlocal)))
    do i = 1, this%nblock
      sbuf(:, i) = block(:, this%recv_slot(i))
    end do
    call MPI_Alltoallv(sbuf, ncomp * this%recv_count, ncomp * this%recv_displ, &
        MPI_DOUBLE_PRECISION, rbuf, ncomp * this%send_count, ncomp * this%send_displ, &
        MPI_DOUBLE_PRECISION, par_comm())
    do i = 1, this%nlocal
      local(:, this%send_order(i)) = rbuf(:, i)
    end do
  end subroutine redistribute_from_block

end module parallel_redistribute
