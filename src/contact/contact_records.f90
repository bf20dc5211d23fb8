!> Records of contact contributions travelling from the RCB parts to the
!> mesh owners of the nodes, and their sum in a fixed order.
!>
!> A record is (contact index of the node, interface, key) and nv values; a
!> part writes its records in (interface, key) order; after the exchange the
!> owner has every record of its nodes sorted by (owned index, interface,
!> key), the order of a one-rank run, so sums over them are bitwise
!> independent of the number of ranks. Buffers are kept from stage to stage
!> (take moves them in and out of the caller's long-lived holder).
module contact_records
  use core_kinds, only: rk, i8
  use parallel_env, only: par_size, traffic_t
  use parallel_exchange, only: par_exchange_partners
  implicit none
  private
  public :: take, add_record, send_records, sum_records

  !> Contributions travelling from the parts to the mesh owners: ids
  !> (contact index, interface, key) and nv values each.
  type, public :: records_t
    integer :: n = 0
    integer :: nv = 3
    integer(i8), allocatable :: id(:, :) !< (3, capacity)
    real(rk), allocatable :: val(:, :) !< (nv, capacity)
    ! Buffers of the exchange, kept from stage to stage. A message holds
    ! the three ids of its records, then their values bit for bit (one
    ! transfer per message).
    integer(i8), allocatable :: isend(:), irecv(:)
    real(rk), allocatable :: rsend(:), rrecv(:)
    integer, allocatable :: node(:) !< (capacity) owned index of a received record
    integer, allocatable :: start(:), place(:) !< (nown + 1) buckets of the owned nodes
  end type records_t

contains

  !> Move a record buffer (its storage) from one holder to another, emptied.
  subroutine take(from, to, nv)
    type(records_t), intent(inout) :: from, to
    integer, intent(in) :: nv !< values per record
    to%n = 0
    to%nv = nv
    if (allocated(from%id)) call move_alloc(from%id, to%id)
    if (allocated(from%val)) call move_alloc(from%val, to%val)
    if (allocated(from%isend)) call move_alloc(from%isend, to%isend)
    if (allocated(from%irecv)) call move_alloc(from%irecv, to%irecv)
    if (allocated(from%rsend)) call move_alloc(from%rsend, to%rsend)
    if (allocated(from%rrecv)) call move_alloc(from%rrecv, to%rrecv)
    if (allocated(from%node)) call move_alloc(from%node, to%node)
    if (allocated(from%start)) call move_alloc(from%start, to%start)
    if (allocated(from%place)) call move_alloc(from%place, to%place)
    from%n = 0
  end subroutine take

  !> Append one record.
  subroutine add_record(r, node, k, key, val)
    type(records_t), intent(inout) :: r
    integer, intent(in) :: node, k !< node of the part's local set, interface
    integer(i8), intent(in) :: key
    real(rk), intent(in) :: val(:)
    integer(i8), allocatable :: grown_id(:, :)
    real(rk), allocatable :: grown_val(:, :)
    if (.not. allocated(r%id)) allocate(r%id(3, 64), r%val(r%nv, 64))
    if (r%n == size(r%id, 2)) then
      allocate(grown_id(3, 2 * r%n), grown_val(r%nv, 2 * r%n))
      grown_id(:, :r%n) = r%id(:, :r%n)
      grown_val(:, :r%n) = r%val(:, :r%n)
      call move_alloc(grown_id, r%id)
      call move_alloc(grown_val, r%val)
    end if
    r%n = r%n + 1
    r%id(:, r%n) = [int(node, i8), int(k, i8), key]
    r%val(:, r%n) = val
  end subroutine add_record

  !> Send every record to the mesh owner of its node; on return r holds the
  !> records received, sorted by (owned index, interface, key), with id(1, :)
  !> replaced by the owned index. Each part sends its records in (interface,
  !> key) order, so a node's records arrive as one ascending run per part:
  !> a stable bucket sort by node and an insertion sort of each (short,
  !> nearly sorted) bucket put them in order in linear time. One message per
  !> partner of the migration plan, ids and values together (values bit for
  !> bit), its length the count: no exchange of counts.
  subroutine send_records(r, owner, owner_pos, send_own, send_count, nown, to, from, traffic)
    type(records_t), intent(inout) :: r
    integer, intent(in) :: owner(:) !< (ncn) mesh-owner rank of each node of the local set
    !> (ncn) its place among the nodes its owner sends this part (the
    !> migration plan's order, from 1)
    integer, intent(in) :: owner_pos(:)
    !> owned index of each node this rank sends each part, by part (the plan's)
    integer, intent(in) :: send_own(:)
    integer, intent(in) :: send_count(:) !< (nranks) nodes this rank sends each part
    integer, intent(in) :: nown !< owned contact nodes of this rank
    !> (nranks) the owners of this part's local set, which get a message
    logical, intent(in) :: to(:)
    !> (nranks) the parts holding owned nodes of this rank, which send one
    logical, intent(in) :: from(:)
    type(traffic_t), intent(inout) :: traffic
    integer, allocatable :: count(:), got(:), fill(:), plan_start(:), dest(:)
    integer(i8) :: id(3)
    real(rk) :: val(r%nv)
    integer :: j, o, nranks, nr, d, nv, i, e, w, at, n, source
    nranks = par_size()
    nv = r%nv
    w = 3 + nv
    allocate(count(nranks), got(nranks), fill(nranks))
    ! A record names its node by its place in the owner's plan for this
    ! part: the owner finds the owned index there.
    allocate(dest(r%n))
    count = 0
    do j = 1, r%n
      dest(j) = owner(r%id(1, j)) + 1
      count(dest(j)) = count(dest(j)) + 1
      r%id(1, j) = int(owner_pos(r%id(1, j)), i8)
    end do
    fill(1) = 0
    do o = 2, nranks
      fill(o) = fill(o - 1) + count(o - 1)
    end do
    if (nranks == 1) then
      ! One rank: the records stay here, in the order they were made (what
      ! the message would carry), with no packing.
      call reserve_i8(r%irecv, 3 * r%n)
      call reserve_real(r%rrecv, nv * r%n)
      do j = 1, r%n
        r%irecv(3 * j - 2:3 * j) = r%id(:, j)
        r%rrecv(nv * (j - 1) + 1:nv * j) = r%val(:, j)
      end do
      got(1) = r%n
    else
      ! Ids and values by destination, then each destination's message: its
      ! ids, then its values.
      call reserve_i8(r%irecv, 3 * r%n)
      call reserve_real(r%rsend, nv * r%n)
      do j = 1, r%n
        o = dest(j)
        fill(o) = fill(o) + 1
        d = fill(o)
        r%irecv(3 * d - 2:3 * d) = r%id(:, j)
        r%rsend(nv * (d - 1) + 1:nv * d) = r%val(:, j)
      end do
      call reserve_i8(r%isend, w * r%n)
      at = 0
      do o = 1, nranks
        n = count(o)
        d = fill(o) - n
        r%isend(at + 1:at + 3 * n) = r%irecv(3 * d + 1:3 * (d + n))
        if (n > 0) r%isend(at + 3 * n + 1:at + w * n) = transfer(r%rsend(nv * d + 1:nv * (d + n)), &
            1_i8, nv * n)
        at = at + w * n
      end do
      call par_exchange_partners(r%isend, w * count, to, r%irecv, got, from, traffic)
      got = got / w
      ! The values of each source's message apart, in the same order.
      call reserve_real(r%rrecv, nv * sum(got))
      at = 0
      d = 0
      do o = 1, nranks
        n = got(o)
        if (n > 0) r%rrecv(nv * d + 1:nv * (d + n)) = transfer(r%irecv(at + 3 * n + 1:at + w * n), &
            1.0_rk, nv * n)
        r%irecv(3 * d + 1:3 * (d + n)) = r%irecv(at + 1:at + 3 * n)
        at = at + w * n
        d = d + n
      end do
    end if
    nr = sum(got)
    r%n = nr
    if (.not. allocated(r%id)) allocate(r%id(3, 64), r%val(nv, 64))
    if (size(r%id, 2) < nr) then
      deallocate(r%id, r%val)
      allocate(r%id(3, 2 * nr), r%val(nv, 2 * nr))
    end if
    ! Bucket sort by owned node (stable). The owned nodes change with a
    ! surface refresh (erosion): the buckets follow.
    if (allocated(r%start)) then
      if (size(r%start) /= nown + 1) deallocate(r%start)
    end if
    if (allocated(r%place)) then
      if (size(r%place) /= nown + 1) deallocate(r%place)
    end if
    if (.not. allocated(r%start)) allocate(r%start(nown + 1))
    if (.not. allocated(r%place)) allocate(r%place(nown + 1))
    if (allocated(r%node)) then
      if (size(r%node) < nr) deallocate(r%node)
    end if
    if (.not. allocated(r%node)) allocate(r%node(max(2 * nr, 64)))
    ! Each source's records in turn: the owned index from the plan.
    allocate(plan_start(nranks))
    plan_start(1) = 0
    do o = 2, nranks
      plan_start(o) = plan_start(o - 1) + send_count(o - 1)
    end do
    r%start = 0
    j = 0
    do source = 1, nranks
      do i = 1, got(source)
        j = j + 1
        r%node(j) = send_own(plan_start(source) + int(r%irecv(3 * j - 2)))
        r%start(r%node(j) + 1) = r%start(r%node(j) + 1) + 1
      end do
    end do
    r%start(1) = 1
    do i = 1, nown
      r%start(i + 1) = r%start(i + 1) + r%start(i)
    end do
    r%place(:nown) = r%start(:nown)
    do j = 1, nr
      d = r%place(r%node(j))
      r%place(r%node(j)) = d + 1
      r%id(:, d) = [int(r%node(j), i8), r%irecv(3 * j - 1:3 * j)]
      r%val(:, d) = r%rrecv(nv * (j - 1) + 1:nv * j)
    end do
    ! Within a node: (interface, key) ascending.
    do i = 1, nown
      do j = r%start(i) + 1, r%start(i + 1) - 1
        id = r%id(:, j)
        val = r%val(:, j)
        e = j - 1
        do while (e >= r%start(i))
          if (r%id(2, e) < id(2) .or. (r%id(2, e) == id(2) .and. r%id(3, e) <= id(3))) exit
          r%id(:, e + 1) = r%id(:, e)
          r%val(:, e + 1) = r%val(:, e)
          e = e - 1
        end do
        r%id(:, e + 1) = id
        r%val(:, e + 1) = val
      end do
    end do

  end subroutine send_records

  !> Make a buffer hold at least n elements (grown by doubling, kept).
  subroutine reserve_i8(a, n)
    integer(i8), allocatable, intent(inout) :: a(:)
    integer, intent(in) :: n
    if (allocated(a)) then
      if (size(a) >= n) return
      deallocate(a)
    end if
    allocate(a(max(2 * n, 64)))
  end subroutine reserve_i8

  !> Make a buffer hold at least n elements (grown by doubling, kept).
  subroutine reserve_real(a, n)
    real(rk), allocatable, intent(inout) :: a(:)
    integer, intent(in) :: n
    if (allocated(a)) then
      if (size(a) >= n) return
      deallocate(a)
    end if
    allocate(a(max(2 * n, 64)))
  end subroutine reserve_real

  !> Sums of 3-vector records per (owned node, interface), in key order.
  subroutine sum_records(r, fck, has)
    type(records_t), intent(in) :: r
    real(rk), intent(inout) :: fck(:, :, :)
    logical, intent(inout) :: has(:, :)
    integer :: j, i, k
    do j = 1, r%n
      i = int(r%id(1, j))
      k = int(r%id(2, j))
      fck(:, i, k) = fck(:, i, k) + r%val(:, j)
      has(i, k) = .true.
    end do
  end subroutine sum_records

end module contact_records
