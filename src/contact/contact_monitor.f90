!> Contact monitoring: the geometric penetration audit (contact_audit) run on
!> the whole contact surfaces at set-up (initial penetration: error, adjust
!> or ignore), at every global search and at every dump; the per-interface
!> force and work of each step; and the warning policy (on_penetration).
!>
!> The audit reads positions only. Every rank holds every contact node's
!> position (one sum over the ranks per audit) and audits the nodes it owns
!> against the whole opposite surface, so each node's gap, and so the
!> maxima and counts, are the same on any number of ranks.
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
  use core_sort, only: sort_unique, sorted_find
  use contact_surface, only: contact_surface_t, surface_renumbered
  use contact_audit, only: audit_gaps, segment_sizes, node_tolerance, audit_reach
  use contact_state, only: contact_spec_t, interface_t, contact_t, contact_method_t, &
      initial_offsets_t, DIAG_FORCE, DIAG_WORK, DIAG_AUDIT, SURFACE_LEN, owned_index
  use contact_factory, only: contact_method_new
  use contact_sides, only: side_context_t, side_surface
  use mesh_local, only: mesh_t
  use parallel_env, only: par_sum_array, par_sum_exact, par_rank, par_size, par_allgather
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

contains

  !> The audit of one side: gaps of the selected nodes of `own` against
  !> `other`, penetration beyond the offsets, and each node's tolerance.
  subroutine audit_side(x, own, other, self, reach, tol_fixed, offset, selected, planes, side)
    real(rk), intent(in) :: x(:, :)
    type(contact_surface_t), intent(in) :: own, other
    logical, intent(in) :: self
    real(rk), intent(in) :: reach, tol_fixed
    real(rk), intent(in) :: offset(:) !< (own%nnode)
    logical, intent(in) :: selected(:) !< (own%nnode)
    real(rk), intent(in) :: planes(:, :) !< (4, n) symmetry planes (contact_audit)
    type(side_t), intent(out) :: side
    real(rk), allocatable :: osz(:), tsz(:), tsag(:)
    real(rk) :: hmin
    integer :: i, e, n
    n = own%nnode
    allocate(side%gap(n), side%pen(n), side%tol(n), side%inward(3, n), side%hit(n))
    ! (the target's sizes and sagittas from audit_gaps, which computes them;
    ! of the own side only the sizes)
    call audit_gaps(x, own, other, self, reach, selected, side%gap, side%hit, side%inward, &
        planes, tsz, tsag)
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


  !> The audit of every interface at positions x (local mesh nodes; the
  !> owned ones are read): history columns, the per-node smallest gap for
  !> the dumps, a rate-limited warning, and ct%stop_run for on_penetration =
  !> 'stop'. Collective.
  !> Every contact node's position, on every rank: the owners' positions
  !> summed (one owner each, zero elsewhere: exact). Collective.
  function positions_everywhere(ct, x) result(xall)
    type(contact_t), intent(in) :: ct
    real(rk), intent(in) :: x(:, :) !< (3, nnode local)
    real(rk), allocatable :: xall(:, :)
    real(rk), allocatable :: flat(:)
    integer :: i, c
    allocate(flat(3 * ct%nall))
    flat = 0.0_rk
    do i = 1, ct%nown
      c = ct%own_contact(i)
      flat(3 * c - 2:3 * c) = x(:, ct%own_local(i))
    end do
    call par_sum_array(flat)
    xall = reshape(flat, [3, ct%nall])
  end function positions_everywhere

  !> Per node of a global surface, whether this rank owns it.
  function owned_nodes(ct, surf) result(owned)
    type(contact_t), intent(in) :: ct
    type(contact_surface_t), intent(in) :: surf
    logical, allocatable :: owned(:)
    integer :: i
    allocate(owned(surf%nnode))
    do i = 1, surf%nnode
      owned(i) = owned_index(ct, surf%nodes(i)) > 0
    end do
  end function owned_nodes

  !> Every contact node's penetration of the other side of each deck
  !> interface at x (the deeper of its depths on sides a and b, zero
  !> outside), on every rank, with the nodes' global ids: what a refresh
  !> compares before and after (contact_refresh_offsets). Collective.
  subroutine contact_depths(ct, x, gid, depth)
    type(contact_t), intent(in) :: ct
    real(rk), intent(in) :: x(:, :) !< (3, nnode local) positions now
    integer(i8), allocatable, intent(out) :: gid(:) !< (nall) global ids
    real(rk), allocatable, intent(out) :: depth(:, :) !< (nall, ndeck)
    real(rk), allocatable :: xall(:, :), zero_a(:), zero_b(:)
    logical, allocatable :: sel_a(:), sel_b(:)
    type(side_t) :: ra, rb
    integer :: k, i

    allocate(gid(ct%nall), depth(ct%nall, ct%ndeck))
    gid = ct%all_gid
    depth = 0.0_rk
    if (ct%npair == 0) return
    xall = positions_everywhere(ct, x)
    do k = 1, ct%ndeck
      associate(p => ct%pairs(k))
        sel_a = owned_nodes(ct, p%all_a)
        sel_b = owned_nodes(ct, p%all_b)
        allocate(zero_a(p%all_a%nnode), zero_b(p%all_b%nnode))
        zero_a = 0.0_rk
        zero_b = 0.0_rk
        call audit_side(xall, p%all_a, p%all_b, p%self, p%reach, &
            p%spec%penetration_tolerance, zero_a, sel_a, ct%planes, ra)
        do i = 1, p%all_a%nnode
          if (sel_a(i)) depth(p%all_a%nodes(i), k) = max(depth(p%all_a%nodes(i), k), ra%pen(i))
        end do
        if (.not. p%self) then
          call audit_side(xall, p%all_b, p%all_a, .false., p%reach, &
              p%spec%penetration_tolerance, zero_b, sel_b, ct%planes, rb)
          do i = 1, p%all_b%nnode
            if (sel_b(i)) depth(p%all_b%nodes(i), k) = max(depth(p%all_b%nodes(i), k), &
                rb%pen(i))
          end do
        end if
        ! (one owner each, zero elsewhere: the sums are the owners' values)
        call par_sum_array(depth(:, k))
        deallocate(sel_a, sel_b, zero_a, zero_b)
      end associate
    end do
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
    integer :: k, i, c, o
    if (ct%npair == 0) return
    call contact_depths(ct, x, gid_now, depth_now)
    do k = 1, ct%ndeck
      associate(p => ct%pairs(k))
        do o = 1, ct%nown
          i = ct%own_contact(o)
          c = sorted_find(gid, gid_now(i))
          before = 0.0_rk
          if (c > 0) before = depth(c, k)
          p%offset(o) = max(p%offset(o) + depth_now(i, k) - before, 0.0_rk)
        end do
      end associate
    end do
    do k = ct%ndeck + 1, ct%npair
      if (ct%pairs(k)%mirror_of > 0) ct%pairs(k)%offset = ct%pairs(ct%pairs(k)%mirror_of)%offset
    end do
  end subroutine contact_refresh_offsets

  subroutine contact_audit_run(ct, x, cycle, time)
    type(contact_t), intent(inout) :: ct
    real(rk), intent(in) :: x(:, :)
    integer(i8), intent(in) :: cycle
    real(rk), intent(in) :: time
    real(rk), allocatable :: xall(:, :), rec(:), all(:, :)
    type(side_t) :: ra, rb
    logical, allocatable :: sel_a(:), sel_b(:)
    real(rk) :: sums(4), worst(2), deep
    integer :: k, i, c, o, r, unheld, deep_node
    character(len=600) :: text

    if (ct%npair == 0) return
    xall = positions_everywhere(ct, x)
    ct%gap_own = huge(1.0_rk)
    allocate(rec(6), all(6, par_size()))
    ! The deck's interfaces (a reverse pass audits nothing of its own).
    do k = 1, ct%ndeck
      associate(p => ct%pairs(k))
        sel_a = owned_nodes(ct, p%all_a)
        sel_b = owned_nodes(ct, p%all_b)
        call audit_side(xall, p%all_a, p%all_b, p%self, p%reach, &
            p%spec%penetration_tolerance, owned_offsets(p%all_a), sel_a, ct%planes, ra)
        if (.not. p%self) call audit_side(xall, p%all_b, p%all_a, .false., p%reach, &
            p%spec%penetration_tolerance, owned_offsets(p%all_b), sel_b, ct%planes, rb)
        worst = 0.0_rk
        sums = 0.0_rk
        unheld = 0
        deep = -1.0_rk
        deep_node = 0
        do i = 1, p%all_a%nnode
          if (.not. sel_a(i)) cycle
          c = p%all_a%nodes(i)
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
          do i = 1, p%all_b%nnode
            if (.not. sel_b(i)) cycle
            c = p%all_b%nodes(i)
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
        if (deep_node > 0) rec(3:5) = xall(:, deep_node)
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

    !> The interface's offsets of the owned nodes of a surface, by surface
    !> node (zero on the others, which the audit does not read).
    function owned_offsets(surf) result(off)
      type(contact_surface_t), intent(in) :: surf
      real(rk), allocatable :: off(:)
      integer :: n, o
      allocate(off(surf%nnode))
      off = 0.0_rk
      do n = 1, surf%nnode
        o = owned_index(ct, surf%nodes(n))
        if (o > 0) off(n) = ct%pairs(k)%offset(o)
      end do
    end function owned_offsets

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
