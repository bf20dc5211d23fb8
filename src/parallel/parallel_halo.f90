!> Halo refresh: copies of owned items (nodes or zones) sent to the ranks that
!> hold them as ghosts. Built once from global ids and owner ranks.
module parallel_halo
  use mpi_f08
  use core_kinds, only: rk, i8
  use parallel_env, only: par_comm, par_size, par_rank, par_abort
  implicit none
  private

  !> Communication pattern of one kind of item.
  type, public :: halo_t
    integer :: nneighbour = 0 !< ranks we exchange with
    integer, allocatable :: neighbour(:) !< their ranks
    integer, allocatable :: send_start(:), send_index(:) !< CSR of owned local indices per neighbour
    integer, allocatable :: recv_start(:), recv_index(:) !< CSR of ghost local indices per neighbour
    real(rk), allocatable :: send_buffer(:), recv_buffer(:) !< work space, sized for 3 components
    type(MPI_Request), allocatable :: requests(:)
    integer(i8) :: bytes_sent = 0 !< bytes sent by the exchanges so far
    integer(i8) :: messages_sent = 0 !< messages sent by the exchanges so far
  contains
    procedure :: init => halo_init
    procedure :: free => halo_free
    procedure :: halo_exchange, halo_exchange_scalar
    generic :: exchange => halo_exchange, halo_exchange_scalar
  end type halo_t

contains

  !> Build the pattern. Items 1..nowned are owned (sorted by global id); the
  !> others are ghosts whose owner rank is given.
  subroutine halo_init(this, gid, owner, nowned)
    class(halo_t), intent(inout) :: this
    integer(i8), intent(in) :: gid(:) !< global id of every local item
    integer, intent(in) :: owner(:) !< owner rank of every local item
    integer, intent(in) :: nowned !< items 1..nowned are owned by this rank
    type(MPI_Comm) :: comm
    integer :: nrank, me, i, r, k, n, pos
    integer, allocatable :: need_count(:), give_count(:), need_displ(:), give_displ(:), order(:)
    integer(i8), allocatable :: need_gid(:), give_gid(:)
    integer, allocatable :: fill(:)

    call this%free()
    comm = par_comm()
    nrank = par_size()
    me = par_rank()
    n = size(gid)
    allocate(need_count(0:nrank - 1), give_count(0:nrank - 1))
    allocate(need_displ(0:nrank - 1), give_displ(0:nrank - 1))
    need_count = 0
    do i = nowned + 1, n
      need_count(owner(i)) = need_count(owner(i)) + 1
    end do
    if (need_count(me) /= 0) call par_abort('halo: a ghost is owned by its own rank', 2)
    call MPI_Alltoall(need_count, 1, MPI_INTEGER, give_count, 1, MPI_INTEGER, comm)
    need_displ(0) = 0
    give_displ(0) = 0
    do r = 1, nrank - 1
      need_displ(r) = need_displ(r - 1) + need_count(r - 1)
      give_displ(r) = give_displ(r - 1) + give_count(r - 1)
    end do
    ! Ghosts grouped by owner, in local order (ghosts are sorted by global id).
    allocate(need_gid(max(1, sum(need_count))), order(max(1, sum(need_count))))
    allocate(fill(0:nrank - 1))
    fill = need_displ
    do i = nowned + 1, n
      r = owner(i)
      fill(r) = fill(r) + 1
      need_gid(fill(r)) = gid(i)
      order(fill(r)) = i
    end do
    allocate(give_gid(max(1, sum(give_count))))
    call MPI_Alltoallv(need_gid, need_count, need_displ, MPI_INTEGER8, give_gid, give_count, &
        give_displ, MPI_INTEGER8, comm)

    this%nneighbour = count(need_count > 0 .or. give_count > 0)
    allocate(this%neighbour(this%nneighbour))
    allocate(this%send_start(this%nneighbour + 1), this%recv_start(this%nneighbour + 1))
    allocate(this%send_index(max(1, sum(give_count))), this%recv_index(max(1, sum(need_count))))
    k = 0
    this%send_start(1) = 1
    this%recv_start(1) = 1
    do r = 0, nrank - 1
      if (need_count(r) == 0 .and. give_count(r) == 0) cycle
      k = k + 1
      this%neighbour(k) = r
      do i = 1, give_count(r)
        pos = find_owned(gid, nowned, give_gid(give_displ(r) + i))
        if (pos == 0) call par_abort('halo: requested item not owned here', 2)
        this%send_index(this%send_start(k) + i - 1) = pos
      end do
      this%send_start(k + 1) = this%send_start(k) + give_count(r)
      do i = 1, need_count(r)
        this%recv_index(this%recv_start(k) + i - 1) = order(need_displ(r) + i)
      end do
      this%recv_start(k + 1) = this%recv_start(k) + need_count(r)
    end do
    ! One spare slot: an empty message still names its (first) buffer element.
    allocate(this%send_buffer(3 * (sum(give_count) + 1)))
    allocate(this%recv_buffer(3 * (sum(need_count) + 1)))
    allocate(this%requests(2 * this%nneighbour))
  end subroutine halo_init

  !> Binary search of a global id among the owned (sorted) items; 0 if absent.
  pure integer function find_owned(gid, nowned, key) result(pos)
    integer(i8), intent(in) :: gid(:)
    integer, intent(in) :: nowned
    integer(i8), intent(in) :: key
    integer :: lo, hi, mid
    lo = 1
    hi = nowned
    pos = 0
    do while (lo <= hi)
      mid = (lo + hi) / 2
      if (gid(mid) == key) then
        pos = mid
        return
      else if (gid(mid) < key) then
        lo = mid + 1
      else
        hi = mid - 1
      end if
    end do
  end function find_owned

  !> Release everything.
  subroutine halo_free(this)
    class(halo_t), intent(inout) :: this
    this%nneighbour = 0
    if (allocated(this%neighbour)) deallocate(this%neighbour)
    if (allocated(this%send_start)) deallocate(this%send_start)
    if (allocated(this%send_index)) deallocate(this%send_index)
    if (allocated(this%recv_start)) deallocate(this%recv_start)
    if (allocated(this%recv_index)) deallocate(this%recv_index)
    if (allocated(this%send_buffer)) deallocate(this%send_buffer)
    if (allocated(this%recv_buffer)) deallocate(this%recv_buffer)
    if (allocated(this%requests)) deallocate(this%requests)
  end subroutine halo_free

  !> Overwrite the ghost copies of field(1:ncomp, :) with the owners' values
  !> (buffers grow on first use with more than 3 components).
  subroutine halo_exchange(this, field)
    class(halo_t), intent(inout) :: this
    real(rk), intent(inout) :: field(:, :) !< (ncomp, nlocal)
    call exchange_core(this, size(field, 1), size(field, 2), field)
  end subroutine halo_exchange

  !> The same for a field with one value per item.
  subroutine halo_exchange_scalar(this, field)
    class(halo_t), intent(inout) :: this
    real(rk), intent(inout) :: field(:) !< (nlocal)
    call exchange_core(this, 1, size(field), field)
  end subroutine halo_exchange_scalar

  subroutine exchange_core(this, ncomp, nitem, field)
    class(halo_t), intent(inout) :: this
    integer, intent(in) :: ncomp, nitem
    real(rk), intent(inout) :: field(ncomp, nitem)
    integer :: k, i, c, first, count_k, tag
    type(MPI_Comm) :: comm

    if (this%nneighbour == 0) return
    comm = par_comm()
    if (ncomp * this%send_start(this%nneighbour + 1) > size(this%send_buffer)) then
      deallocate(this%send_buffer)
      allocate(this%send_buffer(ncomp * this%send_start(this%nneighbour + 1)))
    end if
    if (ncomp * this%recv_start(this%nneighbour + 1) > size(this%recv_buffer)) then
      deallocate(this%recv_buffer)
      allocate(this%recv_buffer(ncomp * this%recv_start(this%nneighbour + 1)))
    end if
    tag = 71
    do k = 1, this%nneighbour
      first = this%recv_start(k)
      count_k = this%recv_start(k + 1) - first
      call MPI_Irecv(this%recv_buffer(ncomp * (first - 1) + 1), ncomp * count_k, &
          MPI_DOUBLE_PRECISION, this%neighbour(k), tag, comm, this%requests(k))
    end do
    do k = 1, this%nneighbour
      first = this%send_start(k)
      count_k = this%send_start(k + 1) - first
      do i = first, first + count_k - 1
        do c = 1, ncomp
          this%send_buffer(ncomp * (i - 1) + c) = field(c, this%send_index(i))
        end do
      end do
      this%bytes_sent = this%bytes_sent + 8_i8 * ncomp * count_k
      this%messages_sent = this%messages_sent + 1
      call MPI_Isend(this%send_buffer(ncomp * (first - 1) + 1), ncomp * count_k, &
          MPI_DOUBLE_PRECISION, this%neighbour(k), tag, comm, &
          this%requests(this%nneighbour + k))
    end do
    call MPI_Waitall(2 * this%nneighbour, this%requests, MPI_STATUSES_IGNORE)
    do i = 1, this%recv_start(this%nneighbour + 1) - 1
      do c = 1, ncomp
        field(c, this%recv_index(i)) = this%recv_buffer(ncomp * (i - 1) + c)
      end do
    end do
  end subroutine exchange_core

end module parallel_halo
