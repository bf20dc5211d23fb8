!> Personalised all-to-all exchange of variable-length records, for the
!> migration of contact data between mesh owners and RCB parts.
!>
!> The send buffer holds the records for rank 0, then rank 1, ... (counts in
!> elements per destination); the receive buffer comes back ordered by source
!> rank, each source's records in the order it sent them. Both orders are
!> fixed, so a caller that sorts by its own keys gets results independent of
!> the number of ranks.
!>
!> The exchanges are sparse: one message per pair of ranks with something to
!> send (nonblocking point to point), so their cost follows the number of
!> partners (the RCB neighbours of a part), not the number of ranks as a
!> dense MPI_Alltoallv's may. par_exchange needs the receive counts, from
!> par_exchange_counts (an all-to-all of one integer per pair) or from a
!> plan made once; par_exchange_partners needs only the partners (who sends
!> to whom, known from a plan): each partner gets one message, empty when
!> there is nothing to send, and its length tells the receiver the count, so
!> the all-to-all of counts goes.
!>
!> Each takes an optional traffic_t (parallel_env) that counts what this
!> rank sent, the exchanges and collectives it took part in, and the time
!> it spent in them (the caller's run report).
module parallel_exchange
  use mpi_f08
  use core_kinds, only: rk, i8
  use parallel_env, only: par_comm, par_size, par_rank, par_abort, traffic_t, traffic_count
  implicit none
  private
  public :: par_exchange, par_exchange_counts, par_exchange_partners

  !> Message tags: par_exchange, par_exchange_partners (each exchange is
  !> complete before the next; pairs of ranks keep their message order).
  integer, parameter :: EXCHANGE_TAG = 7301, PARTNER_TAG = 7302

  !> recv = the records every rank sent to this one (by source rank).
  interface par_exchange
    module procedure exchange_real, exchange_i8
  end interface par_exchange

contains

  !> recv_counts(r + 1) = number of elements rank r will send here.
  subroutine par_exchange_counts(send_counts, recv_counts, traffic)
    integer, intent(in) :: send_counts(:) !< (nranks) elements for each destination
    integer, intent(out) :: recv_counts(:) !< (nranks)
    type(traffic_t), intent(inout), optional :: traffic
    real(rk) :: t0
    t0 = MPI_Wtime()
    call MPI_Alltoall(send_counts, 1, MPI_INTEGER, recv_counts, 1, MPI_INTEGER, par_comm())
    if (present(traffic)) call traffic_count(traffic, t0)
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

  !> Messages, bytes and the exchange itself into traffic (after the wait).
  subroutine count_exchange(traffic, send_counts, recv_counts, bytes_per, t0)
    type(traffic_t), intent(inout) :: traffic
    integer, intent(in) :: send_counts(:), recv_counts(:)
    integer, intent(in) :: bytes_per !< bytes per element
    real(rk), intent(in) :: t0 !< MPI_Wtime before the wait
    integer :: me
    if (par_size() == 1) return
    me = par_rank() + 1
    traffic%bytes = traffic%bytes + int(bytes_per, i8) * &
        int(sum(send_counts) - send_counts(me), i8)
    traffic%messages = traffic%messages + count(send_counts > 0) - &
        merge(1, 0, send_counts(me) > 0)
    if (any(send_counts(:me - 1) > 0) .or. any(send_counts(me + 1:) > 0) .or. &
        any(recv_counts(:me - 1) > 0) .or. any(recv_counts(me + 1:) > 0)) &
        traffic%exchanges = traffic%exchanges + 1
    traffic%wait_seconds = traffic%wait_seconds + (MPI_Wtime() - t0)
  end subroutine count_exchange

  !> Exchange reals; recv is grown when smaller than the total received
  !> (kept otherwise, so a caller's buffer is reused from stage to stage).
  subroutine exchange_real(send, send_counts, recv, recv_counts, traffic)
    real(rk), intent(in) :: send(:)
    integer, intent(in) :: send_counts(:)
    real(rk), allocatable, intent(inout) :: recv(:)
    integer, intent(in) :: recv_counts(:) !< from par_exchange_counts
    type(traffic_t), intent(inout), optional :: traffic
    type(MPI_Request), allocatable :: requests(:)
    integer :: sd(size(send_counts)), rd(size(recv_counts)), r, me, n
    real(rk) :: t0
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
    t0 = MPI_Wtime()
    call MPI_Waitall(n, requests(:n), MPI_STATUSES_IGNORE)
    if (present(traffic)) call count_exchange(traffic, send_counts, recv_counts, 8, t0)
  end subroutine exchange_real

  !> Exchange 64-bit integers; recv grows as for reals.
  subroutine exchange_i8(send, send_counts, recv, recv_counts, traffic)
    integer(i8), intent(in) :: send(:)
    integer, intent(in) :: send_counts(:)
    integer(i8), allocatable, intent(inout) :: recv(:)
    integer, intent(in) :: recv_counts(:)
    type(traffic_t), intent(inout), optional :: traffic
    type(MPI_Request), allocatable :: requests(:)
    integer :: sd(size(send_counts)), rd(size(recv_counts)), r, me, n
    real(rk) :: t0
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
    t0 = MPI_Wtime()
    call MPI_Waitall(n, requests(:n), MPI_STATUSES_IGNORE)
    if (present(traffic)) call count_exchange(traffic, send_counts, recv_counts, 8, t0)
  end subroutine exchange_i8

  !> Exchange 64-bit integers between known partners without exchanging
  !> counts first: every rank r with to(r + 1) gets one message (empty when
  !> send_counts(r + 1) = 0), and one message comes from every rank r with
  !> from(r + 1); the two masks must agree over the ranks (to on rank p for
  !> q exactly when from on rank q for p), as the two directions of one
  !> migration plan do. recv comes back by source rank as for par_exchange,
  !> recv_counts(r + 1) the elements from rank r; recv grows as there.
  !> Sending to a rank that is not a partner is an error (it would wait for
  !> a message nobody sends).
  subroutine par_exchange_partners(send, send_counts, to, recv, recv_counts, from, traffic)
    integer(i8), intent(in) :: send(:)
    integer, intent(in) :: send_counts(:) !< (nranks) elements for each destination
    logical, intent(in) :: to(:) !< (nranks) a message goes to this rank
    integer(i8), allocatable, intent(inout) :: recv(:)
    integer, intent(out) :: recv_counts(:) !< (nranks)
    logical, intent(in) :: from(:) !< (nranks) a message comes from this rank
    type(traffic_t), intent(inout), optional :: traffic
    type(MPI_Request), allocatable :: requests(:)
    type(MPI_Message), allocatable :: messages(:)
    type(MPI_Status) :: status
    integer :: sd(size(send_counts)), rd(size(send_counts)), r, me, n
    real(rk) :: t0
    me = par_rank() + 1
    sd = displacements(send_counts)
    allocate(requests(size(send_counts)), messages(size(send_counts)))
    n = 0
    do r = 1, size(send_counts)
      if (r == me) cycle
      if (.not. to(r)) then
        if (send_counts(r) > 0) call par_abort('par_exchange_partners: records for a rank '// &
            'that is not a partner', 3)
        cycle
      end if
      n = n + 1
      call MPI_Isend(send(sd(r) + 1:sd(r) + send_counts(r)), send_counts(r), MPI_INTEGER8, &
          r - 1, PARTNER_TAG, par_comm(), requests(n))
    end do
    t0 = MPI_Wtime()
    ! The lengths first (each partner's message, in rank order), then the data.
    recv_counts = 0
    recv_counts(me) = send_counts(me)
    do r = 1, size(send_counts)
      if (r == me .or. .not. from(r)) cycle
      call MPI_Mprobe(r - 1, PARTNER_TAG, par_comm(), messages(r), status)
      call MPI_Get_count(status, MPI_INTEGER8, recv_counts(r))
    end do
    if (allocated(recv)) then
      if (size(recv) < sum(recv_counts)) deallocate(recv)
    end if
    if (.not. allocated(recv)) allocate(recv(max(2 * sum(recv_counts), 64)))
    rd = displacements(recv_counts)
    recv(rd(me) + 1:rd(me) + recv_counts(me)) = send(sd(me) + 1:sd(me) + send_counts(me))
    do r = 1, size(send_counts)
      if (r == me .or. .not. from(r)) cycle
      call MPI_Mrecv(recv(rd(r) + 1:rd(r) + recv_counts(r)), recv_counts(r), MPI_INTEGER8, &
          messages(r), MPI_STATUS_IGNORE)
    end do
    call MPI_Waitall(n, requests(:n), MPI_STATUSES_IGNORE)
    if (present(traffic)) then
      if (par_size() > 1) then
        traffic%bytes = traffic%bytes + 8_i8 * int(sum(send_counts) - send_counts(me), i8)
        traffic%messages = traffic%messages + n
        if (n > 0 .or. count(from) - merge(1, 0, from(me)) > 0) &
            traffic%exchanges = traffic%exchanges + 1
        traffic%wait_seconds = traffic%wait_seconds + (MPI_Wtime() - t0)
      end if
    end if
  end subroutine par_exchange_partners

end module parallel_exchange
