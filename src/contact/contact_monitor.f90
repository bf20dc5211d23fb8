!> Contact monitoring: the geometric penetration audit (contact_audit) run on
!> the whole contact surfaces at set-up (initial penetration: error, adjust
!> or ignore), at every global search and at every dump; the per-interface
!> force and work of each step; and the warning policy (on_penetration).
!>
!> The audit reads positions only. Each rank audits the nodes it owns. It
!> gets the positions of the contact nodes near them from their owners (one
!> exchange: every rank's box of owned nodes, widened by the reach and two
!> segment spans, near_nodes), and audits its nodes against the segments of
!> the opposite surface whose corners all arrived. Those hold every segment
!> within reach of an owned node and the segments around their corners, and
!> the bucket grid is the whole surface's (its box from one reduction), so
!> each node's closest point, and the order in which its candidates are
!> visited, are those of the whole surface: the gaps, maxima and counts are
!> the same on any number of ranks. No rank holds a position array of every
!> contact node.
!>
!> Penetration of a node = its depth inside the opposite body (the audit's
!> negative gap) less the initial penetration the deck kept for it (the
!> offset). A node is a violation when that exceeds its tolerance: the deck's
!> penetration_tolerance, or by default the larger of 5% of the smaller
!> adjacent segment and the opposite segment's faceting sagitta. A violation
!> is unheld when the node carried no force of the interface in the last
!> corrector (DAM: slave nodes; a master node's penetration is reported in
!> the side-b columns).
module contact_monitor
  use core_kinds, only: rk, ik, i8
  use core_exact_sum, only: exact_sum_t, exact_value
  use core_status, only: status_t
  use, intrinsic :: iso_fortran_env, only: output_unit, error_unit
  use core_sort, only: sort_unique, sorted_find, sort_order
  use contact_surface, only: contact_surface_t, surface_renumbered, surface_from_segments, &
      surface_node_index
  use contact_audit, only: audit_gaps, segment_sizes, node_tolerance, audit_reach
  use contact_state, only: contact_spec_t, interface_t, contact_t, contact_method_t, &
      initial_offsets_t, DIAG_FORCE, DIAG_WORK, DIAG_AUDIT, SURFACE_LEN, owned_index
  use contact_factory, only: contact_method_new
  use contact_sides, only: side_context_t, side_surface
  use mesh_local, only: mesh_t
  use parallel_env, only: par_sum_array, par_sum_exact, par_rank, par_size, par_allgather, &
      par_max_array, par_max
  use parallel_route, only: par_min_array
  use parallel_exchange, only: par_exchange, par_exchange_counts
  implicit none
  private
  public :: contact_initial, contact_audit_run, contact_step_end, contact_audit_due
  public :: contact_depths, contact_refresh_offsets

  !> At most one audit warning per interface in this many cycles.
  integer, parameter :: WARN_EVERY = 100

  !> One side's audit: per node of the surface.
  type :: side_t
    real(rk), allocatable :: gap(:), pen(:), tol(:), inward(:, :)
    integer, allocatable :: hit(:)
  end type side_t

  !> The contact nodes near this rank's owned ones, with their positions
  !> (near_nodes): the audit's node numbering (the near index).
  type :: near_t
    !> every contact node (one rank): the near index is the contact index,
    !> and the audit reads the whole surfaces
    logical :: all = .false.
    integer, allocatable :: c(:) !< (n) contact indices, ascending
    real(rk), allocatable :: x(:, :) !< (3, n) their positions
  end type near_t

  !> The widening of a rank's box of owned nodes: the reach and this many
  !> largest segment spans (two are needed: a segment within reach of a node
  !> and the segments around its corners; the rest is margin).
  real(rk), parameter :: SPAN_WIDENING = 2.5_rk
  !> Most boxes a rank sends for its owned nodes (near_nodes; beyond, the
  !> last box grows to hold the rest).
  integer, parameter :: MAX_BOXES = 64

contains

  !> The audit of one side: gaps of the selected nodes of `own` against
  !> `other`, penetration beyond the offsets, and each node's tolerance.
  subroutine audit_side(x, own, other, self, reach, tol_fixed, offset, selected, planes, side, &
      grid_box)
    real(rk), intent(in) :: x(:, :)
    type(contact_surface_t), intent(in) :: own, other
    logical, intent(in) :: self
    real(rk), intent(in) :: reach, tol_fixed
    real(rk), intent(in) :: offset(:) !< (own%nnode)
    logical, intent(in) :: selected(:) !< (own%nnode)
    real(rk), intent(in) :: planes(:, :) !< (4, n) symmetry planes (contact_audit)
    type(side_t), intent(out) :: side
    !> (3, 2) box of the whole surface of which other is a part (audit_gaps)
    real(rk), intent(in), optional :: grid_box(:, :)
    real(rk), allocatable :: osz(:), tsz(:), tsag(:)
    real(rk) :: hmin
    integer :: i, e, n
    n = own%nnode
    allocate(side%gap(n), side%pen(n), side%tol(n), side%inward(3, n), side%hit(n))
    ! (the target's sizes and sagittas from audit_gaps, which computes them;
    ! of the own side only the sizes)
    call audit_gaps(x, own, other, self, reach, selected, side%gap, side%hit, side%inward, &
        planes, tsz, tsag, grid_box)
    allocate(osz(own%nseg))
    call segment_sizes(x, own, osz)
    do i = 1, n
      side%pen(i) = max(-side%gap(i) - offset(i), 0.0_rk)
      if (tol_fixed > 0.0_rk) then
        side%tol(i) = tol_fixed
      else
        hmin = huge(1.0_rk)
        do e = own%node_start(i), own%node_start(i + 1) - 1
          hmin = min(hmin, osz(own%node_segments(e)))
        end do
        if (side%hit(i) > 0) then
          side%tol(i) = node_tolerance(hmin, tsz(side%hit(i)), tsag(side%hit(i)))
        else
          side%tol(i) = node_tolerance(hmin, hmin, 0.0_rk)
        end if
      end if
    end do
  end subroutine audit_side

  !> Initial penetration, at set-up, before the nodal masses: the audit of
  !> every interface on the deck's mesh. Per interface, rank 0 reports the
  !> nodes beyond the tolerance (count, deepest, histogram); then by the
  !> deck's initial_penetration: 'error' adds an input error, 'adjust' moves
  !> the penetrating nodes of one side (DAM: the slave; DLM: surface_a) onto
  !> the other surface, 'ignore' keeps every penetration as an offset.
  !> Penetration within the tolerance is an offset under every option.
  !> The surfaces come from each rank's local mesh and the positions of
  !> their nodes from the nodes' owners, so every rank computes the same
  !> with no whole-mesh array; a moved node is moved in x on every rank that
  !> holds it. Collective.
  subroutine contact_initial(specs, mesh, x, planes, offsets, status, context)
    type(contact_spec_t), intent(in) :: specs(:)
    type(mesh_t), intent(in) :: mesh
    real(rk), intent(inout) :: x(:, :) !< (3, nnode local) node positions
    real(rk), intent(in) :: planes(:, :) !< (4, n) the deck's symmetry planes
    type(initial_offsets_t), allocatable, intent(out) :: offsets(:)
    type(status_t), intent(inout) :: status
    !> the deck's blocks and closed face sets, for surfaces given by blocks
    type(side_context_t), intent(in), optional :: context
    type(side_context_t) :: sides
    type(contact_surface_t) :: sa, sb, ga, gb
    type(side_t) :: ra, rb
    character(len=SURFACE_LEN) :: slave_set, master_set
    class(contact_method_t), allocatable :: method
    logical :: single
    character(len=600) :: text
    character(len=:), allocatable :: where
    integer(i8), allocatable :: gid(:)
    real(rk), allocatable :: xc(:, :)
    real(rk) :: reach, moved, deepest, where_x(3)
    integer :: k, i, n, nbeyond_a, nbeyond_b, deepest_node, bins(4)
    integer(i8) :: deepest_gid
    logical :: self, ok

    if (present(context)) then
      sides = context
    else
      allocate(sides%block_names(0), sides%closed_sets(0))
    end if
    allocate(offsets(size(specs)))
    do k = 1, size(specs)
      where = '&contact '''//trim(specs(k)%name)//''''
      ! The method's sides (DAM: a is the slave side).
      call contact_method_new(specs(k), .false., method, single)
      call method%sides(specs(k), slave_set, master_set)
      ok = status%ok()
      call side_surface(slave_set, master_set, mesh, sides, trim(where), ga, status)
      call side_surface(master_set, slave_set, mesh, sides, trim(where), gb, status)
      allocate(offsets(k)%a(ga%nnode), offsets(k)%b(gb%nnode))
      offsets(k)%a = 0.0_rk
      offsets(k)%b = 0.0_rk
      if (.not. status%ok() .or. .not. ok) cycle
      ! The interface's nodes (ascending global id), their positions, and
      ! the two surfaces in that numbering.
      call surface_positions(mesh, x, ga, gb, gid, xc, sa, sb)
      self = specs(k)%surface_a == specs(k)%surface_b
      reach = audit_reach(xc, sa, sb)
      call both_sides()
      nbeyond_a = count(ra%pen > ra%tol)
      nbeyond_b = 0
      if (.not. self) nbeyond_b = count(rb%pen > rb%tol)
      if (nbeyond_a + nbeyond_b == 0) then
        call keep_within()
        cycle
      end if
      call deepest_of()
      if (par_rank() == 0) then
        write(text, '(a,i0,a,i0,a,i0,a,3es13.5,a,es10.3,a,es10.3,a,4(i0,a))') &
            'impact3d: '//where//': initial penetration beyond the tolerance: ', &
            nbeyond_a, ' nodes of surface a, ', nbeyond_b, ' of surface b; deepest node ', &
            deepest_gid, ' at (', where_x, ') by ', deepest, ' (tolerance ', &
            tolerance_of(deepest_node), '); depth/tolerance 1-2: ', bins(1), ', 2-4: ', &
            bins(2), ', 4-8: ', bins(3), ', > 8: ', bins(4), ''
        write(output_unit, '(a)') trim(text)
      end if
      select case (specs(k)%initial_penetration)
      case ('error')
        write(text, '(a,i0,a,i0,a,3es13.5,a,es10.3,a)') &
            ': initial_penetration: ', nbeyond_a + nbeyond_b, &
            ' node(s) penetrate the other surface at set-up; the deepest, node ', deepest_gid, &
            ' at (', where_x, '), by ', deepest, '; move the parts apart, or set '// &
            'initial_penetration = ''adjust'' (move them onto the other surface) or '// &
            '''ignore'' (keep the overlap)'
        call status%add(where//trim(text))
      case ('adjust')
        ! Move side a's nodes beyond the tolerance onto the other surface.
        moved = 0.0_rk
        do i = 1, sa%nnode
          if (.not. ra%pen(i) > ra%tol(i)) cycle
          xc(:, sa%nodes(i)) = xc(:, sa%nodes(i)) + (-ra%gap(i)) * ra%inward(:, i)
          moved = max(moved, -ra%gap(i))
        end do
        ! Every copy of a moved node moves (owned and ghost alike).
        do n = 1, mesh%nnode
          i = sorted_find(gid, mesh%node_gid(n))
          if (i > 0) x(:, n) = xc(:, i)
        end do
        call both_sides()
        call keep_within()
        if (par_rank() == 0) write(output_unit, '(a,i0,a,es10.3)') 'impact3d: '//where// &
            ': initial_penetration = ''adjust'': moved ', nbeyond_a, &
            ' node(s) of surface a onto surface b, largest move ', moved
        if (self .or. nbeyond_b == 0) cycle
        if (par_rank() == 0 .and. count(rb%pen > rb%tol) > 0) write(output_unit, '(a,i0,a)') &
            'warning: '//where//': ', count(rb%pen > rb%tol), ' node(s) of surface '// &
            'b still penetrate surface a after the adjustment; kept as offsets'
        offsets(k)%b = max(offsets(k)%b, rb%pen)
      case default
        if (par_rank() == 0) write(output_unit, '(a,es10.3,a)') 'warning: '//where// &
            ': initial_penetration = ''ignore'': the overlap (deepest ', deepest, &
            ') is kept as an offset and held, not pushed out'
        offsets(k)%a = ra%pen
        if (.not. self) offsets(k)%b = rb%pen
      end select
    end do

  contains

    subroutine both_sides()
      real(rk), allocatable :: zero_a(:), zero_b(:)
      allocate(zero_a(sa%nnode), zero_b(sb%nnode))
      zero_a = 0.0_rk
      zero_b = 0.0_rk
      call audit_side(xc, sa, sb, self, reach, specs(k)%penetration_tolerance, &
          zero_a, [(.true., i = 1, sa%nnode)], planes, ra)
      if (.not. self) call audit_side(xc, sb, sa, .false., reach, &
          specs(k)%penetration_tolerance, zero_b, [(.true., i = 1, sb%nnode)], planes, rb)
    end subroutine both_sides

    !> Penetration within the tolerance: an offset under every option.
    subroutine keep_within()
      where (ra%pen <= ra%tol) offsets(k)%a = ra%pen
      if (.not. self) then
        where (rb%pen <= rb%tol) offsets(k)%b = rb%pen
      else
        offsets(k)%b = offsets(k)%a
      end if
    end subroutine keep_within

    subroutine deepest_of()
      integer :: j
      deepest = -1.0_rk
      bins = 0
      do j = 1, sa%nnode
        if (ra%pen(j) > ra%tol(j)) call add(ra%pen(j), ra%tol(j), int(sa%nodes(j)))
      end do
      if (.not. self) then
        do j = 1, sb%nnode
          if (rb%pen(j) > rb%tol(j)) call add(rb%pen(j), rb%tol(j), int(sb%nodes(j)))
        end do
      end if
      where_x = xc(:, deepest_node)
      deepest_gid = gid(deepest_node)
    end subroutine deepest_of

    subroutine add(pen, tol, node)
      real(rk) :: r
      real(rk), intent(in) :: pen, tol
      integer, intent(in) :: node
      r = pen / tol
      if (r < 2.0_rk) then
        bins(1) = bins(1) + 1
      else if (r < 4.0_rk) then
        bins(2) = bins(2) + 1
      else if (r < 8.0_rk) then
        bins(3) = bins(3) + 1
      else
        bins(4) = bins(4) + 1
      end if
      if (pen > deepest) then
        deepest = pen
        deepest_node = node
      end if
    end subroutine add

    real(rk) function tolerance_of(node) result(t)
      integer, intent(in) :: node
      integer :: j
      t = 0.0_rk
      do j = 1, sa%nnode
        if (sa%nodes(j) == node) t = ra%tol(j)
      end do
      if (.not. self) then
        do j = 1, sb%nnode
          if (sb%nodes(j) == node) t = rb%tol(j)
        end do
      end if
    end function tolerance_of

  end subroutine contact_initial

  !> The nodes of surfaces ga and gb (global node ids) in ascending global
  !> id, their positions from their owners (one sum over the ranks: each
  !> node has one owner, zeros elsewhere), and the surfaces numbered by
  !> position in gid. Collective.
  subroutine surface_positions(mesh, x, ga, gb, gid, xc, sa, sb)
    type(mesh_t), intent(in) :: mesh
    real(rk), intent(in) :: x(:, :) !< (3, nnode local)
    type(contact_surface_t), intent(in) :: ga, gb
    integer(i8), allocatable, intent(out) :: gid(:)
    real(rk), allocatable, intent(out) :: xc(:, :) !< (3, size(gid))
    type(contact_surface_t), intent(inout) :: sa, sb
    real(rk), allocatable :: flat(:)
    integer :: n, i
    gid = [int(ga%nodes, i8), int(gb%nodes, i8)]
    call sort_unique(gid)
    allocate(flat(3 * size(gid)))
    flat = 0.0_rk
    do n = 1, mesh%nnode_owned
      i = sorted_find(gid, mesh%node_gid(n))
      if (i > 0) flat(3 * i - 2:3 * i) = x(:, n)
    end do
    call par_sum_array(flat)
    xc = reshape(flat, [3, size(gid)])
    call surface_renumbered(ga, gid, xc, sa)
    call surface_renumbered(gb, gid, xc, sb)
  end subroutine surface_positions


  !> The contact nodes within the audit's reach of this rank's owned ones,
  !> and around them, with their positions from their owners. Each rank's
  !> boxes of owned contact nodes, one per side of each deck interface (a
  !> rank's mesh part can hold the sides of different interfaces, or of
  !> bodies far apart, and one box around them all would hold much of the
  !> problem), go to every rank (one gather), and each owner sends the
  !> positions of its nodes inside a box widened by h. h is the largest
  !> reach and SPAN_WIDENING times the largest segment span (the distance
  !> between two corners of one segment); the span is measured, after the
  !> exchange, by the owner of each segment's first corner, and when the
  !> exchange was too narrow (a segment with a corner missing, or h below
  !> the reach and two spans) it is repeated wider. One rank holds every
  !> node (near%all). Collective.
  subroutine near_nodes(ct, x, near)
    type(contact_t), intent(inout) :: ct
    real(rk), intent(in) :: x(:, :) !< (3, nnode local)
    type(near_t), intent(out) :: near
    real(rk), allocatable :: xo(:, :), mine(:), boxes(:, :), sbuf(:), rbuf(:)
    integer, allocatable :: scount(:), rcount(:), order(:)
    integer(i8), allocatable :: key(:)
    real(rk) :: reach, h, meas(2)
    integer :: np, o, r, n, j, k, fill, nbox
    np = par_size()
    allocate(xo(3, ct%nown))
    do o = 1, ct%nown
      xo(:, o) = x(:, ct%own_local(o))
    end do
    if (np == 1) then
      near%all = .true.
      near%c = ct%own_contact
      call move_alloc(xo, near%x)
      return
    end if
    reach = 0.0_rk
    do j = 1, ct%ndeck
      reach = max(reach, ct%pairs(j)%reach)
    end do
    h = 2.0_rk * reach
    if (ct%audit_span > 0.0_rk) h = reach + SPAN_WIDENING * ct%audit_span
    ! Box b: corners 6 (b - 1) + 1:3 (lower), + 4:6 (the negated upper).
    allocate(mine(6 * MAX_BOXES), scount(np), rcount(np))
    mine = huge(1.0_rk)
    nbox = 0
    do k = 1, ct%ndeck
      call side_boxes(ct%pairs(k)%all_a)
      call side_boxes(ct%pairs(k)%all_b)
    end do
    n = max(par_max(nbox), 1)
    allocate(boxes(6 * n, np))
    call par_allgather(mine(1:6 * n), boxes)
    do
      do r = 1, np
        scount(r) = 4 * count([(inside(xo(:, o), boxes(:, r)), o = 1, ct%nown)])
      end do
      if (allocated(sbuf)) deallocate(sbuf)
      allocate(sbuf(max(sum(scount), 1)))
      fill = 0
      do r = 1, np
        do o = 1, ct%nown
          if (.not. inside(xo(:, o), boxes(:, r))) cycle
          sbuf(fill + 1:fill + 4) = [real(ct%own_contact(o), rk), xo(:, o)]
          fill = fill + 4
        end do
      end do
      call par_exchange_counts(scount, rcount)
      call par_exchange(sbuf, scount, rbuf, rcount)
      n = sum(rcount) / 4
      ! (a contact index is exact in a double)
      key = [(int(rbuf(4 * j - 3), i8), j = 1, n)]
      call sort_order(key, order)
      near%c = int(key(order))
      if (allocated(near%x)) deallocate(near%x)
      allocate(near%x(3, n))
      do j = 1, n
        near%x(:, j) = rbuf(4 * order(j) - 2:4 * order(j))
      end do
      meas = spans()
      call par_max_array(meas)
      if (meas(2) == 0.0_rk .and. reach + 2.0_rk * meas(1) <= h) exit
      h = max(2.0_rk * h, reach + SPAN_WIDENING * meas(1))
    end do
    ct%audit_span = meas(1)

  contains

    !> The boxes of this rank's owned nodes of one surface: split where
    !> the nodes leave a gap wider than 2 h along an axis (separate bodies,
    !> separate pieces of one body), so no box spans the space between.
    subroutine side_boxes(surf)
      type(contact_surface_t), intent(in) :: surf
      integer, allocatable :: list(:)
      integer :: m
      allocate(list(ct%nown))
      m = 0
      do o = 1, ct%nown
        if (surface_node_index(surf, ct%own_contact(o)) == 0) cycle
        m = m + 1
        list(m) = o
      end do
      if (m > 0) call split(list(1:m))
    end subroutine side_boxes

    !> One box around the owned nodes list, or (a gap along an axis, and
    !> room for more boxes) the boxes of the two sides of the gap.
    recursive subroutine split(list)
      integer, intent(in) :: list(:)
      integer, allocatable :: ord(:)
      integer :: d, i, b
      if (nbox < MAX_BOXES - 1) then
        do d = 1, 3
          call sort_order(xo(d, list), ord)
          do i = 1, size(list) - 1
            if (xo(d, list(ord(i + 1))) - xo(d, list(ord(i))) > 2.0_rk * h) then
              call split(list(ord(1:i)))
              call split(list(ord(i + 1:)))
              return
            end if
          end do
        end do
      end if
      if (nbox == MAX_BOXES) then
        b = MAX_BOXES
      else
        nbox = nbox + 1
        b = nbox
      end if
      do i = 1, size(list)
        mine(6 * b - 5:6 * b - 3) = min(mine(6 * b - 5:6 * b - 3), xo(:, list(i)))
        mine(6 * b - 2:6 * b) = min(mine(6 * b - 2:6 * b), -xo(:, list(i)))
      end do
    end subroutine split

    !> Point q within one of a rank's boxes bx widened by h.
    pure logical function inside(q, bx)
      real(rk), intent(in) :: q(3), bx(:)
      integer :: b
      inside = .false.
      do b = 1, size(bx) / 6
        if (all(q >= bx(6 * b - 5:6 * b - 3) - h) .and. all(-q >= bx(6 * b - 2:6 * b) - h)) then
          inside = .true.
          return
        end if
      end do
    end function inside

    !> The largest span of the segments whose first corner this rank owns
    !> (those with every corner here), and 1 when one of them has a corner
    !> that did not arrive.
    function spans() result(m)
      real(rk) :: m(2)
      integer :: k
      m = 0.0_rk
      do k = 1, ct%ndeck
        call surface_spans(ct%pairs(k)%all_a, m)
        call surface_spans(ct%pairs(k)%all_b, m)
      end do
    end function spans

    subroutine surface_spans(surf, m)
      type(contact_surface_t), intent(in) :: surf
      real(rk), intent(inout) :: m(2)
      integer :: s, a, b, ia, ib
      do s = 1, surf%nseg
        if (owned_index(ct, int(surf%segments(1, s))) == 0) cycle
        do a = 1, 4
          ia = sorted_find(near%c, int(surf%segments(a, s)))
          if (ia == 0) then
            m(2) = 1.0_rk
            exit
          end if
          do b = 1, a - 1
            ib = sorted_find(near%c, int(surf%segments(b, s)))
            m(1) = max(m(1), norm2(near%x(:, ia) - near%x(:, ib)))
          end do
        end do
      end do
    end subroutine surface_spans

  end subroutine near_nodes

  !> The segments of a whole surface whose corners are all near, as a
  !> surface numbered by near index, in the whole surface's order (so its
  !> node -> segment lists and neighbours are the whole surface's wherever
  !> every segment around a node is there).
  subroutine near_surface(surf, near, sub)
    type(contact_surface_t), intent(in) :: surf
    type(near_t), intent(in) :: near
    type(contact_surface_t), intent(inout) :: sub
    integer(ik), allocatable :: segs(:, :)
    integer, allocatable :: list(:)
    integer :: s, k, n, j(4), pass
    ! (counted first: nothing here is sized by the whole surface)
    do pass = 1, 2
      n = 0
      do s = 1, surf%nseg
        do k = 1, 4
          j(k) = sorted_find(near%c, int(surf%segments(k, s)))
          if (j(k) == 0) exit
        end do
        if (k <= 4) cycle
        n = n + 1
        if (pass == 1) cycle
        segs(:, n) = int(j, ik)
        list(n) = s
      end do
      if (pass == 1) allocate(segs(4, n), list(n))
    end do
    call surface_from_segments(segs, surf%segment_id(list), surf=sub)
  end subroutine near_surface

  !> The boxes (lower and upper corners) of every deck interface's whole
  !> surfaces a and b at x: each rank's owned nodes, one reduction.
  !> (3, 2, 2, ndeck): corner, lower/upper, side a/b, interface. Collective.
  function surface_boxes(ct, x) result(boxes)
    type(contact_t), intent(in) :: ct
    real(rk), intent(in) :: x(:, :) !< (3, nnode local)
    real(rk), allocatable :: boxes(:, :, :, :)
    real(rk), allocatable :: v(:)
    integer :: k, o, c, base
    allocate(v(12 * ct%ndeck), boxes(3, 2, 2, ct%ndeck))
    v = huge(1.0_rk)
    do k = 1, ct%ndeck
      do o = 1, ct%nown
        c = ct%own_contact(o)
        base = 12 * (k - 1)
        if (surface_node_index(ct%pairs(k)%all_a, c) > 0) call widen(base)
        if (surface_node_index(ct%pairs(k)%all_b, c) > 0) call widen(base + 6)
      end do
    end do
    ! (the upper corners as minima of the negated coordinates: one reduction)
    call par_min_array(v)
    do k = 1, ct%ndeck
      base = 12 * (k - 1)
      boxes(:, 1, 1, k) = v(base + 1:base + 3)
      boxes(:, 2, 1, k) = -v(base + 4:base + 6)
      boxes(:, 1, 2, k) = v(base + 7:base + 9)
      boxes(:, 2, 2, k) = -v(base + 10:base + 12)
    end do
  contains
    subroutine widen(b)
      integer, intent(in) :: b
      v(b + 1:b + 3) = min(v(b + 1:b + 3), x(:, ct%own_local(o)))
      v(b + 4:b + 6) = min(v(b + 4:b + 6), -x(:, ct%own_local(o)))
    end subroutine widen
  end function surface_boxes

  !> Per node of a surface numbered by near index, whether this rank owns it.
  function owned_nodes(ct, near, surf) result(owned)
    type(contact_t), intent(in) :: ct
    type(near_t), intent(in) :: near
    type(contact_surface_t), intent(in) :: surf
    logical, allocatable :: owned(:)
    integer :: i
    allocate(owned(surf%nnode))
    do i = 1, surf%nnode
      owned(i) = owned_index(ct, near%c(surf%nodes(i))) > 0
    end do
  end function owned_nodes

  !> The audit of both sides of deck interface k at the near positions,
  !> with the given offsets of the owned nodes (absent: zero): the
  !> surfaces (the whole ones on one rank, the near parts otherwise), the
  !> owned nodes of each, and each side's audit. Side b is not audited in
  !> self-contact.
  subroutine audit_interface(ct, near, boxes, k, with_offsets, sa, sb, sel_a, sel_b, ra, rb)
    type(contact_t), intent(in) :: ct
    type(near_t), intent(in) :: near
    real(rk), intent(in) :: boxes(:, :, :, :) !< surface_boxes (unread on one rank)
    integer, intent(in) :: k
    logical, intent(in) :: with_offsets
    type(contact_surface_t), intent(inout) :: sa, sb
    logical, allocatable, intent(out) :: sel_a(:), sel_b(:)
    type(side_t), intent(out) :: ra, rb
    associate(p => ct%pairs(k))
      if (near%all) then
        sel_a = owned_nodes(ct, near, p%all_a)
        sel_b = owned_nodes(ct, near, p%all_b)
        call audit_side(near%x, p%all_a, p%all_b, p%self, p%reach, &
            p%spec%penetration_tolerance, offsets_of(p%all_a), sel_a, ct%planes, ra)
        if (.not. p%self) call audit_side(near%x, p%all_b, p%all_a, .false., p%reach, &
            p%spec%penetration_tolerance, offsets_of(p%all_b), sel_b, ct%planes, rb)
      else
        call near_surface(p%all_a, near, sa)
        call near_surface(p%all_b, near, sb)
        sel_a = owned_nodes(ct, near, sa)
        sel_b = owned_nodes(ct, near, sb)
        call audit_side(near%x, sa, sb, p%self, p%reach, p%spec%penetration_tolerance, &
            offsets_of(sa), sel_a, ct%planes, ra, boxes(:, :, 2, k))
        if (.not. p%self) call audit_side(near%x, sb, sa, .false., p%reach, &
            p%spec%penetration_tolerance, offsets_of(sb), sel_b, ct%planes, rb, &
            boxes(:, :, 1, k))
      end if
    end associate
  contains
    !> The interface's offsets of the owned nodes of a surface, by surface
    !> node (zero on the others, which the audit does not read).
    function offsets_of(surf) result(off)
      type(contact_surface_t), intent(in) :: surf
      real(rk), allocatable :: off(:)
      integer :: n, o
      allocate(off(surf%nnode))
      off = 0.0_rk
      if (.not. with_offsets) return
      do n = 1, surf%nnode
        o = owned_index(ct, near%c(surf%nodes(n)))
        if (o > 0) off(n) = ct%pairs(k)%offset(o)
      end do
    end function offsets_of
  end subroutine audit_interface

  !> Each owned contact node's penetration of the other side of each deck
  !> interface at x (the deeper of its depths on sides a and b, zero
  !> outside), with the nodes' global ids (ascending): what a refresh
  !> compares before and after (contact_refresh_offsets; a refresh keeps
  !> each node's mesh owner). Collective.
  subroutine contact_depths(ct, x, gid, depth)
    type(contact_t), intent(inout) :: ct
    real(rk), intent(in) :: x(:, :) !< (3, nnode local) positions now
    integer(i8), allocatable, intent(out) :: gid(:) !< (nown) global ids
    real(rk), allocatable, intent(out) :: depth(:, :) !< (nown, ndeck)
    type(near_t) :: near
    type(contact_surface_t) :: sa, sb
    real(rk), allocatable :: boxes(:, :, :, :)
    logical, allocatable :: sel_a(:), sel_b(:)
    type(side_t) :: ra, rb
    integer :: k

    allocate(gid(ct%nown), depth(ct%nown, ct%ndeck))
    gid = ct%all_gid(ct%own_contact)
    depth = 0.0_rk
    if (ct%npair == 0) return
    call near_nodes(ct, x, near)
    allocate(boxes(3, 2, 2, ct%ndeck))
    if (.not. near%all) boxes = surface_boxes(ct, x)
    do k = 1, ct%ndeck
      call audit_interface(ct, near, boxes, k, .false., sa, sb, sel_a, sel_b, ra, rb)
      call deepen(ct%pairs(k)%all_a, sa, sel_a, ra)
      if (.not. ct%pairs(k)%self) call deepen(ct%pairs(k)%all_b, sb, sel_b, rb)
    end do
  contains
    subroutine deepen(whole, part, sel, side)
      type(contact_surface_t), intent(in) :: whole, part
      logical, intent(in) :: sel(:)
      type(side_t), intent(in) :: side
      integer :: i, o
      do i = 1, size(sel)
        if (.not. sel(i)) cycle
        if (near%all) then
          o = owned_index(ct, near%c(whole%nodes(i)))
        else
          o = owned_index(ct, near%c(part%nodes(i)))
        end if
        depth(o, k) = max(depth(o, k), side%pen(i))
      end do
    end subroutine deepen
  end subroutine contact_depths

  !> After a refresh, at the same positions x as contact_depths took gid and
  !> depth before it: each node's offset follows the change of its depth
  !> that the new surfaces made, offset + depth now - depth before (a node
  !> that joined had none), and not less than zero. An erosion exposes
  !> faces that can lie inside the other body already (the eroded zone was
  !> between them), or takes away the face a node was held against; that
  !> depth is not the contact's to remove. Pushed out by the recovery, over
  !> a few steps, it would be put back at many times the impact's speed
  !> and put energy into the run; the contact holds it where it is and
  !> stops it going deeper, as the set-up keeps an initial overlap under
  !> 'ignore'. The audit measures beyond these offsets. Collective.
  subroutine contact_refresh_offsets(ct, x, gid, depth)
    type(contact_t), intent(inout) :: ct
    real(rk), intent(in) :: x(:, :) !< (3, nnode local) positions now
    integer(i8), intent(in) :: gid(:) !< contact_depths before the refresh
    real(rk), intent(in) :: depth(:, :) !< contact_depths before the refresh
    integer(i8), allocatable :: gid_now(:)
    real(rk), allocatable :: depth_now(:, :)
    real(rk) :: before
    integer :: k, c, o
    if (ct%npair == 0) return
    call contact_depths(ct, x, gid_now, depth_now)
    do k = 1, ct%ndeck
      associate(p => ct%pairs(k))
        do o = 1, ct%nown
          c = sorted_find(gid, gid_now(o))
          before = 0.0_rk
          if (c > 0) before = depth(c, k)
          p%offset(o) = max(p%offset(o) + depth_now(o, k) - before, 0.0_rk)
        end do
      end associate
    end do
    do k = ct%ndeck + 1, ct%npair
      if (ct%pairs(k)%mirror_of > 0) ct%pairs(k)%offset = ct%pairs(ct%pairs(k)%mirror_of)%offset
    end do
  end subroutine contact_refresh_offsets

  !> The audit of every interface at positions x (local mesh nodes; the
  !> owned ones are read): history columns, the per-node smallest gap for
  !> the dumps, a rate-limited warning, and ct%stop_run for on_penetration =
  !> 'stop'. Collective.
  subroutine contact_audit_run(ct, x, cycle, time)
    type(contact_t), intent(inout) :: ct
    real(rk), intent(in) :: x(:, :)
    integer(i8), intent(in) :: cycle
    real(rk), intent(in) :: time
    real(rk), allocatable :: rec(:), all(:, :), boxes(:, :, :, :)
    type(near_t) :: near
    type(contact_surface_t) :: sa, sb
    type(side_t) :: ra, rb
    logical, allocatable :: sel_a(:), sel_b(:)
    real(rk) :: sums(4), worst(2), deep
    integer :: k, i, c, o, r, unheld, deep_node
    character(len=600) :: text

    if (ct%npair == 0) return
    call near_nodes(ct, x, near)
    allocate(boxes(3, 2, 2, ct%ndeck))
    if (.not. near%all) boxes = surface_boxes(ct, x)
    ct%gap_own = huge(1.0_rk)
    allocate(rec(6), all(6, par_size()))
    ! The deck's interfaces (a reverse pass audits nothing of its own).
    do k = 1, ct%ndeck
      associate(p => ct%pairs(k))
        call audit_interface(ct, near, boxes, k, .true., sa, sb, sel_a, sel_b, ra, rb)
        worst = 0.0_rk
        sums = 0.0_rk
        unheld = 0
        deep = -1.0_rk
        deep_node = 0
        do i = 1, size(sel_a)
          if (.not. sel_a(i)) cycle
          c = contact_of(p%all_a, sa, i)
          o = owned_index(ct, c)
          ct%gap_own(o) = min(ct%gap_own(o), ra%gap(i))
          worst(1) = max(worst(1), ra%pen(i))
          if (ra%pen(i) > ra%tol(i)) then
            sums(1) = sums(1) + 1.0_rk
            if (.not. p%was_active(o)) sums(3) = sums(3) + 1.0_rk
            call deeper(ra%pen(i), c)
          end if
        end do
        if (.not. p%self) then
          do i = 1, size(sel_b)
            if (.not. sel_b(i)) cycle
            c = contact_of(p%all_b, sb, i)
            o = owned_index(ct, c)
            ct%gap_own(o) = min(ct%gap_own(o), rb%gap(i))
            worst(2) = max(worst(2), rb%pen(i))
            if (rb%pen(i) > rb%tol(i)) then
              sums(2) = sums(2) + 1.0_rk
              if (held_b(p, o)) cycle
              sums(3) = sums(3) + 1.0_rk
              call deeper(rb%pen(i), c)
            end if
          end do
        end if
        call par_sum_array(sums)
        ! The deepest violation over the ranks (ties to the lower node).
        rec = [deep, real(deep_node, rk), 0.0_rk, 0.0_rk, 0.0_rk, worst(1)]
        if (deep_node > 0) rec(3:5) = x(:, ct%own_local(owned_index(ct, deep_node)))
        call par_allgather(rec, all)
        worst(1) = maxval(all(6, :))
        rec(6) = worst(2)
        call par_allgather(rec, all)
        worst(2) = maxval(all(6, :))
        r = 0
        do i = 1, par_size()
          if (all(1, i) < 0.0_rk) cycle
          if (r == 0) then
            r = i
          else if (all(1, i) > all(1, r) .or. (all(1, i) == all(1, r) .and. &
              all(2, i) < all(2, r))) then
            r = i
          end if
        end do
        if (p%self) then
          worst(2) = worst(1)
          sums(2) = sums(1)
        end if
        p%diag(DIAG_AUDIT:DIAG_AUDIT + 4) = [worst(1), worst(2), sums(1), sums(2), sums(3)]
        if (r > 0) call violation(p, p%spec%name, all(:, r), nint(sums(1) + sums(2)))
        deallocate(sel_a, sel_b)
      end associate
    end do
    where (ct%gap_own == huge(1.0_rk)) ct%gap_own = 0.0_rk
    ct%node_gap = 0.0_rk
    ct%node_gap(ct%own_local) = ct%gap_own
    ct%audit_due = .false.
    ct%audited_cycle = cycle
    ct%audits = ct%audits + 1

  contains

    !> Contact index of node i of the audited surface: the whole surface's
    !> (one rank) or its near part's.
    integer function contact_of(whole, part, i) result(cc)
      type(contact_surface_t), intent(in) :: whole, part
      integer, intent(in) :: i
      if (near%all) then
        cc = near%c(whole%nodes(i))
      else
        cc = near%c(part%nodes(i))
      end if
    end function contact_of

    !> Whether a penetrating node of surface b (owned node o) counts as held:
    !> a method that enforces surface b's nodes (DLM), or a reverse pass,
    !> holds such a node when it carried a force in the last corrector; one
    !> that enforces a's nodes only (DAM's one pass) reports a master node in
    !> the side-b columns and not as unheld.
    logical function held_b(p, o)
      type(interface_t), intent(in) :: p
      integer, intent(in) :: o
      if (p%method%enforces_b()) then
        held_b = p%was_active(o)
      else if (p%mirror > 0) then
        held_b = ct%pairs(p%mirror)%was_active(o)
      else
        held_b = .true.
      end if
    end function held_b

    subroutine deeper(pen, node)
      real(rk), intent(in) :: pen
      integer, intent(in) :: node
      if (pen > deep .or. (pen == deep .and. node < deep_node)) then
        deep = pen
        deep_node = node
      end if
    end subroutine deeper

    !> A violation: a warning at most once per WARN_EVERY cycles (with the
    !> count since the last one), or the stop request.
    subroutine violation(p, name, worst_rec, nodes)
      type(interface_t), intent(inout) :: p
      character(len=*), intent(in) :: name
      real(rk), intent(in) :: worst_rec(6)
      integer, intent(in) :: nodes
      integer(i8) :: gid
      gid = ct%all_gid(nint(worst_rec(2)))
      if (p%spec%on_penetration == 'stop') then
        ct%stop_run = .true.
        if (par_rank() == 0) then
          write(text, '(a,i0,a,i0,a,3es13.5,a,es10.3,a,i0,a,es12.5)') &
              'error: &contact '''//trim(name)//''': ', nodes, &
              ' node(s) penetrate beyond the tolerance (on_penetration = ''stop''); the '// &
              'deepest, node ', gid, ' at (', worst_rec(3:5), '), by ', worst_rec(1), &
              ', in cycle ', cycle, ', time ', time
          write(error_unit, '(a)') trim(text)
          flush(error_unit)
        end if
        return
      end if
      p%warn_skipped = p%warn_skipped + 1
      if (cycle - p%warn_cycle < WARN_EVERY) return
      if (par_rank() == 0) then
        write(text, '(a,i0,a,i0,a,3es13.5,a,es10.3,a,i0,a,es12.5,a,i0,a)') &
            'warning: &contact '''//trim(name)//''': ', nodes, &
            ' node(s) penetrate beyond the tolerance; the deepest, node ', gid, ' at (', &
            worst_rec(3:5), '), by ', worst_rec(1), ', cycle ', cycle, ', t = ', time, &
            ' (', p%warn_skipped, ' audit(s) with violations since the last warning)'
        write(error_unit, '(a)') trim(text)
        flush(error_unit)
      end if
      p%warn_cycle = cycle
      p%warn_skipped = 0
    end subroutine violation

  end subroutine contact_audit_run

  !> An audit is due at the end of this cycle: a global search ran since the
  !> last one, or the caller's schedule asks (a dump). Never without an
  !> interface.
  logical function contact_audit_due(ct, scheduled) result(due)
    type(contact_t), intent(in) :: ct
    logical, intent(in) :: scheduled
    due = ct%npair > 0 .and. (ct%audit_due .or. scheduled)
  end function contact_audit_due

  !> End of a step: the contact work of the step, and per interface the
  !> contact force on surface a and the work of the step (summed over the
  !> ranks) into the history columns. Collective; nothing without an
  !> interface.
  subroutine contact_step_end(ct, work)
    type(contact_t), intent(inout) :: ct
    real(rk), intent(in) :: work !< the contact work of the step, summed over the ranks
    type(exact_sum_t), allocatable :: sums(:)
    integer :: k, i, m, j
    if (ct%npair == 0) return
    ct%work = ct%work + work
    ! Exact sums (core_exact_sum): the columns do not depend on the rank count.
    allocate(sums(4 * ct%npair))
    do k = 1, ct%npair
      associate(p => ct%pairs(k))
        ! A reverse pass's surface a is its deck interface's surface b.
        do i = 1, ct%nown
          if (p%own_in_a(i) .eqv. p%mirror_of == 0) then
            do j = 1, 3
              call sums(4 * k - 4 + j)%add(p%fc_own(j, i))
            end do
          end if
        end do
        sums(4 * k) = p%work_step
      end associate
    end do
    call par_sum_exact(sums)
    do k = 1, ct%npair
      associate(p => ct%pairs(k))
        p%work = p%work + exact_value(sums(4 * k))
        do j = 1, 3
          p%diag(DIAG_FORCE + j - 1) = exact_value(sums(4 * k - 4 + j))
        end do
        p%diag(DIAG_WORK) = p%work
      end associate
    end do
    ! DAM's reverse passes in their deck interface's columns: the enforced
    ! pairs, forces, momentum and work add up; the largest penetration is
    ! the larger, the RMS over both passes' penetrating nodes. Released
    ! nodes are the first pass's: where it holds the two sides the second
    ! has nothing to do, and whether it enforces a node then flips with the
    ! round-off of a zero gap, which is no release.
    do k = 1, ct%ndeck
      m = ct%pairs(k)%mirror
      if (m == 0) cycle
      associate(p => ct%pairs(k), r => ct%pairs(m))
        p%diag(1:2) = p%diag(1:2) + r%diag(1:2)
        p%diag(3) = max(p%diag(3), r%diag(3))
        p%diag(4) = sqrt((p%pen_sq + r%pen_sq) / max(p%pen_weight + r%pen_weight, 1.0_rk))
        p%diag(6:8) = p%diag(6:8) + r%diag(6:8)
        p%diag(DIAG_FORCE:DIAG_FORCE + 2) = p%diag(DIAG_FORCE:DIAG_FORCE + 2) + &
            r%diag(DIAG_FORCE:DIAG_FORCE + 2)
        p%diag(DIAG_WORK) = p%work + r%work
      end associate
    end do
  end subroutine contact_step_end

end module contact_monitor
