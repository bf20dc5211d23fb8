!> Contact enforcement: the driver of DAM (discrete accurate matching,
!> master-slave; contact_dam) and DLM (discrete Lagrangian multiplier,
!> symmetric; contact_dlm) of Jia, Gong, Zhang & Liu (J. Comput. Phys. 267
!> (2014) 247-285), as described in docs/contact.md, sections 5-6: set-up,
!> the rounds of a stage (search, migration, the methods on the RCB parts,
!> the owners' sums) and the diagnostics. This is the narrow interface
!> between the hydro state and contact. The methods are types
!> (contact_method_t, made by contact_factory): this driver runs their
!> rounds and never asks which method it runs. Set-up and
!> contact_surface_refresh (surfaces given by blocks, rebuilt from the live
!> zones) share index_surfaces, the contact index space.
!>
!> Where it sits. In each stage, after the hydro forces f of the stage are
!> known and before v = v^n + h (f + fc)/m (h = dt/2 in the predictor, dt in
!> the corrector): contact_apply returns the contact force fc of every owned
!> contact node, added to the node force, so the boundary conditions
!> re-imposed by the velocity update come after it. The original plan put
!> contact in the corrector only; the rigid wall acts in both stages, and a
!> contact that skips the predictor lets the half-step geometry interpenetrate,
!> so the contact pressure lags half a step and the mirror test fails (2e-3 of
!> the body size on a Taylor rod). The global search, when due, and the
!> geometry at x^n run in the predictor's call; the corrector reuses them, and
!> only the corrector's forces do work and give the diagnostics
!> (docs/contact.md, section 4).
!> Both methods are expressed as a contact force: DLM's pair forces directly,
!> DAM's corrected velocities v' as fc = m (v' - v^n)/dt - f. The work of the
!> contact forces over the step (trapezoid velocity) is the contact work of
!> the energy balance.
!>
!> Parallel contact by RCB: see contact_parts (the search on the parts, the
!> local sets and the migration plan) and contact_records (the ordered sums).
!>
!> Contact index space. The nodes of all contact surfaces, sorted by global
!> id, are numbered 1..nall (the global surfaces all_a, all_b use it); the
!> local set of a part is numbered 1..ncn in the same order, and its
!> surfaces a, b and pair lists use local numbers, so the order of every loop
!> follows global ids.
!>
!> Closing condition (both methods, docs/contact.md section 4). A pair is
!> enforced when the free motion (hydro forces only) would close its gap by
!> the end of the step: pen_free = pen + dt w + dt^2/2 (ah - ad) > 0, w the
!> approach velocity and ah - ad the relative free acceleration along the
!> normal. Otherwise the pair is released (tension, or opening faster than the
!> other side follows). The same rule gives release and re-contact in DAM and
!> DLM.
!>
module contact_enforce
  use core_kinds, only: rk, ik, i8
  use core_exact_sum, only: exact_sum_t
  use core_status, only: status_t
  use core_sort, only: sort_values, sort_unique
  use, intrinsic :: iso_fortran_env, only: output_unit
  use mesh_local, only: mesh_t
  use contact_surface, only: contact_surface_t, surface_build, surface_from_segments, &
      surface_node_index, set_names_of, surface_relabelled
  use contact_records, only: records_t, take, send_records
  use contact_search, only: find_key
  use contact_state, only: RIGID_MASS_FACTOR, CONTACT_DIAG_COUNT, CONTACT_DIAG_NAMES, &
      SURFACE_LEN, contact_spec_t, surface_geometry_t, selection_t, contact_t, &
      initial_offsets_t, step_sums_t, contact_method_t, method_slot_t, DIAG_AUDIT
  use contact_audit, only: surface_sagitta, audit_reach
  use contact_factory, only: contact_method_new
  use contact_impact, only: impact_step_limit, IMPACT_FLOOR
  use contact_sides, only: side_context_t, side_surface, side_is_blocks, blocks_of, block_faces
  use contact_parts, only: segment_homes, contact_rebuild, contact_localize, gather_nodes, &
      scatter_nodes, directory_build
  use parallel_env, only: par_sum_array, par_min, par_max, par_max_array, par_rank, par_size, &
      par_sum_in_place
  implicit none
  private
  public :: contact_setup, contact_apply, contact_work_update, contact_surface_refresh
  public :: contact_report, contact_active_flags, contact_active_restore
  public :: contact_resume_state, contact_resume, contact_offset_values, contact_offset_restore
  ! The state the application and the deck reader see.
  public :: CONTACT_DIAG_COUNT, CONTACT_DIAG_NAMES, SURFACE_LEN, contact_spec_t, contact_t
  public :: side_context_t

  !> Per-node values of the owners' last round, on this part (ncn).
  type :: inflow_t
    real(rk), allocatable :: v(:, :, :)
  end type inflow_t

contains

  !> Build the contact surfaces in contact-index space, the owned-node map and
  !> the nodal masses. Problems go to status (group, key, reason).
  subroutine contact_setup(specs, mesh, x, node_mass, ct, status, offsets, planes, &
      rigid, context)
    type(contact_spec_t), intent(in) :: specs(:)
    type(mesh_t), intent(in) :: mesh
    real(rk), intent(in) :: x(:, :) !< (3, nnode local) node positions
    real(rk), intent(in) :: node_mass(:) !< (nnode local) nodal masses
    type(contact_t), intent(inout) :: ct
    type(status_t), intent(inout) :: status
    !> initial penetration kept per surface node (contact_initial); none: zero
    type(initial_offsets_t), intent(in), optional :: offsets(:)
    !> (4, n) the deck's symmetry planes (unit normal, offset) for the audit
    real(rk), intent(in), optional :: planes(:, :)
    !> (nnode local) nodes whose motion is prescribed: rigid for the contact
    logical, intent(in), optional :: rigid(:)
    !> the deck's blocks and closed face sets, for surfaces given by blocks
    type(side_context_t), intent(in), optional :: context
    type(side_context_t) :: sides
    type(contact_surface_t), allocatable :: raw_a(:), raw_b(:)
    integer :: k, m
    character(len=SURFACE_LEN) :: side_a, side_b
    type(method_slot_t), allocatable :: methods(:)
    logical, allocatable :: single(:)

    if (present(planes)) then
      ct%planes = planes
    else
      allocate(ct%planes(4, 0))
    end if
    ct%ndeck = size(specs)
    if (present(context)) then
      sides = context
    else
      allocate(sides%block_names(0), sides%closed_sets(0))
    end if
    ! The methods first: each may add a reverse pass after the deck's.
    allocate(methods(ct%ndeck), single(ct%ndeck))
    ct%npair = ct%ndeck
    do k = 1, ct%ndeck
      call contact_method_new(specs(k), .false., methods(k)%method, single(k))
      if (methods(k)%method%reverse_pass()) ct%npair = ct%npair + 1
    end do
    allocate(ct%pairs(ct%npair), raw_a(ct%npair), raw_b(ct%npair))
    if (ct%npair == 0) return
    m = ct%ndeck
    do k = 1, ct%ndeck
      associate(p => ct%pairs(k))
        p%spec = specs(k)
        p%self = specs(k)%surface_a == specs(k)%surface_b
        p%single_part = single(k)
        call move_alloc(methods(k)%method, p%method)
        ! The method's sides: for DAM, b is the master side.
        call p%method%sides(specs(k), side_a, side_b)
        call side_surface(side_a, side_b, mesh, sides, 'contact '''// &
            trim(specs(k)%name)//'''', raw_a(k), status)
        call side_surface(side_b, side_a, mesh, sides, 'contact '''// &
            trim(specs(k)%name)//'''', raw_b(k), status)
        if (p%method%reverse_pass()) then
          ! The reverse pass: the same interface with the sides swapped.
          m = m + 1
          p%mirror = m
          ct%pairs(m)%spec = p%spec
          ct%pairs(m)%self = p%self
          ct%pairs(m)%mirror_of = k
          call contact_method_new(specs(k), .true., ct%pairs(m)%method, &
              ct%pairs(m)%single_part)
          raw_a(m) = raw_b(k)
          raw_b(m) = raw_a(k)
        end if
      end associate
    end do
    if (.not. status%ok()) return

    call index_surfaces(ct, raw_a, raw_b, mesh, x, node_mass, rigid, offsets=offsets)
    allocate(ct%node_gap(size(node_mass)))
    ct%node_gap = 0.0_rk

  end subroutine contact_setup

  !> Surfaces that change during a run: every deck interface whose sides
  !> name blocks gets them again from the exterior faces of the zones live
  !> now (contact_surface_rebuild on each rank's local mesh; live covers
  !> the ghost zones, refreshed by the caller through the zone halo); sides
  !> given by face sets keep their faces. The contact index space, owned
  !> nodes, segment homes and RCB key nodes follow; each node keeps its
  !> offset (a node that joins has none; contact_refresh_offsets then
  !> measures them); sagittas and reach are taken at
  !> x; a global search and RCB run at the next stage (contact_apply), and
  !> the audit after it. The work of each interface goes on. Collective.
  subroutine contact_surface_refresh(ct, mesh, x, node_mass, live, context, rigid)
    type(contact_t), intent(inout) :: ct
    type(mesh_t), intent(in) :: mesh
    real(rk), intent(in) :: x(:, :) !< (3, nnode local) node positions
    real(rk), intent(in) :: node_mass(:) !< (nnode local)
    logical, intent(in) :: live(:) !< (nzone local) zones live, ghosts included
    type(side_context_t), intent(in) :: context
    logical, intent(in), optional :: rigid(:) !< (nnode local) prescribed motion
    type(contact_surface_t), allocatable :: raw_a(:), raw_b(:)
    type(status_t) :: status
    integer(i8), allocatable :: old_gid(:)
    real(rk), allocatable :: old_offset(:, :)
    character(len=SURFACE_LEN) :: side_a, side_b
    integer :: k, m

    if (ct%npair == 0) return
    allocate(raw_a(ct%npair), raw_b(ct%npair), old_offset(ct%nown, ct%npair))
    do k = 1, ct%ndeck
      associate(p => ct%pairs(k))
        call p%method%sides(p%spec, side_a, side_b)
        call side_raw(side_a, side_b, p%all_a, raw_a(k))
        call side_raw(side_b, side_a, p%all_b, raw_b(k))
        m = p%mirror
        if (m > 0) then
          raw_a(m) = raw_b(k)
          raw_b(m) = raw_a(k)
        end if
      end associate
    end do
    if (.not. status%ok()) error stop 'contact_surface_refresh: the deck''s blocks changed'
    ! Each owned node's offset by global id (the same rank owns it after the
    ! refresh).
    old_gid = ct%all_gid(ct%own_contact)
    do k = 1, ct%npair
      old_offset(:, k) = ct%pairs(k)%offset
    end do
    call forget_index(ct)
    call index_surfaces(ct, raw_a, raw_b, mesh, x, node_mass, rigid, old_gid=old_gid, &
        old_offset=old_offset)
    ! (the offsets then follow the new surfaces: contact_refresh_offsets)
    ct%refreshed = .true.
    ! The next stage searches again on the new surfaces.
    ct%next_search = 0
    if (allocated(ct%all_of)) deallocate(ct%all_of)
    ct%audit_due = .true.

  contains

    !> A side's surface in global node ids: rebuilt from blocks, or as it is.
    subroutine side_raw(list, other, current, raw)
      character(len=*), intent(in) :: list, other
      type(contact_surface_t), intent(in) :: current
      type(contact_surface_t), intent(inout) :: raw
      integer, allocatable :: blocks(:), facing(:)
      integer(i8), allocatable :: ids(:)
      integer(ik), allocatable :: nodes(:, :)
      integer :: i
      if (.not. side_is_blocks(list)) then
        allocate(nodes(4, current%nseg))
        do i = 1, current%nseg
          nodes(:, i) = int(ct%all_gid(current%segments(:, i)), ik)
        end do
        call surface_from_segments(nodes, current%segment_id, surf=raw)
        return
      end if
      call blocks_of(list, context, 'contact refresh', blocks, status)
      allocate(facing(0))
      if (side_is_blocks(other) .and. other /= list) then
        call blocks_of(other, context, 'contact refresh', facing, status)
        facing = pack(facing, [(all(blocks /= facing(i)), i = 1, size(facing))])
      end if
      call block_faces(mesh, live, blocks, facing, context, ids, nodes)
      call surface_from_segments(nodes, ids, surf=raw)
    end subroutine side_raw

  end subroutine contact_surface_refresh

  !> Release what index_surfaces builds (before a refresh builds it again).
  subroutine forget_index(ct)
    type(contact_t), intent(inout) :: ct
    integer :: k
    deallocate(ct%own_contact, ct%own_local, ct%own_mass, ct%own_rigid, ct%dir_gid, &
        ct%dir_owner, ct%fc, ct%gap_own, ct%key_capable)
    do k = 1, ct%npair
      associate(p => ct%pairs(k))
        deallocate(p%was_active, p%offset, p%own_in_a, p%fc_own, p%own_slave)
        call p%all_a%free()
        call p%all_b%free()
      end associate
    end do
  end subroutine forget_index

  !> The contact index space of the interfaces' surfaces raw_a, raw_b
  !> (global node ids): every contact node by global id, the surfaces in it,
  !> the owned nodes, masses, owners and positions (from the owners: x),
  !> segment homes, and the audit's offsets, sagittas (at x) and reach.
  !> offsets: the set-up's initial offsets per surface node; old_gid,
  !> old_offset: a refresh's previous contact nodes and their offsets per
  !> interface. Collective.
  subroutine index_surfaces(ct, raw_a, raw_b, mesh, x, node_mass, rigid, offsets, old_gid, &
      old_offset)
    type(contact_t), intent(inout) :: ct
    !> (moved into the interfaces' whole surfaces: left empty)
    type(contact_surface_t), intent(inout) :: raw_a(:), raw_b(:)
    type(mesh_t), intent(in) :: mesh
    real(rk), intent(in) :: x(:, :), node_mass(:)
    logical, intent(in), optional :: rigid(:)
    type(initial_offsets_t), intent(in), optional :: offsets(:)
    integer(i8), intent(in), optional :: old_gid(:)
    !> (size(old_gid), npair) offsets of old_gid, the owned nodes before a refresh
    real(rk), intent(in), optional :: old_offset(:, :)
    integer(i8), allocatable :: all(:)
    real(rk), allocatable :: xc(:, :)
    integer :: k, n, i, c, count_all

    ! Contact nodes: every node of every surface, by global id.
    count_all = 0
    do k = 1, ct%npair
      count_all = count_all + raw_a(k)%nnode + raw_b(k)%nnode
    end do
    allocate(all(count_all))
    count_all = 0
    do k = 1, ct%npair
      all(count_all + 1:count_all + raw_a(k)%nnode) = int(raw_a(k)%nodes, i8)
      count_all = count_all + raw_a(k)%nnode
      all(count_all + 1:count_all + raw_b(k)%nnode) = int(raw_b(k)%nodes, i8)
      count_all = count_all + raw_b(k)%nnode
    end do
    call sort_unique(all)
    ct%nall = size(all)
    call move_alloc(all, ct%all_gid)

    ! Owned contact nodes of this rank; masses, owners and positions of all.
    ct%nown = 0
    allocate(ct%own_contact(mesh%nnode_owned), ct%own_local(mesh%nnode_owned))
    do n = 1, mesh%nnode_owned
      i = find_key(ct%all_gid, mesh%node_gid(n))
      if (i == 0) cycle
      ct%nown = ct%nown + 1
      ct%own_contact(ct%nown) = i
      ct%own_local(ct%nown) = n
    end do
    ct%own_contact = ct%own_contact(:ct%nown)
    ct%own_local = ct%own_local(:ct%nown)
    ! The owners' masses; a node whose motion is prescribed is rigid for the
    ! contact: its mass is scaled by RIGID_MASS_FACTOR, so every exchange
    ! and multiplier moves the other side only, and it takes no contact
    ! force (the constraint's reaction is the boundary's work). The parts
    ! get the masses of their local sets with the migration plan.
    allocate(ct%own_mass(ct%nown), ct%own_rigid(ct%nown))
    do i = 1, ct%nown
      ct%own_mass(i) = node_mass(ct%own_local(i))
      ct%own_rigid(i) = .false.
      if (present(rigid)) ct%own_rigid(i) = rigid(ct%own_local(i))
    end do
    where (ct%own_rigid) ct%own_mass = RIGID_MASS_FACTOR * ct%own_mass
    call directory_build(ct)
    ! Every contact node's position at x, for the edge flags, sizes,
    ! sagittas and reach below.
    allocate(xc(3, ct%nall))
    xc = 0.0_rk
    do i = 1, ct%nown
      xc(:, ct%own_contact(i)) = x(:, ct%own_local(i))
    end do
    ! (one owner each, zero elsewhere: the sums are the owners' values)
    call par_sum_in_place(xc)
    ! (edge flags are read on the parts' local surfaces only, made from the
    ! local set's positions at each search, never on the whole ones)
    do k = 1, ct%npair
      call surface_relabelled(raw_a(k), ct%all_gid, ct%pairs(k)%all_a)
      call surface_relabelled(raw_b(k), ct%all_gid, ct%pairs(k)%all_b)
      ct%pairs(k)%size = 0.5_rk * (median_size(xc, ct%pairs(k)%all_a) + &
          median_size(xc, ct%pairs(k)%all_b))
    end do
    allocate(ct%fc(3, ct%nown))
    ct%fc = 0.0_rk
    call segment_homes(ct, mesh)
    do k = 1, ct%npair
      allocate(ct%pairs(k)%was_active(ct%nown))
      ct%pairs(k)%was_active = .false.
    end do

    ! The audit's set-up: offsets, sagittas at t = 0, reach, force output.
    allocate(ct%gap_own(ct%nown))
    ct%gap_own = 0.0_rk
    do k = 1, ct%npair
      associate(p => ct%pairs(k))
        allocate(p%offset(ct%nown), p%own_in_a(ct%nown), p%fc_own(3, ct%nown))
        p%offset = 0.0_rk
        p%fc_own = 0.0_rk
        ! Per owned node: the larger of its initial offsets on sides a and b.
        if (present(offsets) .and. p%mirror_of == 0) then
          do i = 1, ct%nown
            c = surface_node_index(p%all_a, ct%own_contact(i))
            if (c > 0) p%offset(i) = max(p%offset(i), offsets(k)%a(c))
            c = surface_node_index(p%all_b, ct%own_contact(i))
            if (c > 0) p%offset(i) = max(p%offset(i), offsets(k)%b(c))
          end do
        end if
        ! A refresh keeps each node's offset (by global id; a node that joins
        ! has none); the caller then has them follow the new surfaces
        ! (contact_refresh_offsets).
        if (present(old_gid) .and. p%mirror_of == 0) then
          do i = 1, ct%nown
            c = find_key(old_gid, ct%all_gid(ct%own_contact(i)))
            if (c > 0) p%offset(i) = old_offset(c, k)
          end do
        end if
        ! A reverse pass keeps the initial penetration of its deck interface
        ! (offsets are per owned contact node, so the same array).
        if (p%mirror_of > 0) p%offset = ct%pairs(p%mirror_of)%offset
        do i = 1, ct%nown
          p%own_in_a(i) = surface_node_index(p%all_a, ct%own_contact(i)) > 0
        end do
        call surface_sagitta(xc, p%all_a, p%sag_a)
        call surface_sagitta(xc, p%all_b, p%sag_b)
        p%reach = audit_reach(xc, p%all_a, p%all_b)
        ! Nothing reads the whole surfaces' neighbours after this but the
        ! audit on one rank, which audits the whole surfaces (on more, it
        ! audits near parts that find their own: contact_monitor).
        if (par_size() > 1) deallocate(p%all_a%neighbours, p%all_b%neighbours)
      end associate
    end do


  end subroutine index_surfaces


  !> Median of the longest segment edge over a surface.
  function median_size(x, surf) result(h)
    real(rk), intent(in) :: x(:, :)
    type(contact_surface_t), intent(in) :: surf
    real(rk) :: h
    real(rk), allocatable :: sizes(:)
    integer :: s, c
    h = 0.0_rk
    if (surf%nseg == 0) return
    allocate(sizes(surf%nseg))
    do s = 1, surf%nseg
      sizes(s) = 0.0_rk
      do c = 1, 4
        sizes(s) = max(sizes(s), norm2(x(:, surf%segments(mod(c, 4) + 1, s)) - &
            x(:, surf%segments(c, s))))
      end do
    end do
    call sort_values(sizes)
    h = sizes((surf%nseg + 1) / 2)
  end function median_size

  !> Contact forces of the stage for the owned nodes: force(:, local) += fc.
  !> x_old, v_old: positions and velocities at t^n; force: hydro force of the
  !> stage. Collective.
  subroutine contact_apply(ct, x_old, v_old, force, stage_dt, cycle, final, wall_clock, &
      cycle_dt)
    type(contact_t), intent(inout) :: ct
    real(rk), intent(in) :: x_old(:, :), v_old(:, :)
    real(rk), intent(inout) :: force(:, :)
    real(rk), intent(in) :: stage_dt !< the stage's step (the predictor: half the cycle's)
    integer(i8), intent(in) :: cycle !< the cycle being computed (for search scheduling)
    logical, intent(in) :: final !< the corrector (its forces give the diagnostics)
    interface
      function wall_clock() result(t)
        import :: rk
        real(rk) :: t
      end function wall_clock
    end interface
    !> the predictor: the cycle's step, which the impact limit may shorten
    !> (contact_impact; collective), and the stage's with it
    real(rk), intent(inout), optional :: cycle_dt
    real(rk), allocatable :: fck(:, :, :)
    logical, allocatable :: has(:, :)
    real(rk) :: t0, speed, dt, limit
    type(selection_t), allocatable :: sel(:)
    integer :: i, k
    logical :: rebuilt

    if (ct%npair == 0) return
    dt = stage_dt
    t0 = wall_clock()
    ! The largest speed at t^n: once per step (both stages have the same v^n).
    if (ct%speed_cycle /= cycle) then
      speed = 0.0_rk
      do i = 1, ct%nown
        speed = max(speed, norm2(v_old(:, ct%own_local(i))))
      end do
      ct%speed = par_max(speed, ct%traffic)
      ct%speed_cycle = cycle
      call lap(ct%wait_seconds)
    end if
    rebuilt = cycle >= ct%next_search .or. .not. allocated(ct%all_of)
    ! After a restart the first search only rebuilds what the dump does not
    ! hold: the uninterrupted run's schedule (and so its audits) goes on.
    if (rebuilt .and. cycle >= ct%resumed_search) ct%audit_due = .true.
    if (rebuilt) call contact_rebuild(ct, x_old, dt, cycle, sel)
    if (rebuilt) ct%gathered_cycle = -1
    if (rebuilt .and. cycle < ct%resumed_search) ct%next_search = ct%resumed_search
    ct%resumed_search = -1
    call lap(ct%search_seconds)
    ! x^n and v^n of the local set once per step, the forces every stage.
    call gather_nodes(ct, x_old, v_old, force, ct%gathered_cycle /= cycle)
    ct%gathered_cycle = cycle
    call lap(ct%migrate_seconds)
    if (rebuilt) then
      call contact_localize(ct, sel)
      call lap(ct%search_seconds)
    end if
    if (present(cycle_dt)) then
      ! The impact limit at t^n, over every rank's pairs. The recovery keeps
      ! its speed over the stable step (landing).
      limit = par_min(impact_step_limit(ct), ct%traffic)
      if (limit < cycle_dt) then
        limit = max(limit, IMPACT_FLOOR * cycle_dt)
        dt = stage_dt * (limit / cycle_dt)
        ct%landing = ct%landing * (limit / cycle_dt)
        cycle_dt = limit
        ct%impact_cycles = ct%impact_cycles + 1
      end if
      call lap(ct%enforce_seconds)
    end if

    allocate(fck(3, ct%nown, ct%npair), has(ct%nown, ct%npair))
    fck = 0.0_rk
    has = .false.
    ct%fc = 0.0_rk
    call stage_round(1, ct%ndeck)
    if (ct%npair > ct%ndeck) then
      ! The reverse passes (DAM symmetric = .true.), master and slave swapped,
      ! start from the force with the deck interfaces' contact forces in it:
      ! where the first pass matched the two sides nothing is left to do,
      ! and master nodes that cross the slave surface are caught.
      call gather_nodes(ct, x_old, v_old, force, .false.)
      call lap(ct%migrate_seconds)
      call stage_round(ct%ndeck + 1, ct%npair)
    end if
    if (final) then
      do k = 1, ct%npair
        do i = 1, ct%nown
          ct%pairs(k)%fc_own(:, i) = 0.0_rk
          if (has(i, k)) ct%pairs(k)%fc_own(:, i) = fck(:, i, k)
        end do
      end do
    end if
    if (final) call reduce_diagnostics(ct, has)
    if (final) ct%cycles = ct%cycles + 1
    call lap(ct%migrate_seconds)

  contains

    !> The interfaces first..last in one round: each method's rounds on the
    !> parts and at the owners (contact_method_t), and their contact forces
    !> added to force and ct%fc.
    subroutine stage_round(first, last)
      integer, intent(in) :: first, last
      type(records_t), allocatable :: out(:)
      type(inflow_t), allocatable :: inflow(:)
      real(rk), allocatable :: values(:, :, :)
      real(rk) :: fsum(3)
      integer :: r, nround
      allocate(out(first:last), inflow(first:last))
      nround = 0
      do k = first, last
        nround = max(nround, ct%pairs(k)%method%rounds())
        ct%pairs(k)%sums = step_sums_t()
        allocate(inflow(k)%v(0, 0, 1))
      end do
      do r = 1, nround
        ! The parts: each interface's records for the owners.
        do k = first, last
          associate(p => ct%pairs(k))
            if (r > p%method%rounds()) cycle
            call take(p%method%kept(r), out(k), p%method%record_width(r))
            call p%method%part_round(ct, p, k, r, dt, final, inflow(k)%v(:, :, 1), &
                out(k))
          end associate
        end do
        call lap(ct%enforce_seconds)
        ! The owners: sums in key order; values for the next round to the parts.
        do k = first, last
          associate(p => ct%pairs(k))
            if (r > p%method%rounds()) cycle
            call send_records(out(k), ct%owner, ct%owner_pos, ct%send_own, ct%send_count, &
                ct%nown, ct%recv_count > 0, ct%send_count > 0, ct%traffic)
            allocate(values(max(p%method%owner_width(r), 0), ct%nown, 1))
            call p%method%owner_round(ct, p, r, out(k), v_old, force, dt, values(:, :, 1), &
                fck(:, :, k), has(:, k))
            if (r < p%method%rounds()) call scatter_nodes(ct, values, inflow(k)%v)
            deallocate(values)
            call take(out(k), p%method%kept(r), p%method%record_width(r))
          end associate
        end do
        call lap(ct%migrate_seconds)
      end do
      do i = 1, ct%nown
        if (ct%own_rigid(i)) then
          ! Prescribed motion: the boundary holds the node (contact_setup).
          has(i, first:last) = .false.
          cycle
        end if
        fsum = 0.0_rk
        do k = first, last
          if (has(i, k)) fsum = fsum + fck(:, i, k)
        end do
        ct%fc(:, i) = ct%fc(:, i) + fsum
        force(:, ct%own_local(i)) = force(:, ct%own_local(i)) + fsum
      end do
    end subroutine stage_round

    subroutine lap(total)
      real(rk), intent(inout) :: total
      real(rk) :: t
      t = wall_clock()
      total = total + (t - t0)
      t0 = t
    end subroutine lap

  end subroutine contact_apply

  !> Diagnostics of the step from every part's sums; released nodes from the
  !> owners. The sums per interface as they always were (the MPI library's
  !> order), the largest penetrations of all interfaces in one reduction.
  !> Collective.
  subroutine reduce_diagnostics(ct, has)
    type(contact_t), intent(inout) :: ct
    logical, intent(in) :: has(:, :)
    real(rk) :: sums(8), pen_max(ct%npair)
    integer :: k
    do k = 1, ct%npair
      pen_max(k) = ct%pairs(k)%sums%pen_max
    end do
    call par_max_array(pen_max, ct%traffic)
    do k = 1, ct%npair
      associate(p => ct%pairs(k), s => ct%pairs(k)%sums)
        sums = [s%active, s%force, s%pen_sq, s%weight, s%dmom, &
            real(count(p%was_active .and. .not. has(:, k)), rk)]
        p%was_active = has(:, k)
        call par_sum_array(sums, ct%traffic)
        p%pen_sq = sums(3)
        p%pen_weight = sums(4)
        ! pen_rms: over the method's weights (DLM: overlap area, DAM: slaves).
        p%diag(1:8) = [sums(1), sums(2), pen_max(k), p%method%pen_rms(sums(3), sums(4)), &
            sums(8), sums(5:7)]
      end associate
    end do
  end subroutine reduce_diagnostics


  !> After the velocity update: the work of the contact forces over the step
  !> on the owned nodes, its terms added exactly (core_exact_sum; the caller
  !> reduces it), and per interface in work_step. Nothing without an
  !> interface.
  subroutine contact_work_update(ct, v_old, v_new, dt, work)
    type(contact_t), intent(inout) :: ct
    real(rk), intent(in) :: v_old(:, :), v_new(:, :)
    real(rk), intent(in) :: dt
    type(exact_sum_t), intent(inout) :: work !< + this rank's terms of the step's contact work
    integer :: i, n, k
    do i = 1, ct%nown
      n = ct%own_local(i)
      call work%add(0.5_rk * dt * dot_product(ct%fc(:, i), v_old(:, n) + v_new(:, n)))
    end do
    do k = 1, ct%npair
      associate(p => ct%pairs(k))
        p%work_step = exact_sum_t()
        do i = 1, ct%nown
          n = ct%own_local(i)
          call p%work_step%add(0.5_rk * dt * dot_product(p%fc_own(:, i), &
              v_old(:, n) + v_new(:, n)))
        end do
      end associate
    end do
  end subroutine contact_work_update

  !> End-of-run summary on rank 0: the contact time split (largest over the
  !> ranks) and the local sets against the whole contact surface. Collective.
  subroutine contact_report(ct, loop_seconds)
    type(contact_t), intent(in) :: ct
    real(rk), intent(in) :: loop_seconds !< this rank's time loop without dumps
    real(rk) :: search, enforce, migrate, total, loop, whole, local, wait, audit, owned
    real(rk) :: bytes, messages, exchanges, collectives, comm, per
    integer :: largest, smallest, k
    if (ct%npair == 0) return
    ! The traffic per cycle, each figure its largest rank's.
    per = 1.0_rk / real(max(ct%cycles, 1_i8), rk)
    bytes = par_max(real(ct%traffic%bytes, rk)) * per
    messages = par_max(real(ct%traffic%messages, rk)) * per
    exchanges = par_max(real(ct%traffic%exchanges, rk)) * per
    collectives = par_max(real(ct%traffic%collectives, rk)) * per
    comm = par_max(ct%traffic%wait_seconds)
    search = par_max(ct%search_seconds)
    enforce = par_max(ct%enforce_seconds)
    migrate = par_max(ct%migrate_seconds)
    wait = par_max(ct%wait_seconds)
    audit = par_max(ct%audit_seconds)
    total = par_max(ct%search_seconds + ct%enforce_seconds + ct%migrate_seconds)
    largest = par_max(ct%ncn_max)
    smallest = -par_max(-ct%ncn_max)
    loop = par_max(loop_seconds)
    ! Memory (bytes): the static whole-surface data every rank holds (the
    ! contact nodes' global ids, the surfaces and their sagittas), this
    ! part's working data (local set: x, v, f, mass, offsets, owner,
    ! contact index; local surfaces, geometry and pair caches), and the
    ! owners' share (per owned node: indices, mass, rigid flag, key flag
    ! and weight, force, gap; per interface its flags, offset and force;
    ! the owner directory's entries).
    whole = 8.0_rk * real(ct%nall, rk)
    local = real(ct%ncn_max, rk) * (88.0_rk + 8.0_rk * real(ct%npair, rk))
    owned = real(ct%nown, rk) * (64.0_rk + 40.0_rk * real(ct%npair, rk)) + &
        12.0_rk * real(size(ct%dir_gid), rk)
    do k = 1, ct%npair
      associate(p => ct%pairs(k))
        whole = whole + surface_bytes(p%all_a) + surface_bytes(p%all_b) + &
            8.0_rk * real(p%all_a%nseg + p%all_b%nseg, rk)
        local = local + surface_bytes(p%a) + surface_bytes(p%b) + geometry_bytes(p%ga) + &
            geometry_bytes(p%gb)
        local = local + p%method%bytes()
      end associate
    end do
    whole = par_max(whole)
    local = par_max(local)
    owned = par_max(owned)
    if (par_rank() /= 0) return
    write(output_unit, '(a,3(f10.3,a),f6.1,a)') 'impact3d: contact ', search, &
        ' s search and RCB, ', enforce, ' s enforcement, ', migrate, ' s migration (', &
        100.0_rk * total / max(loop, 1.0e-9_rk), &
        '% of the loop; largest over the ranks)'
    write(output_unit, '(a,f10.3,a,i0,a,f6.1,a)') 'impact3d: contact audit ', audit, ' s (', &
        ct%audits, ' audits, ', 100.0_rk * audit / max(loop, 1.0e-9_rk), &
        '% of the loop; largest over the ranks, not in the contact times above)'
    if (par_size() > 1) then
      write(output_unit, '(a,f10.3,a)') 'impact3d: contact entry wait ', wait, &
          ' s (the other ranks'' hydro: load imbalance; largest over the ranks, not in the '// &
          'contact times)'
      write(output_unit, '(a,f0.1,a,f0.1,a,f0.1,a,f0.1,a,f0.1,a)') &
          'impact3d: contact exchange per cycle, largest rank: ', bytes / 1.0e3_rk, ' kB in ', &
          messages, ' messages; ', exchanges + collectives, ' synchronisations (', exchanges, &
          ' point-to-point exchanges, ', collectives, ' collectives)'
      write(output_unit, '(a,f10.3,a)') 'impact3d: contact communication calls ', comm, &
          ' s (waiting for the other ranks and transfer; largest over the ranks, in the '// &
          'contact times)'
    end if
    write(output_unit, '(a,i0,a,i0,a)') 'impact3d: contact impact limit shortened ', &
        ct%impact_cycles, ' of ', ct%cycles, ' cycles (docs/contact.md, 4.2)'
    write(output_unit, '(a,i0,a,i0,a,i0,a,i0,a)') 'impact3d: contact local sets ', smallest, &
        ' to ', largest, ' nodes per rank of ', ct%nall, ' contact nodes; ', ct%rebuilds, &
        ' global searches'
    if (ct%balanced_searches > 0) write(output_unit, '(a,f6.3,a,f6.3,a,i0,a,i0,a)') &
        'impact3d: contact pairs per part, largest / mean: ', &
        ct%balance_sum / real(ct%balanced_searches, rk), ' on average, ', ct%balance_worst, &
        ' at worst; ', ct%recuts, ' of ', ct%rebuilds, ' searches re-cut the RCB (load drift)'
    write(output_unit, '(a,f10.3,a,f10.3,a,f10.3,a)') 'impact3d: contact memory per rank ', &
        local / 1.0e6_rk, ' MB working set (largest), ', whole / 1.0e6_rk, &
        ' MB whole-surface topology (every rank), ', owned / 1.0e6_rk, &
        ' MB owned nodes and owner directory (largest)'

  contains

    real(rk) function surface_bytes(surf) result(b)
      type(contact_surface_t), intent(in) :: surf
      b = 0.0_rk
      if (.not. allocated(surf%segments)) return
      b = real(size(surf%segments) + size(surf%nodes) + size(surf%node_start) + &
          size(surf%node_segments), rk) * 4.0_rk + real(size(surf%segment_id), rk) * 8.0_rk
      if (allocated(surf%neighbours)) b = b + real(size(surf%neighbours), rk) * 4.0_rk
      if (allocated(surf%edge_convex)) b = b + real(size(surf%edge_convex), rk) * 4.0_rk
    end function surface_bytes

    real(rk) function geometry_bytes(g) result(b)
      type(surface_geometry_t), intent(in) :: g
      b = 0.0_rk
      if (.not. allocated(g%facets)) return
      b = real(size(g%facets) + size(g%normal) + size(g%area) + size(g%quad_normal) + &
          size(g%nodal_area), rk) * 8.0_rk
    end function geometry_bytes

  end subroutine contact_report




  !> Per local node (nnode) the interfaces whose force it carried in the
  !> last step, bit k - 1 for interface k, as a real (restart state: the
  !> history's released count and the audit's unheld nodes read it); empty
  !> without interfaces.
  function contact_active_flags(ct, nnode) result(flags)
    type(contact_t), intent(in) :: ct
    integer, intent(in) :: nnode
    real(rk), allocatable :: flags(:)
    integer :: i, k
    if (ct%npair == 0 .or. .not. allocated(ct%own_local)) then
      allocate(flags(0))
      return
    end if
    allocate(flags(nnode))
    flags = 0.0_rk
    do k = 1, ct%npair
      do i = 1, ct%nown
        if (ct%pairs(k)%was_active(i)) flags(ct%own_local(i)) = flags(ct%own_local(i)) + &
            real(2_i8**(k - 1), rk)
      end do
    end do
  end function contact_active_flags

  !> The flags of contact_active_flags back into the interfaces.
  subroutine contact_active_restore(ct, flags)
    type(contact_t), intent(inout) :: ct
    real(rk), intent(in) :: flags(:) !< (nnode local)
    integer :: i, k
    if (ct%npair == 0 .or. .not. allocated(ct%own_local)) return
    do k = 1, ct%npair
      do i = 1, ct%nown
        ct%pairs(k)%was_active(i) = btest(nint(flags(ct%own_local(i)), i8), k - 1)
      end do
    end do
  end subroutine contact_active_restore

  !> Per deck interface and local node (ndeck, nnode) the offsets of the
  !> owned contact nodes (zero elsewhere), once a refresh has measured some
  !> (restart state: contact_refresh_offsets measured them at positions the
  !> restart does not have); empty before, and without interfaces.
  function contact_offset_values(ct, nnode) result(values)
    type(contact_t), intent(in) :: ct
    integer, intent(in) :: nnode
    real(rk), allocatable :: values(:, :)
    integer :: i, k
    if (ct%npair == 0 .or. .not. ct%refreshed) then
      allocate(values(0, 0))
      return
    end if
    allocate(values(ct%ndeck, nnode))
    values = 0.0_rk
    do k = 1, ct%ndeck
      do i = 1, ct%nown
        values(k, ct%own_local(i)) = ct%pairs(k)%offset(i)
      end do
    end do
  end function contact_offset_values

  !> contact_offset_values' values back into the interfaces (after the
  !> restart's refresh; each owned node's).
  subroutine contact_offset_restore(ct, values)
    type(contact_t), intent(inout) :: ct
    real(rk), intent(in) :: values(:, :) !< (ndeck, nnode local)
    integer :: i, k
    if (ct%npair == 0 .or. size(values, 1) /= ct%ndeck) return
    do k = 1, ct%ndeck
      do i = 1, ct%nown
        ct%pairs(k)%offset(i) = values(k, ct%own_local(i))
      end do
    end do
    do k = ct%ndeck + 1, ct%npair
      if (ct%pairs(k)%mirror_of > 0) ct%pairs(k)%offset = ct%pairs(ct%pairs(k)%mirror_of)%offset
    end do
  end subroutine contact_offset_restore

  !> What a restart needs to go on with the uninterrupted run's search
  !> schedule and history: the next search's cycle, then per deck interface
  !> the last audit's columns (restart attributes, dump_write).
  function contact_resume_state(ct) result(values)
    type(contact_t), intent(in) :: ct
    real(rk), allocatable :: values(:)
    integer :: k
    allocate(values(0))
    if (ct%npair == 0) return
    values = [real(ct%next_search, rk)]
    do k = 1, ct%ndeck
      values = [values, ct%pairs(k)%diag(DIAG_AUDIT:CONTACT_DIAG_COUNT)]
    end do
  end function contact_resume_state

  !> contact_resume_state's values back (a dump without them: nothing).
  subroutine contact_resume(ct, values)
    type(contact_t), intent(inout) :: ct
    real(rk), intent(in) :: values(:)
    integer :: k, n
    if (ct%npair == 0 .or. size(values) == 0) return
    n = CONTACT_DIAG_COUNT - DIAG_AUDIT + 1
    if (size(values) /= 1 + n * ct%ndeck) return
    ct%resumed_search = nint(values(1), i8)
    do k = 1, ct%ndeck
      ct%pairs(k)%diag(DIAG_AUDIT:CONTACT_DIAG_COUNT) = values(2 + n * (k - 1):1 + n * k)
    end do
  end subroutine contact_resume

end module contact_enforce