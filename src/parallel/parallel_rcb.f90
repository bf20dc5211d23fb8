!> Recursive coordinate bisection (RCB) of weighted points, found in parallel
!> from global reductions only: no rank ever holds the points of another.
!>
!> The cut tree is bitwise the same on every rank and for every distribution
!> of the points over any number of ranks, because every decision is taken
!> from exact reductions: integer sums of integer weights, and minima of the
!> ordered integer images ("keys") of the coordinates and of the global ids.
!>
!> The build works level by level on the open subproblems (tree nodes with at
!> least two parts). For each, with np parts and nl = np / 2 of them on the left:
!> * its global bounding box gives the cut dimension d, the longest extent
!>   (ties: the lowest dimension);
!> * its total weight W gives the left target T = nint(W nl / np), rounded half up
!>   (a subproblem whose points all weigh zero is balanced by point count instead);
!> * the cut is the smallest key (value, gid), in lexicographic order, with the
!>   value in the subproblem's box and the gid from one below its lowest gid to its
!>   highest, such that the weight of the points with (x(d), gid) <= (value, gid)
!>   reaches T (with unit weights the left side weighs exactly T, since gids are
!>   unique and so no two keys are equal). It is found by a search on the key of
!>   the value, then on the gid among the points at that value. Every round
!>   probes up to 255 keys per subproblem at once (eight bisection steps; fewer
!>   on a level with many subproblems, down to four steps, so that a round's
!>   histogram stays near 1024 bins) with one reduction for all the
!>   subproblems of the level: a 64-bit key takes about eight rounds instead
!>   of sixteen at four steps, and the cut does not depend on the probes.
!> A point goes to the left part iff (x(d), gid) <= (cut value, cut gid). A
!> subproblem without points is cut at the middle of its region, across the
!> region's longest extent. Coordinates must not be NaN; gids must differ from
!> -huge(gid) - 1 and -huge(gid); W * 2 * nparts must fit in integer(i8).
module parallel_rcb
  use mpi_f08, only: MPI_Allreduce, MPI_Op, MPI_INTEGER8, MPI_SUM, MPI_MIN
  use core_kinds, only: rk, i8
  use core_sort, only: sort_values
  use parallel_env, only: par_comm, par_abort
  implicit none
  private
  public :: rcb_build, rcb_part_of, rcb_parts_of_box

  !> Number of coordinates of a point.
  integer, parameter :: NDIM = 3
  !> Bisection steps done at once in one search round: at most, at least,
  !> and the histogram bins of a round aimed at (subproblems times probes).
  integer, parameter :: PROBE_DEPTH = 8, MIN_PROBE_DEPTH = 4, ROUND_BINS = 1024
  !> Search phases of a subproblem.
  integer, parameter :: PHASE_DONE = 0, PHASE_VALUE = 1, PHASE_GID = 2

  !> The RCB cut tree and the parts' regions, identical on every rank.
  !> Internal nodes are numbered breadth first from the root (node 1), left
  !> child before right child; there are nparts - 1 of them.
  type, public :: rcb_t
    !> number of parts (leaves), numbered 0 .. nparts - 1
    integer :: nparts = 1
    !> (nnode) dimension (1..3) cut at each internal node
    integer, allocatable :: cut_dim(:)
    !> (nnode) cut value: a point goes left iff (x(d), gid) <= (cut_value, cut_gid)
    real(rk), allocatable :: cut_value(:)
    !> (nnode) tie-breaking id of each cut
    integer(i8), allocatable :: cut_gid(:)
    !> (2, nnode) left and right child: > 0 an internal node, <= 0 the leaf part -child
    integer, allocatable :: child(:, :)
    !> (2, nnode) first and last part of each internal node's subtree
    integer, allocatable :: node_parts(:, :)
    !> (3, 0:nparts-1) lower corner of each part's region (-huge(1.0_rk) if open)
    real(rk), allocatable :: part_lo(:, :)
    !> (3, 0:nparts-1) upper corner of each part's region (huge(1.0_rk) if open)
    real(rk), allocatable :: part_hi(:, :)
    !> (0:nparts-1) global weight of each part's points
    integer(i8), allocatable :: part_weight(:)
    !> (0:nparts-1) global number of each part's points
    integer(i8), allocatable :: part_count(:)
    !> number of global reductions the build made (diagnostic)
    integer :: reductions = 0
  end type rcb_t

contains

  !> Build the RCB cut tree of the points of all ranks. Collective.
  subroutine rcb_build(x, weight, gid, nparts, rcb)
    real(rk), intent(in) :: x(:, :) !< (3, n) this rank's points; n may be 0
    integer(i8), intent(in) :: weight(:) !< (n) non-negative work weights
    integer(i8), intent(in) :: gid(:) !< (n) globally unique ids
    integer, intent(in) :: nparts !< number of parts, >= 1, the same on every rank
    type(rcb_t), intent(out) :: rcb !< the cut tree, identical on every rank
    integer(i8), allocatable :: key(:, :)
    integer, allocatable :: point_item(:)
    ! The items of a level: the subproblems (open, np >= 2) and the leaves (np == 1).
    integer :: nitem, nnode, k, i, c, side, d
    integer, allocatable :: item_first(:), item_np(:), item_node(:)
    real(rk), allocatable :: item_lo(:, :), item_hi(:, :)
    integer(i8), allocatable :: item_sum(:, :), item_box(:, :)
    ! The cut of each open item of the level.
    integer, allocatable :: item_dim(:), item_child(:, :)
    integer(i8), allocatable :: item_key(:), item_gid(:)
    real(rk), allocatable :: item_value(:)
    ! The next level.
    integer :: nnext
    integer, allocatable :: next_first(:), next_np(:), next_node(:)
    real(rk), allocatable :: next_lo(:, :), next_hi(:, :)
    integer :: first, np, nl

    call check_arguments(x, weight, gid, nparts, rcb%reductions)
    rcb%nparts = nparts
    allocate(rcb%cut_dim(nparts - 1), rcb%cut_value(nparts - 1), rcb%cut_gid(nparts - 1))
    allocate(rcb%child(2, nparts - 1), rcb%node_parts(2, nparts - 1))
    allocate(rcb%part_lo(NDIM, 0:nparts - 1), rcb%part_hi(NDIM, 0:nparts - 1))
    allocate(rcb%part_weight(0:nparts - 1), rcb%part_count(0:nparts - 1))

    allocate(key(NDIM, size(x, 2)))
    key = real_key(x)
    allocate(point_item(size(x, 2)))
    point_item = 1

    nitem = 1
    allocate(item_first(1), item_np(1), item_node(1), item_lo(NDIM, 1), item_hi(NDIM, 1))
    item_first = 0
    item_np = nparts
    item_node = merge(1, 0, nparts >= 2)
    item_lo = -huge(1.0_rk)
    item_hi = huge(1.0_rk)
    nnode = min(nparts - 1, 1)

    do
      ! Count and weight of every item; the leaves are final.
      allocate(item_sum(2, nitem))
      item_sum = 0
      do i = 1, size(point_item)
        k = point_item(i)
        if (k == 0) cycle
        item_sum(1, k) = item_sum(1, k) + 1
        item_sum(2, k) = item_sum(2, k) + weight(i)
      end do
      call reduce(item_sum, MPI_SUM, rcb%reductions)
      do k = 1, nitem
        if (item_np(k) /= 1) cycle
        first = item_first(k)
        rcb%part_count(first) = item_sum(1, k)
        rcb%part_weight(first) = item_sum(2, k)
        rcb%part_lo(:, first) = item_lo(:, k)
        rcb%part_hi(:, first) = item_hi(:, k)
      end do
      if (all(item_np(1:nitem) == 1)) exit

      ! Bounding box (keys) and gid range of every open item.
      allocate(item_box(2 * NDIM + 2, nitem))
      item_box = huge(1_i8)
      do i = 1, size(point_item)
        k = point_item(i)
        if (k == 0) cycle
        if (item_np(k) < 2) cycle
        item_box(1:NDIM, k) = min(item_box(1:NDIM, k), key(:, i))
        item_box(NDIM + 1:2 * NDIM, k) = min(item_box(NDIM + 1:2 * NDIM, k), -key(:, i))
        item_box(2 * NDIM + 1, k) = min(item_box(2 * NDIM + 1, k), gid(i))
        item_box(2 * NDIM + 2, k) = min(item_box(2 * NDIM + 2, k), -gid(i))
      end do
      call reduce(item_box, MPI_MIN, rcb%reductions)

      allocate(item_dim(nitem), item_key(nitem), item_gid(nitem), item_value(nitem))
      call find_cuts(key, weight, gid, point_item, item_np, item_lo, item_hi, item_sum, &
          item_box, item_dim, item_key, item_gid, item_value, rcb%reductions)

      ! Record the cuts; the children of the open items make the next level.
      allocate(item_child(2, nitem))
      item_child = 0
      nnext = 2 * count(item_np(1:nitem) >= 2)
      allocate(next_first(nnext), next_np(nnext), next_node(nnext))
      allocate(next_lo(NDIM, nnext), next_hi(NDIM, nnext))
      nnext = 0
      do k = 1, nitem
        if (item_np(k) < 2) cycle
        c = item_node(k)
        d = item_dim(k)
        first = item_first(k)
        np = item_np(k)
        nl = np / 2
        rcb%cut_dim(c) = d
        rcb%cut_value(c) = item_value(k)
        rcb%cut_gid(c) = item_gid(k)
        rcb%node_parts(:, c) = [first, first + np - 1]
        do side = 1, 2
          nnext = nnext + 1
          item_child(side, k) = nnext
          next_lo(:, nnext) = item_lo(:, k)
          next_hi(:, nnext) = item_hi(:, k)
          if (side == 1) then
            next_first(nnext) = first
            next_np(nnext) = nl
            next_hi(d, nnext) = item_value(k)
          else
            next_first(nnext) = first + nl
            next_np(nnext) = np - nl
            next_lo(d, nnext) = item_value(k)
          end if
          if (next_np(nnext) >= 2) then
            nnode = nnode + 1
            next_node(nnext) = nnode
            rcb%child(side, c) = nnode
          else
            next_node(nnext) = 0
            rcb%child(side, c) = -next_first(nnext)
          end if
        end do
      end do

      ! Move every point of an open item to its child; the points of leaves are done.
      do i = 1, size(point_item)
        k = point_item(i)
        if (k == 0) cycle
        if (item_np(k) < 2) then
          point_item(i) = 0
          cycle
        end if
        d = item_dim(k)
        if (key_less_equal(key(d, i), gid(i), item_key(k), item_gid(k))) then
          point_item(i) = item_child(1, k)
        else
          point_item(i) = item_child(2, k)
        end if
      end do

      nitem = nnext
      call move_alloc(next_first, item_first)
      call move_alloc(next_np, item_np)
      call move_alloc(next_node, item_node)
      call move_alloc(next_lo, item_lo)
      call move_alloc(next_hi, item_hi)
      deallocate(item_sum, item_box, item_dim, item_key, item_gid, item_value, item_child)
    end do
  end subroutine rcb_build

  !> The part (0 .. nparts - 1) of a point with this global id.
  pure integer function rcb_part_of(rcb, point, gid) result(part)
    type(rcb_t), intent(in) :: rcb !< a built tree
    real(rk), intent(in) :: point(:) !< (3) coordinates
    integer(i8), intent(in) :: gid !< the point's global id (breaks ties on a cut)
    integer :: node, next, d
    logical :: left

    part = 0
    if (rcb%nparts < 2) return
    node = 1
    do
      d = rcb%cut_dim(node)
      if (point(d) < rcb%cut_value(node)) then
        left = .true.
      else if (point(d) > rcb%cut_value(node)) then
        left = .false.
      else
        left = gid <= rcb%cut_gid(node)
      end if
      if (left) then
        next = rcb%child(1, node)
      else
        next = rcb%child(2, node)
      end if
      if (next <= 0) then
        part = -next
        return
      end if
      node = next
    end do
  end function rcb_part_of

  !> Every part whose region meets the closed box [lo, hi], in ascending order.
  !> A box touching a cut plane meets both sides. An empty box (lo > hi in some
  !> dimension) meets nothing.
  pure subroutine rcb_parts_of_box(rcb, lo, hi, parts, n)
    type(rcb_t), intent(in) :: rcb !< a built tree
    real(rk), intent(in) :: lo(:) !< (3) lower corner of the box
    real(rk), intent(in) :: hi(:) !< (3) upper corner of the box
    integer, intent(out) :: parts(:) !< (nparts) the parts met, ascending, in parts(1:n)
    integer, intent(out) :: n !< number of parts met
    ! Depth-first walk; the tree depth is below 32 for any default integer nparts.
    integer :: stack(64), top, node, d

    n = 0
    if (any(lo(1:NDIM) > hi(1:NDIM))) return
    top = 1
    ! A tree of one part is the leaf 0.
    stack(1) = merge(1, 0, rcb%nparts >= 2)
    do while (top > 0)
      node = stack(top)
      top = top - 1
      if (node <= 0) then
        ! A too small parts(:) is the caller's error: n still counts every part.
        n = n + 1
        if (n <= size(parts)) parts(n) = -node
        cycle
      end if
      d = rcb%cut_dim(node)
      ! Push the right child first so that the left subtree (lower parts) comes out first.
      if (hi(d) >= rcb%cut_value(node)) then
        top = top + 1
        stack(top) = rcb%child(2, node)
      end if
      if (lo(d) <= rcb%cut_value(node)) then
        top = top + 1
        stack(top) = rcb%child(1, node)
      end if
    end do
  end subroutine rcb_parts_of_box

  !> Check the arguments on every rank, including that nparts is the same everywhere.
  subroutine check_arguments(x, weight, gid, nparts, reductions)
    real(rk), intent(in) :: x(:, :)
    integer(i8), intent(in) :: weight(:), gid(:)
    integer, intent(in) :: nparts
    integer, intent(inout) :: reductions
    integer(i8) :: flags(3, 1)
    logical :: ok

    ok = size(x, 1) == NDIM .and. size(weight) == size(x, 2) .and. size(gid) == size(x, 2)
    if (ok) ok = all(weight >= 0)
    flags(:, 1) = [int(nparts, i8), -int(nparts, i8), merge(1_i8, 0_i8, ok)]
    call reduce(flags, MPI_MIN, reductions)
    if (flags(3, 1) == 0) then
      call par_abort('rcb_build: x must be (3, n), weight and gid (n), weights >= 0', 2)
    end if
    if (flags(1, 1) /= -flags(2, 1) .or. flags(1, 1) < 1) then
      call par_abort('rcb_build: nparts must be >= 1 and the same on every rank', 2)
    end if
  end subroutine check_arguments

  !> Find the cut of every open item of a level (batched search rounds).
  subroutine find_cuts(key, weight, gid, point_item, item_np, item_lo, item_hi, item_sum, &
      item_box, item_dim, item_key, item_gid, item_value, reductions)
    integer(i8), intent(in) :: key(:, :) !< (3, n) keys of the coordinates
    integer(i8), intent(in) :: weight(:) !< (n)
    integer(i8), intent(in) :: gid(:) !< (n)
    integer, intent(in) :: point_item(:) !< (n) item of each point, 0 if done
    integer, intent(in) :: item_np(:) !< (nitem) parts of each item
    real(rk), intent(in) :: item_lo(:, :), item_hi(:, :) !< (3, nitem) regions
    integer(i8), intent(in) :: item_sum(:, :) !< (2, nitem) global count and weight
    integer(i8), intent(in) :: item_box(:, :) !< (8, nitem) min keys, -max keys, min gid, -max gid
    integer, intent(out) :: item_dim(:) !< (nitem) cut dimension
    integer(i8), intent(out) :: item_key(:) !< (nitem) key of the cut value
    integer(i8), intent(out) :: item_gid(:) !< (nitem) cut gid
    real(rk), intent(out) :: item_value(:) !< (nitem) cut value
    integer, intent(inout) :: reductions
    integer :: nitem, k, d, i, j, phase(size(item_np)), nprobe(size(item_np))
    integer(i8) :: target_weight(size(item_np))
    integer(i8) :: search_lo(size(item_np)), search_hi(size(item_np))
    integer(i8) :: below(size(item_np))
    integer(i8) :: total, w, cumulative, below_next
    integer(i8), allocatable :: probe(:, :), histogram(:, :)
    integer, allocatable :: active(:)
    integer :: nactive, m, depth
    logical :: by_count(size(item_np))
    real(rk) :: extent(NDIM), lo(NDIM), hi(NDIM)

    nitem = size(item_np)
    phase = PHASE_DONE
    item_dim = 1
    item_key = 0
    item_gid = 0
    item_value = 0.0_rk
    target_weight = 0
    search_lo = 0
    search_hi = 0
    by_count = .false.
    do k = 1, nitem
      if (item_np(k) < 2) cycle
      if (item_sum(1, k) == 0) then
        ! No points: cut the region in the middle of its longest extent.
        lo = item_lo(:, k)
        hi = item_hi(:, k)
      else
        lo = key_real(item_box(1:NDIM, k))
        hi = key_real(-item_box(NDIM + 1:2 * NDIM, k))
      end if
      ! Halves first: no overflow for regions open to +-huge.
      extent = 0.5_rk * hi - 0.5_rk * lo
      d = 1
      do j = 2, NDIM
        if (extent(j) > extent(d)) d = j
      end do
      item_dim(k) = d
      if (item_sum(1, k) == 0) then
        item_value(k) = 0.5_rk * lo(d) + 0.5_rk * hi(d)
        item_key(k) = real_key(item_value(k))
        cycle
      end if
      by_count(k) = item_sum(2, k) == 0
      total = merge(item_sum(1, k), item_sum(2, k), by_count(k))
      target_weight(k) = (2 * total * (item_np(k) / 2) + item_np(k)) / (2 * item_np(k))
      phase(k) = PHASE_VALUE
      search_lo(k) = item_box(d, k)
      search_hi(k) = -item_box(NDIM + d, k)
      call settle(k)
    end do

    ! Only the points inside their item's search interval are visited: "active"
    ! lists them, and below(k) is the (global) weight of item k's points under it.
    allocate(active(size(point_item)))
    nactive = 0
    do i = 1, size(point_item)
      k = point_item(i)
      if (k == 0) cycle
      if (phase(k) == PHASE_DONE) cycle
      nactive = nactive + 1
      active(nactive) = i
    end do
    call keep_active()
    below = 0
    nprobe = 0
    ! Steps per round: the same on every rank (from the open subproblems).
    depth = PROBE_DEPTH
    do while (depth > MIN_PROBE_DEPTH .and. count(item_np >= 2) * (2**depth - 1) > ROUND_BINS)
      depth = depth - 1
    end do
    allocate(probe(2**depth - 1, nitem), histogram(2**depth - 1, nitem))
    do while (any(phase /= PHASE_DONE))
      do k = 1, nitem
        nprobe(k) = 0
        if (phase(k) /= PHASE_DONE) call make_probes(search_lo(k), search_hi(k), depth, &
            probe(:, k), nprobe(k))
      end do
      ! histogram(j, k): weight of the active points of item k whose key (value, then gid)
      ! is in (probe j-1, probe j].
      histogram = 0
      do m = 1, nactive
        i = active(m)
        k = point_item(i)
        if (by_count(k)) then
          w = 1
        else
          w = weight(i)
        end if
        if (w == 0) cycle
        if (phase(k) == PHASE_VALUE) then
          j = first_at_least(probe(:, k), nprobe(k), key(item_dim(k), i))
        else
          j = first_at_least(probe(:, k), nprobe(k), gid(i))
        end if
        if (j > 0) histogram(j, k) = histogram(j, k) + w
      end do
      call reduce(histogram, MPI_SUM, reductions)
      ! Keep the interval between the last probe below the target and the first reaching it.
      do k = 1, nitem
        if (phase(k) == PHASE_DONE) cycle
        cumulative = below(k)
        below_next = below(k)
        j = 0
        do m = 1, nprobe(k)
          cumulative = cumulative + histogram(m, k)
          if (cumulative >= target_weight(k)) then
            j = m
            exit
          end if
          below_next = cumulative
        end do
        if (j > 0) then
          search_hi(k) = probe(j, k)
          if (j > 1) then
            search_lo(k) = probe(j - 1, k) + 1
            below(k) = below_next
          end if
        else
          search_lo(k) = probe(nprobe(k), k) + 1
          below(k) = cumulative
        end if
        call settle(k)
      end do
      call keep_active()
    end do

  contains

    !> Drop from the active list the points outside their item's search interval.
    subroutine keep_active()
      integer :: m, i, k, nkept
      logical :: keep
      nkept = 0
      do m = 1, nactive
        i = active(m)
        k = point_item(i)
        select case (phase(k))
        case (PHASE_VALUE)
          keep = search_lo(k) <= key(item_dim(k), i) .and. key(item_dim(k), i) <= search_hi(k)
        case (PHASE_GID)
          keep = key(item_dim(k), i) == item_key(k) .and. search_lo(k) <= gid(i) .and. &
              gid(i) <= search_hi(k)
        case default
          keep = .false.
        end select
        if (keep) then
          nkept = nkept + 1
          active(nkept) = i
        end if
      end do
      nactive = nkept
    end subroutine keep_active

    !> Move item k on when its search interval has shrunk to one key.
    subroutine settle(k)
      integer, intent(in) :: k
      if (phase(k) == PHASE_VALUE .and. search_lo(k) == search_hi(k)) then
        item_key(k) = search_lo(k)
        item_value(k) = key_real(item_key(k))
        phase(k) = PHASE_GID
        ! From one below the lowest gid, so that a zero target leaves the left side empty.
        search_lo(k) = item_box(2 * NDIM + 1, k) - 1
        search_hi(k) = -item_box(2 * NDIM + 2, k)
      end if
      if (phase(k) == PHASE_GID .and. search_lo(k) == search_hi(k)) then
        item_gid(k) = search_lo(k)
        phase(k) = PHASE_DONE
      end if
    end subroutine settle

  end subroutine find_cuts

  !> The keys of up to depth bisection steps on [lo, hi] (lo < hi), ascending.
  pure subroutine make_probes(lo, hi, depth, probe, nprobe)
    integer(i8), intent(in) :: lo, hi
    integer, intent(in) :: depth !< 1 .. PROBE_DEPTH
    integer(i8), intent(out) :: probe(:) !< (2**depth - 1)
    integer, intent(out) :: nprobe
    integer(i8) :: a(2**PROBE_DEPTH), b(2**PROBE_DEPTH), a_next(2**PROBE_DEPTH)
    integer(i8) :: b_next(2**PROBE_DEPTH), middle
    integer :: step, m, ninterval, nnext

    nprobe = 0
    ninterval = 1
    a(1) = lo
    b(1) = hi
    do step = 1, depth
      nnext = 0
      do m = 1, ninterval
        if (a(m) >= b(m)) cycle
        middle = floor_average(a(m), b(m))
        nprobe = nprobe + 1
        probe(nprobe) = middle
        a_next(nnext + 1) = a(m)
        b_next(nnext + 1) = middle
        a_next(nnext + 2) = middle + 1
        b_next(nnext + 2) = b(m)
        nnext = nnext + 2
      end do
      ninterval = nnext
      a(1:nnext) = a_next(1:nnext)
      b(1:nnext) = b_next(1:nnext)
    end do
    call sort_values(probe(1:nprobe))
  end subroutine make_probes

  !> floor((a + b) / 2) without overflow.
  elemental function floor_average(a, b) result(m)
    integer(i8), intent(in) :: a, b
    integer(i8) :: m
    m = iand(a, b) + shifta(ieor(a, b), 1)
  end function floor_average

  !> The first j with value <= sorted(j), 0 if none.
  pure integer function first_at_least(sorted, n, value) result(j)
    integer(i8), intent(in) :: sorted(:) !< ascending in 1..n
    integer, intent(in) :: n !< number of values in sorted
    integer(i8), intent(in) :: value
    integer :: lo, hi, mid
    j = 0
    if (n == 0) return
    if (value > sorted(n)) return
    lo = 1
    hi = n
    do while (lo < hi)
      mid = (lo + hi) / 2
      if (value <= sorted(mid)) then
        hi = mid
      else
        lo = mid + 1
      end if
    end do
    j = lo
  end function first_at_least

  !> (key, gid) <= (cut_key, cut_gid) in lexicographic order.
  elemental logical function key_less_equal(key, gid, cut_key, cut_gid)
    integer(i8), intent(in) :: key, gid, cut_key, cut_gid
    key_less_equal = key < cut_key .or. (key == cut_key .and. gid <= cut_gid)
  end function key_less_equal

  !> Integer image of a real, ordered like the reals; -0.0 and +0.0 both map to 0.
  elemental function real_key(value) result(key)
    real(rk), intent(in) :: value
    integer(i8) :: key
    key = transfer(value, 0_i8)
    if (key == -huge(0_i8) - 1_i8) then
      key = 0
    else if (key < 0) then
      key = ieor(key, huge(0_i8))
    end if
  end function real_key

  !> The real whose key this is (inverse of real_key).
  elemental function key_real(key) result(value)
    integer(i8), intent(in) :: key
    real(rk) :: value
    integer(i8) :: bits
    bits = key
    if (bits < 0) bits = ieor(bits, huge(0_i8))
    value = transfer(bits, 0.0_rk)
  end function key_real

  !> In-place global reduction of an integer(i8) array.
  subroutine reduce(buffer, op, reductions)
    integer(i8), intent(inout), contiguous :: buffer(:, :)
    type(MPI_Op), intent(in) :: op
    integer, intent(inout) :: reductions !< counter of reductions
    integer(i8), allocatable :: reduced(:, :)
    allocate(reduced(size(buffer, 1), size(buffer, 2)))
    call MPI_Allreduce(buffer, reduced, size(buffer), MPI_INTEGER8, op, par_comm())
    buffer = reduced
    reductions = reductions + 1
  end subroutine reduce

end module parallel_rcb
