!> Set-up communication without global arrays: records (columns of 64-bit
!> integers; reals travel bit for bit through transfer) routed to the ranks
!> named per record in one all-to-all, the block layout of global ids, and a
!> global sum taken in the order of global keys whatever the rank count.
module parallel_route
  use mpi_f08
  use core_kinds, only: rk, i8
  use core_sort, only: sort_order
  use parallel_env, only: par_comm, par_size, par_rank
  implicit none
  private
  public :: par_route, par_route_free, par_min_array, par_block_range, par_block_owner, par_ordered_sum, par_max_i8, par_min_i8, &
      par_exscan_i8, par_allgather_text, par_route_rounds

contains

  !> First global id and count of rank r's block of nglobal items (contiguous
  !> ranges, sizes differing by at most one).
  pure subroutine par_block_range(nglobal, nrank, r, first, n)
    integer(i8), intent(in) :: nglobal
    integer, intent(in) :: nrank, r
    integer(i8), intent(out) :: first
    integer, intent(out) :: n
    integer(i8) :: lo, hi
    lo = (nglobal * r) / nrank
    hi = (nglobal * (r + 1)) / nrank
    first = lo + 1
    n = int(hi - lo)
  end subroutine par_block_range

  !> Rank of the block that holds global id g (1 <= g <= nglobal).
  pure integer function par_block_owner(nglobal, nrank, g) result(r)
    integer(i8), intent(in) :: nglobal, g
    integer, intent(in) :: nrank
    integer(i8) :: first
    integer :: n
    r = int(((g - 1) * nrank) / nglobal)
    do
      call par_block_range(nglobal, nrank, r, first, n)
      if (g < first) then
        r = r - 1
      else if (g >= first + n) then
        r = r + 1
      else
        exit
      end if
    end do
  end function par_block_owner

  !> recv = every record (column of send) whose dest is this rank, grouped by
  !> source rank in increasing order, each group in the sender's column order;
  !> source(j) is the rank recv(:, j) came from. With free, send is
  !> deallocated once packed (the caller's records need not outlive the call).
  subroutine par_route(send, dest, recv, source, sent_bytes)
    integer(i8), intent(in) :: send(:, :) !< (ncomp, n) records
    integer, intent(in) :: dest(:) !< (n) destination rank of each record
    integer(i8), allocatable, intent(out) :: recv(:, :) !< (ncomp, nrecv)
    integer, allocatable, intent(out), optional :: source(:)
    integer(i8), intent(inout), optional :: sent_bytes !< increased by the bytes sent to others
    integer(i8), allocatable :: sbuf(:, :)
    integer, allocatable :: scount(:), sdispl(:)
    call pack_records(send, dest, sbuf, scount, sdispl)
    call exchange(sbuf, scount, sdispl, size(send, 1), recv, source, sent_bytes)
  end subroutine par_route

  !> par_route that deallocates send as soon as it is packed, so that the
  !> records are held twice at most (packed and received), never three times.
  subroutine par_route_free(send, dest, recv, source, sent_bytes)
    integer(i8), allocatable, intent(inout) :: send(:, :) !< (ncomp, n) records; freed
    integer, intent(in) :: dest(:) !< (n) destination rank of each record
    integer(i8), allocatable, intent(out) :: recv(:, :) !< (ncomp, nrecv)
    integer, allocatable, intent(out), optional :: source(:)
    integer(i8), intent(inout), optional :: sent_bytes
    integer(i8), allocatable :: sbuf(:, :)
    integer, allocatable :: scount(:), sdispl(:)
    integer :: ncomp
    ncomp = size(send, 1)
    call pack_records(send, dest, sbuf, scount, sdispl)
    deallocate(send)
    call exchange(sbuf, scount, sdispl, ncomp, recv, source, sent_bytes)
  end subroutine par_route_free

  !> The records grouped by destination rank (in order within each group).
  subroutine pack_records(send, dest, sbuf, scount, sdispl)
    integer(i8), intent(in) :: send(:, :)
    integer, intent(in) :: dest(:)
    integer(i8), allocatable, intent(out) :: sbuf(:, :)
    integer, allocatable, intent(out) :: scount(:), sdispl(:)
    integer :: nrank, i, r
    integer, allocatable :: fill(:)
    nrank = par_size()
    allocate(scount(0:nrank - 1), sdispl(0:nrank - 1), fill(0:nrank - 1))
    scount = 0
    do i = 1, size(dest)
      scount(dest(i)) = scount(dest(i)) + 1
    end do
    sdispl(0) = 0
    do r = 1, nrank - 1
      sdispl(r) = sdispl(r - 1) + scount(r - 1)
    end do
    allocate(sbuf(size(send, 1), max(1, size(dest))))
    fill = sdispl
    do i = 1, size(dest)
      fill(dest(i)) = fill(dest(i)) + 1
      sbuf(:, fill(dest(i))) = send(:, i)
    end do
  end subroutine pack_records

  !> The all-to-all of packed records.
  subroutine exchange(sbuf, scount, sdispl, ncomp, recv, source, sent_bytes)
    integer(i8), intent(in) :: sbuf(:, :)
    integer, intent(in) :: scount(0:), sdispl(0:)
    integer, intent(in) :: ncomp
    integer(i8), allocatable, intent(out) :: recv(:, :)
    integer, allocatable, intent(out), optional :: source(:)
    integer(i8), intent(inout), optional :: sent_bytes
    integer :: nrank, r, nrecv
    integer, allocatable :: rcount(:), rdispl(:)
    integer(i8) :: dummy(1, 1)
    nrank = par_size()
    allocate(rcount(0:nrank - 1), rdispl(0:nrank - 1))
    call MPI_Alltoall(scount, 1, MPI_INTEGER, rcount, 1, MPI_INTEGER, par_comm())
    rdispl(0) = 0
    do r = 1, nrank - 1
      rdispl(r) = rdispl(r - 1) + rcount(r - 1)
    end do
    nrecv = sum(rcount)
    allocate(recv(ncomp, nrecv))
    if (ncomp > 0) then
      if (nrecv > 0) then
        call MPI_Alltoallv(sbuf, ncomp * scount, ncomp * sdispl, MPI_INTEGER8, recv, &
            ncomp * rcount, ncomp * rdispl, MPI_INTEGER8, par_comm())
      else
        call MPI_Alltoallv(sbuf, ncomp * scount, ncomp * sdispl, MPI_INTEGER8, dummy, &
            ncomp * rcount, ncomp * rdispl, MPI_INTEGER8, par_comm())
      end if
    end if
    if (present(sent_bytes)) sent_bytes = sent_bytes + 8_i8 * ncomp * &
        (sum(scount) - scount(par_rank()))
    if (present(source)) then
      allocate(source(nrecv))
      do r = 0, nrank - 1
        source(rdispl(r) + 1:rdispl(r) + rcount(r)) = r
      end do
    end if
  end subroutine exchange

  !> Largest x over the ranks.
  function par_max_i8(x) result(s)
    integer(i8), intent(in) :: x
    integer(i8) :: s
    call MPI_Allreduce(x, s, 1, MPI_INTEGER8, MPI_MAX, par_comm())
  end function par_max_i8

  !> In-place minimum of each element over the ranks (one reduction).
  subroutine par_min_array(x)
    real(rk), intent(inout) :: x(:)
    real(rk) :: s(size(x))
    call MPI_Allreduce(x, s, size(x), MPI_DOUBLE_PRECISION, MPI_MIN, par_comm())
    x = s
  end subroutine par_min_array

  !> Smallest x over the ranks.
  function par_min_i8(x) result(s)
    integer(i8), intent(in) :: x
    integer(i8) :: s
    call MPI_Allreduce(x, s, 1, MPI_INTEGER8, MPI_MIN, par_comm())
  end function par_min_i8

  !> Sum of x over the ranks before this one (0 on rank 0).
  function par_exscan_i8(x) result(s)
    integer(i8), intent(in) :: x
    integer(i8) :: s
    call MPI_Exscan(x, s, 1, MPI_INTEGER8, MPI_SUM, par_comm())
    if (par_rank() == 0) s = 0
  end function par_exscan_i8

  !> total = the sum of value(:, i) over every rank's items, added one by one
  !> from zero in increasing key order (keys distinct over all ranks), so it
  !> is bitwise the sum a single rank would form, on any rank count. The
  !> items go to the block owners of their keys, then a running sum passes
  !> from rank to rank: O(items / ranks) work and O(ranks) latency (set-up).
  subroutine par_ordered_sum(key, value, total)
    integer(i8), intent(in) :: key(:) !< (n) global keys >= 1
    real(rk), intent(in) :: value(:, :) !< (ncomp, n)
    real(rk), intent(out) :: total(:) !< (ncomp), the same on every rank
    integer :: nrank, me, ncomp, n, i, j
    integer(i8) :: kmax
    integer(i8), allocatable :: send(:, :), recv(:, :)
    integer, allocatable :: dest(:), order(:)
    real(rk) :: v(size(total))
    nrank = par_size()
    me = par_rank()
    ncomp = size(value, 1)
    n = size(key)
    kmax = par_max_i8(maxval([0_i8, key]))
    total = 0.0_rk
    if (kmax == 0) return
    allocate(send(1 + ncomp, n), dest(n))
    do i = 1, n
      send(1, i) = key(i)
      do j = 1, ncomp
        send(1 + j, i) = transfer(value(j, i), 1_i8)
      end do
      dest(i) = par_block_owner(kmax, nrank, key(i))
    end do
    call par_route(send, dest, recv)
    call sort_order(recv(1, :), order)
    if (me > 0) call MPI_Recv(total, ncomp, MPI_DOUBLE_PRECISION, me - 1, 71, par_comm(), &
        MPI_STATUS_IGNORE)
    do i = 1, size(order)
      do j = 1, ncomp
        v(j) = transfer(recv(1 + j, order(i)), 1.0_rk)
      end do
      total = total + v
    end do
    if (me < nrank - 1) call MPI_Send(total, ncomp, MPI_DOUBLE_PRECISION, me + 1, 71, &
        par_comm())
    call MPI_Bcast(total, ncomp, MPI_DOUBLE_PRECISION, nrank - 1, par_comm())
  end subroutine par_ordered_sum

  !> all = every rank's lines, rank after rank (set-up messages found by
  !> ranges of a file, merged so that every rank holds the same list).
  subroutine par_allgather_text(lines, all)
    character(len=*), intent(in) :: lines(:)
    character(len=len(lines)), allocatable, intent(out) :: all(:)
    integer :: nrank, r
    integer :: n(1)
    integer, allocatable :: counts(:), displ(:)
    character(len=len(lines)) :: dummy(1)
    nrank = par_size()
    allocate(counts(0:nrank - 1), displ(0:nrank - 1))
    n(1) = size(lines)
    call MPI_Allgather(n, 1, MPI_INTEGER, counts, 1, MPI_INTEGER, par_comm())
    displ(0) = 0
    do r = 1, nrank - 1
      displ(r) = displ(r - 1) + counts(r - 1)
    end do
    allocate(all(sum(counts)))
    if (size(all) == 0) return
    if (size(lines) > 0) then
      call MPI_Allgatherv(lines, len(lines) * size(lines), MPI_CHARACTER, all, &
          len(lines) * counts, len(lines) * displ, MPI_CHARACTER, par_comm())
    else
      call MPI_Allgatherv(dummy, 0, MPI_CHARACTER, all, len(lines) * counts, &
          len(lines) * displ, MPI_CHARACTER, par_comm())
    end if
  end subroutine par_allgather_text

  !> All-to-all rounds needed when every rank sends its n records in chunks
  !> of at most chunk (the largest rank's count of chunks; at least 1).
  function par_route_rounds(n, chunk) result(rounds)
    integer(i8), intent(in) :: n
    integer, intent(in) :: chunk
    integer :: rounds
    integer(i8) :: mine, most
    mine = max(1_i8, (n + chunk - 1) / chunk)
    call MPI_Allreduce(mine, most, 1, MPI_INTEGER8, MPI_MAX, par_comm())
    rounds = int(most)
  end function par_route_rounds

end module parallel_route
