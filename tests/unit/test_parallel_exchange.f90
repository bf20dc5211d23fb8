!> The sparse exchanges of contact migration (parallel_exchange): between
!> known partners without a count exchange (par_exchange_partners), empty
!> messages to partners included, every rank receives exactly the elements
!> each partner sent it, by source rank in the order sent, the same as the
!> exchange with counts (par_exchange_counts + par_exchange); two exchanges
!> in a row keep their messages apart; the traffic counters give exactly the
!> messages, bytes and exchanges sent to other ranks. Run on 1 to 4 ranks.
program test_parallel_exchange
  use core_kinds, only: i8
  use parallel_env, only: par_init, par_finalize, par_rank, par_size, traffic_t
  use parallel_exchange, only: par_exchange, par_exchange_counts, par_exchange_partners
  use check, only: check_true, check_summary
  implicit none
  integer :: me, nranks, round

  call par_init()
  me = par_rank()
  nranks = par_size()
  do round = 1, 2
    call check_round(round)
  end do
  call check_summary()
  call par_finalize()

contains

  !> Ranks p and q are partners unless p + q = 1 (mod 3): symmetric, so the
  !> masks of the two directions agree; a rank is its own partner or not.
  pure logical function partners(p, q)
    integer, intent(in) :: p, q
    partners = mod(p + q, 3) /= 1
  end function partners

  !> Elements rank p sends to rank q in a round (0 for a partner: an empty
  !> message; none to a rank that is not a partner).
  pure integer function elements(p, q, round)
    integer, intent(in) :: p, q, round
    elements = 0
    if (partners(p, q)) elements = mod(3 * p + 5 * q + round, 4)
  end function elements

  !> Element e from rank p to rank q (the extremes of integer(i8) included).
  pure integer(i8) function element(p, q, e, round)
    integer, intent(in) :: p, q, e, round
    element = 1000000_i8 * p + 1000_i8 * q + 10_i8 * e + round
    if (e == 1 .and. mod(p, 2) == 0) element = -huge(1_i8)
    if (e == 2) element = huge(1_i8) - p
  end function element

  subroutine check_round(round)
    integer, intent(in) :: round
    integer :: send_counts(nranks), recv_counts(nranks), counted(nranks), q, e, n
    logical :: to(nranks)
    integer(i8), allocatable :: send(:), recv(:), recv_counted(:), expected(:)
    type(traffic_t) :: traffic
    integer(i8) :: bytes
    integer :: messages
    character(len=16) :: tag

    write(tag, '(a,i0,a,i0)') 'round ', round, ' rank ', me
    allocate(send(0), expected(0))
    bytes = 0
    messages = 0
    do q = 0, nranks - 1
      to(q + 1) = partners(me, q)
      send_counts(q + 1) = elements(me, q, round)
      send = [send, (element(me, q, e, round), e = 1, send_counts(q + 1))]
      expected = [expected, (element(q, me, e, round), e = 1, elements(q, me, round))]
      if (q /= me .and. to(q + 1)) then
        messages = messages + 1
        bytes = bytes + 8_i8 * send_counts(q + 1)
      end if
    end do
    ! A kept receive buffer, too small, as the contact's are at first.
    allocate(recv(1))
    call par_exchange_partners(send, send_counts, to, recv, recv_counts, to, traffic)
    n = sum(recv_counts)
    call check_true(trim(tag)//': counts from the message lengths', &
        all(recv_counts == [(elements(q, me, round), q = 0, nranks - 1)]))
    call check_true(trim(tag)//': elements by source rank, in the order sent', &
        n == size(expected) .and. size(recv) >= n)
    if (n == size(expected) .and. size(recv) >= n) &
        call check_true(trim(tag)//': element values', all(recv(:n) == expected))
    call par_exchange_counts(send_counts, counted)
    call par_exchange(send, send_counts, recv_counted, counted)
    call check_true(trim(tag)//': the same as the exchange with counts', &
        all(counted == recv_counts) .and. all(recv_counted(:n) == recv(:n)))
    if (nranks == 1) then
      call check_true(trim(tag)//': nothing counted on one rank', traffic%messages == 0 .and. &
          traffic%bytes == 0 .and. traffic%exchanges == 0 .and. traffic%collectives == 0)
    else
      call check_true(trim(tag)//': messages, bytes and exchanges counted', &
          traffic%messages == messages .and. traffic%bytes == bytes .and. &
          traffic%exchanges == merge(1, 0, count(to) - merge(1, 0, to(me + 1)) > 0) .and. &
          traffic%collectives == 0)
    end if
  end subroutine check_round

end program test_parallel_exchange
