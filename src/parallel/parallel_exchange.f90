!> Personalised all-to-all exchange of variable-length records, for the
!> migration of contact data between mesh owners and RCB parts.
!>
!> The send buffer holds the records for rank 0, then rank 1, ... (counts in
!> elements per destination); the receive buffer comes back ordered by source
!> rank, each source's records in the order it sent them. Both orders are
!> fixed, so a caller that sorts by its own keys gets results independent of
!> the number of ranks.
!>
!> The exchange is sparse: one message per pair of ranks with something to
!> send (nonblocking point to point), so its cost follows the number of
!> partners (the RCB neighbours of a part), not the number of ranks as a
!> dense MPI_Alltoallv's may. Only the counts (par_exchange_counts) are an
!> all-to-all, of one integer per pair.
module parallel_exchange
  use mpi_f08
  use core_kinds, only: rk, i8
  use parallel_env, only: par_comm, par_size
  implicit none
  private
  public :: par_exchange, par_exchange_counts

  !> Message tag of the exchanges (one exchange is complete before the next).
  integer, parameter :: EXCHANGE_TAG = 7301

  !> recv = the records every rank sent to this one (by source rank).
  interface par_exchange
    module procedure exchange_real, exchange_i8
  end interface par_exchange

contains

  !> recv_counts(r + 1) = number of elements rank r will send here.
  subroutine par_exchange_counts(send_counts, recv_counts)
    integer, intent(in) :: send_counts(:) !< (nranks) elements for each destination
    integer, intent(out) :: recv_counts(:) !< (nranks)
    call MPI_Alltoall(send_counts, 1, MPI_INTEGER, recv_counts, 1, MPI_INTEGER, par_comm())
  end subroutine par_exchange_counts

  !> Displacements of a count vector (0-based, as MPI wants them).
  pure function displacements(counts) result(disp)
    integer, intent(in) :: counts(:)
    integer :: disp(size(counts))
    integer :: r
    disp(1) = 0
    do r = 2, size(counts)
      disp(r) = disp(r - 1) + counts(r - 1)
    end do
  end function displacements

  !> Exchange reals; recv is grown when smaller than the total received
  !> (kept otherwise, so a caller's buffer is reused from stage to stage).
  subroutine exchange_real(send, send_counts, recv, recv_counts)
    real(rk), intent(in) :: send(:)
    integer, intent(in) :: send_counts(:)
    real(rk), allocatable, intent(inout) :: recv(:)
    integer, intent(in) :: recv_counts(:) !< from par_exchange_counts
    type(MPI_Request), allocatable :: requests(:)
    integer :: sd(size(send_counts)), rd(size(recv_counts)), r, me, n
    if (allocated(recv)) then
      if (size(recv) < sum(recv_counts)) deallocate(recv)
    end if
    if (.not. allocated(recv)) allocate(recv(max(sum(recv_counts), 1)))
    sd = displacements(send_counts)
    rd = displacements(recv_counts)
    call MPI_Comm_rank(par_comm(), me)
    allocate(requests(2 * size(send_counts)))
    n = 0
    do r = 1, size(recv_counts)
      if (recv_counts(r) == 0 .or. r == me + 1) cycle
      n = n + 1
      call MPI_Irecv(recv(rd(r) + 1:rd(r) + recv_counts(r)), recv_counts(r), &
          MPI_DOUBLE_PRECISION, r - 1, EXCHANGE_TAG, par_comm(), requests(n))
    end do
    do r = 1, size(send_counts)
      if (send_counts(r) == 0 .or. r == me + 1) cycle
      n = n + 1
      call MPI_Isend(send(sd(r) + 1:sd(r) + send_counts(r)), send_counts(r), &
          MPI_DOUBLE_PRECISION, r - 1, EXCHANGE_TAG, par_comm(), requests(n))
    end do
    recv(rd(me + 1) + 1:rd(me + 1) + recv_counts(me + 1)) = &
        send(sd(me + 1) + 1:sd(me + 1) + send_counts(me + 1))
    call MPI_Waitall(n, requests(:n), MPI_STATUSES_IGNORE)
  end subroutine exchange_real

  !> Exchange 64-bit integers; recv grows as for reals.
  subroutine exchange_i8(send, send_counts, recv, recv_counts)
    integer(i8), intent(in) :: send(:)
    integer, intent(in) :: send_counts(:)
    integer(i8), allocatable, intent(inout) :: recv(:)
    integer, intent(in) :: recv_counts(:)
    type(MPI_Request), allocatable :: requests(:)
    integer :: sd(size(send_counts)), rd(size(recv_counts)), r, me, n
    if (allocated(recv)) then
      if (size(recv) < sum(recv_counts)) deallocate(recv)
    end if
    if (.not. allocated(recv)) allocate(recv(max(sum(recv_counts), 1)))
    sd = displacements(send_counts)
    rd = displacements(recv_counts)
    call MPI_Comm_rank(par_comm(), me)
    allocate(requests(2 * size(send_counts)))
    n = 0
    do r = 1, size(recv_counts)
      if (recv_counts(r) == 0 .or. r == me + 1) cycle
      n = n + 1
      call MPI_Irecv(recv(rd(r) + 1:rd(r) + recv_counts(r)), recv_counts(r), &
          MPI_INTEGER8, r - 1, EXCHANGE_TAG, par_comm(), requests(n))
    end do
    do r = 1, size(send_counts)
      if (send_counts(r) == 0 .or. r == me + 1) cycle
      n = n + 1
      call MPI_Isend(send(sd(r) + 1:sd(r) + send_counts(r)), send_counts(r), &
          MPI_INTEGER8, r - 1, EXCHANGE_TAG, par_comm(), requests(n))
    end do
    recv(rd(me + 1) + 1:rd(me + 1) + recv_counts(me + 1)) = &
        send(sd(me + 1) + 1:sd(me + 1) + send_counts(me + 1))
    call MPI_Waitall(n, requests(:n), MPI_STATUSES_IGNORE)
  end subroutine exchange_i8

end module parallel_exchange
