!> Contact enforcement: DAM (discrete accurate matching, master-slave) and DLM
!> (discrete Lagrangian multiplier, symmetric) of Jia, Gong, Zhang & Liu
!> (J. Comput. Phys. 267 (2014) 247-285), as described in docs/contact.md, sections 5-6.
!> This is the narrow interface between the hydro state and contact.
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
!> DLM forms (deck key `form`): with mu = Mh Md/(Mh + Md),
!>   coordinate: fh = mu (Fd/Md - Fh/Mh + (vd - vh)/(dt/2) - pen/(dt^2/2)),
!>   velocity:   fh = mu (Fd/Md - Fh/Mh + (vd - vh - e/dt)/dt), gated by
!>               pen_free > 0, e = recovery * max(pen - allowance, 0): the
!>               approach stopped, and a fraction `recovery` (deck, default
!>               0.2) of the penetration beyond an allowance (2% of the
!>               smaller segment's size) removed per step (Baumgarte-type
!>               position feedback). Without it the one pass, which
!>               under-corrects a node whose neighbours move differently, has
!>               nothing to pull a drifting node back: on the curved Sedov
!>               split the ball's valence-3 vertex escaped through the gas
!>               surface (0.45 at t = 1, fine mesh). Below recovery = 0.5 a
!>               pair never opens a gap, so it does not chatter; the
!>               allowance leaves alone the sagitta mismatch of two faceted
!>               versions of one curved surface, which fighting would only
!>               dissipate energy.
!>   combined:   the velocity form with a target approach velocity at t^n+1 of
!>               -r/dt instead of 0, r = max(pen + dt w/2, 0) the penetration
!>               the velocity form would leave: half of r is removed per step
!>               by a force pair (momentum exact), without the rebound of the
!>               coordinate form.
!> fh = min(fh, 0) in every form. Default: velocity. The equal-bars test
!> rejects the coordinate form (15 openings during the contact, interface
!> velocity 11% of v0); velocity and combined both pass it (residual
!> penetration 7.8e-6 and 3.9e-6 cm), but the combined form's push-out
!> velocity r/(2 dt) pumps energy where a large penetration persists (Al on
!> steel at 1 km/s: the run gained more energy than it had and failed), so it
!> stays an option.
module contact_enforce
  use core_kinds, only: rk, ik, i8
  use core_status, only: status_t
  use core_sort, only: sort_values, sort_unique
  use, intrinsic :: iso_fortran_env, only: output_unit
  use mesh_global, only: global_mesh_t, NAME_LEN
  use mesh_local, only: mesh_t
  use contact_geometry, only: segment_facets, quad_unit_normal, triangle_unit_normal, &
      triangle_overlap, triangle_overlap_2d, triangle_vector_area, SEGMENT_FACET_COUNT, &
      FACET_CORNER, tangent_basis, segment_box, project_facets, facet_box, boxes_meet, covered, &
      plane_offset, bilinear_shape
  use contact_surface, only: contact_surface_t, surface_build, surface_from_segments, &
      surface_node_index, set_names_of, add_ring, local_surface, &
      master_neighbourhood, keep_lower_side, nodal_areas
  use contact_records, only: records_t, take, add_record, send_records, sum_records
  use contact_search, only: bucket_search, primary_pairs, primary_pair_t, segment_pair_search, &
      search_interval, find_key
  use contact_rbf, only: rbf_weights
  use contact_state, only: METHOD_DAM, METHOD_DLM, FORM_COORDINATE, FORM_VELOCITY, &
      FORM_COMBINED, CONTACT_DIAG_COUNT, CONTACT_DIAG_NAMES, SURFACE_LEN, contact_spec_t, &
      surface_geometry_t, interface_t, selection_t, contact_t, capture_of, initial_offsets_t
  use contact_audit, only: surface_sagitta, audit_reach
  use contact_kernels, only: dlm_pair_force, dam_merged_normal_velocity, dam_put_back_velocity, &
      dlm_pair_friction, dam_friction_velocity
  use contact_parts, only: segment_homes, contact_rebuild, contact_localize, gather_nodes, &
      scatter_nodes
  use parallel_env, only: par_sum_array, par_max, par_rank, par_size
  use parallel_exchange, only: par_exchange, par_exchange_counts
  use parallel_rcb, only: rcb_t, rcb_build, rcb_part_of, rcb_parts_of_box
  implicit none
  private
  public :: contact_setup, contact_apply, contact_work_update, contact_diagnostics
  public :: contact_report
  ! The state the application and the deck reader see.
  public :: CONTACT_DIAG_COUNT, CONTACT_DIAG_NAMES, SURFACE_LEN, contact_spec_t, contact_t

  !> Facets facing each other: n_a . n_b below this.
  real(rk), parameter :: FACING = -0.2_rk
  !> DLM velocity form: default fraction of a facet pair's penetration removed
  !> per step (see dlm_step).
  real(rk), parameter :: DEFAULT_RECOVERY = 0.2_rk
  !> Share of the audit's tolerance (contact_audit) a facet pair may keep
  !> without recovery: the recovery starts well below the tolerance, so a
  !> pair it holds keeps a margin for one step's overshoot.
  real(rk), parameter :: ALLOWANCE_SHARE = 0.4_rk
  !> The size part of that allowance, ALLOWANCE_SHARE x SIZE_FRACTION (0.05)
  !> of the size (square root of the area) of the smaller of the two segments.
  real(rk), parameter :: RECOVERY_ALLOWANCE = 0.02_rk
  !> Overlaps smaller than this fraction of the smaller facet's area are
  !> ignored: slivers between facets of neighbouring nodes that coincide in
  !> one projection but not in the slightly tilted common plane of another
  !> segment pair (relative size tilt x penetration / zone, ~1e-12 on the
  !> mirror test). They carry less than this share of a node's force.
  real(rk), parameter :: AREA_TOLERANCE = 1.0e-8_rk
  !> Reals per DLM facet pair: shares wh, wd, penetration at the overlap
  !> centroid, overlap area, normal (3), excess over the recovery allowance,
  !> the gate's penetration (the centroid's; see dlm_geometry).
  integer, parameter :: FP_REALS = 9

contains

  !> Build the contact surfaces in contact-index space, the owned-node map and
  !> the nodal masses. Problems go to status (group, key, reason).
  subroutine contact_setup(specs, global, mesh, node_mass, ct, status, offsets)
    type(contact_spec_t), intent(in) :: specs(:)
    type(global_mesh_t), intent(in) :: global
    type(mesh_t), intent(in) :: mesh
    real(rk), intent(in) :: node_mass(:) !< (nnode local) nodal masses
    type(contact_t), intent(inout) :: ct
    type(status_t), intent(inout) :: status
    !> initial penetration kept per surface node (contact_initial); none: zero
    type(initial_offsets_t), intent(in), optional :: offsets(:)
    type(contact_surface_t), allocatable :: raw_a(:), raw_b(:)
    integer(i8), allocatable :: all(:)
    real(rk), allocatable :: xc(:, :), packed(:, :), flat(:)
    integer :: k, n, i, count_all
    character(len=16) :: where
    character(len=SURFACE_LEN) :: master_set, slave_set

    ct%npair = size(specs)
    allocate(ct%pairs(ct%npair), raw_a(ct%npair), raw_b(ct%npair))
    if (ct%npair == 0) return
    do k = 1, ct%npair
      write(where, '(a,i0,a)') '&contact(', k, ')'
      associate(p => ct%pairs(k))
        p%spec = specs(k)
        p%self = specs(k)%surface_a == specs(k)%surface_b
        select case (specs(k)%method)
        case ('dam')
          p%method = METHOD_DAM
        case default
          p%method = METHOD_DLM
        end select
        select case (specs(k)%form)
        case ('coordinate')
          p%form = FORM_COORDINATE
        case ('combined')
          p%form = FORM_COMBINED
        case default
          p%form = FORM_VELOCITY
        end select
        p%recovery = DEFAULT_RECOVERY
        p%slave_normal = specs(k)%normal == 'slave'
        if (specs(k)%recovery >= 0.0_rk) p%recovery = specs(k)%recovery
        ! For DAM, b is the master side.
        slave_set = specs(k)%surface_a
        master_set = specs(k)%surface_b
        if (p%method == METHOD_DAM .and. specs(k)%master == 'a') then
          slave_set = specs(k)%surface_b
          master_set = specs(k)%surface_a
        end if
        call surface_build(global, set_names_of(slave_set), raw_a(k), status)
        call surface_build(global, set_names_of(master_set), raw_b(k), status)
      end associate
    end do
    if (.not. status%ok()) return

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
    allocate(xc(3, ct%nall))
    xc = global%coordinates(:, ct%all_gid)
    do k = 1, ct%npair
      call renumber(raw_a(k), ct%pairs(k)%all_a)
      call renumber(raw_b(k), ct%pairs(k)%all_b)
      ct%pairs(k)%size = 0.5_rk * (median_size(xc, ct%pairs(k)%all_a) + &
          median_size(xc, ct%pairs(k)%all_b))
      ct%pairs(k)%single_part = ct%pairs(k)%method == METHOD_DLM .and. &
          ct%pairs(k)%spec%sweeps > 1
    end do

    ! Owned contact nodes of this rank; masses and owners of all.
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
    allocate(ct%own_of(ct%nall))
    ct%own_of = 0
    do i = 1, ct%nown
      ct%own_of(ct%own_contact(i)) = i
    end do
    allocate(packed(2, ct%nall))
    packed = 0.0_rk
    do i = 1, ct%nown
      packed(1, ct%own_contact(i)) = node_mass(ct%own_local(i))
      packed(2, ct%own_contact(i)) = real(par_rank(), rk)
    end do
    allocate(flat(2 * ct%nall))
    flat = reshape(packed, [2 * ct%nall])
    call par_sum_array(flat)
    packed = reshape(flat, [2, ct%nall])
    ct%all_mass = packed(1, :)
    ct%all_owner = nint(packed(2, :))
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
        allocate(p%offset(ct%nall), p%own_in_a(ct%nown), p%fc_own(3, ct%nown))
        p%offset = 0.0_rk
        p%fc_own = 0.0_rk
        if (present(offsets)) then
          do i = 1, p%all_a%nnode
            p%offset(p%all_a%nodes(i)) = max(p%offset(p%all_a%nodes(i)), offsets(k)%a(i))
          end do
          do i = 1, p%all_b%nnode
            p%offset(p%all_b%nodes(i)) = max(p%offset(p%all_b%nodes(i)), offsets(k)%b(i))
          end do
        end if
        do i = 1, ct%nown
          p%own_in_a(i) = surface_node_index(p%all_a, ct%own_contact(i)) > 0
        end do
        call surface_sagitta(xc, p%all_a, p%sag_a)
        call surface_sagitta(xc, p%all_b, p%sag_b)
        p%reach = audit_reach(xc, p%all_a, p%all_b)
      end associate
    end do

  contains

    subroutine renumber(raw, surf)
      type(contact_surface_t), intent(in) :: raw
      type(contact_surface_t), intent(inout) :: surf
      integer(ik), allocatable :: segments(:, :)
      integer :: s, c
      allocate(segments(4, raw%nseg))
      do s = 1, raw%nseg
        do c = 1, 4
          segments(c, s) = int(find_key(ct%all_gid, int(raw%segments(c, s), i8)), ik)
        end do
      end do
      call surface_from_segments(segments, raw%segment_id, xc, surf)
    end subroutine renumber

  end subroutine contact_setup

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
  subroutine contact_apply(ct, x_old, v_old, force, dt, cycle, final, wall_clock)
    type(contact_t), intent(inout) :: ct
    real(rk), intent(in) :: x_old(:, :), v_old(:, :)
    real(rk), intent(inout) :: force(:, :)
    real(rk), intent(in) :: dt
    integer(i8), intent(in) :: cycle !< the cycle being computed (for search scheduling)
    logical, intent(in) :: final !< the corrector (its forces give the diagnostics)
    interface
      function wall_clock() result(t)
        import :: rk
        real(rk) :: t
      end function wall_clock
    end interface
    type(records_t) :: dlm_out, dam_out, putback
    real(rk), allocatable :: fck(:, :, :), vmatch(:, :, :), vm_local(:, :, :)
    logical, allocatable :: has(:, :), touched(:, :)
    real(rk) :: t0, speed
    type(selection_t), allocatable :: sel(:)
    integer :: i, k
    logical :: any_dam, rebuilt

    if (ct%npair == 0) return
    t0 = wall_clock()
    speed = 0.0_rk
    do i = 1, ct%nown
      speed = max(speed, norm2(v_old(:, ct%own_local(i))))
    end do
    ct%speed = par_max(speed)
    call lap(ct%wait_seconds)
    rebuilt = cycle >= ct%next_search .or. .not. allocated(ct%all_of)
    if (rebuilt) ct%audit_due = .true.
    if (rebuilt) call contact_rebuild(ct, x_old, dt, cycle, sel)
    call lap(ct%search_seconds)
    call gather_nodes(ct, x_old, v_old, force)
    call lap(ct%migrate_seconds)
    if (rebuilt) then
      call contact_localize(ct, sel)
      call lap(ct%search_seconds)
    end if

    ! The parts: DLM pair forces, DAM exchange over the overlaps.
    call take(ct%kept(1), dlm_out, 3)
    call take(ct%kept(2), dam_out, 10)
    call take(ct%kept(3), putback, 3)
    any_dam = .false.
    do k = 1, ct%npair
      ct%pairs(k)%partial = 0.0_rk
      select case (ct%pairs(k)%method)
      case (METHOD_DLM)
        call dlm_step(ct, ct%pairs(k), k, dt, final, dlm_out)
      case (METHOD_DAM)
        any_dam = .true.
        call dam_exchange(ct, ct%pairs(k), k, dt, final, dam_out)
      end select
    end do
    call lap(ct%enforce_seconds)

    ! The owners: sums in key order.
    allocate(fck(3, ct%nown, ct%npair), has(ct%nown, ct%npair))
    fck = 0.0_rk
    has = .false.
    call send_records(dlm_out, ct%all_owner, ct%own_of, ct%nown)
    call sum_records(dlm_out, fck, has)
    if (any_dam) then
      call send_records(dam_out, ct%all_owner, ct%own_of, ct%nown)
      allocate(vmatch(3, ct%nown, ct%npair), touched(ct%nown, ct%npair))
      call match_masters(ct, dam_out, v_old, force, dt, vmatch, touched)
      call scatter_nodes(ct, vmatch, vm_local)
      call lap(ct%migrate_seconds)
      do k = 1, ct%npair
        if (ct%pairs(k)%method == METHOD_DAM) call dam_put_back(ct, ct%pairs(k), k, dt, &
            vm_local(:, :, k), putback)
      end do
      call lap(ct%enforce_seconds)
      call send_records(putback, ct%all_owner, ct%own_of, ct%nown)
      call dam_forces(ct, putback, v_old, force, dt, vmatch, touched, fck, has)
    end if
    ct%fc = 0.0_rk
    do i = 1, ct%nown
      do k = 1, ct%npair
        if (has(i, k)) ct%fc(:, i) = ct%fc(:, i) + fck(:, i, k)
      end do
      force(:, ct%own_local(i)) = force(:, ct%own_local(i)) + ct%fc(:, i)
    end do
    if (final) then
      do k = 1, ct%npair
        do i = 1, ct%nown
          ct%pairs(k)%fc_own(:, i) = 0.0_rk
          if (has(i, k)) ct%pairs(k)%fc_own(:, i) = fck(:, i, k)
        end do
      end do
    end if
    if (final) call reduce_diagnostics(ct, has, dt)
    call take(dlm_out, ct%kept(1), 3)
    call take(dam_out, ct%kept(2), 10)
    call take(putback, ct%kept(3), 3)
    call lap(ct%migrate_seconds)

  contains

    subroutine lap(total)
      real(rk), intent(inout) :: total
      real(rk) :: t
      t = wall_clock()
      total = total + (t - t0)
      t0 = t
    end subroutine lap

  end subroutine contact_apply

  !> DAM at the owners, first round: the exchanged mass, force and momentum
  !> of the owned nodes summed in key order, then the velocities: free, and
  !> for master nodes the matched normal component (docs/contact.md, 6).
  subroutine match_masters(ct, r, v_old, force, dt, vmatch, touched)
    type(contact_t), intent(in) :: ct
    type(records_t), intent(in) :: r
    real(rk), intent(in) :: v_old(:, :), force(:, :), dt
    real(rk), intent(out) :: vmatch(:, :, :)
    logical, intent(out) :: touched(:, :)
    real(rk), allocatable :: mbar(:, :), fbar(:, :, :), pbar(:, :, :), nmaster(:, :, :)
    real(rk) :: unit(3), vn, mass
    integer :: i, k, j, l
    allocate(mbar(ct%nown, ct%npair), fbar(3, ct%nown, ct%npair), pbar(3, ct%nown, ct%npair), &
        nmaster(3, ct%nown, ct%npair))
    touched = .false.
    do i = 1, ct%nown
      l = ct%own_local(i)
      mass = ct%all_mass(ct%own_contact(i))
      mbar(i, :) = mass
      do k = 1, ct%npair
        fbar(:, i, k) = force(:, l)
        pbar(:, i, k) = mass * v_old(:, l)
      end do
    end do
    nmaster = 0.0_rk
    do j = 1, r%n
      i = int(r%id(1, j))
      k = int(r%id(2, j))
      mbar(i, k) = mbar(i, k) + r%val(1, j)
      fbar(:, i, k) = fbar(:, i, k) + r%val(2:4, j)
      pbar(:, i, k) = pbar(:, i, k) + r%val(5:7, j)
      if (mod(r%id(3, j), 2_i8) == 1_i8) then
        nmaster(:, i, k) = nmaster(:, i, k) + r%val(8:10, j)
        touched(i, k) = .true.
      end if
    end do
    do i = 1, ct%nown
      l = ct%own_local(i)
      mass = ct%all_mass(ct%own_contact(i))
      do k = 1, ct%npair
        vmatch(:, i, k) = v_old(:, l) + dt * force(:, l) / mass
        if (.not. touched(i, k)) cycle
        if (.not. norm2(nmaster(:, i, k)) > 0.0_rk) cycle
        unit = nmaster(:, i, k) / norm2(nmaster(:, i, k))
        vn = dam_merged_normal_velocity(mbar(i, k), pbar(:, i, k), fbar(:, i, k), unit, dt)
        vmatch(:, i, k) = vmatch(:, i, k) + (vn - dot_product(vmatch(:, i, k), unit)) * unit
      end do
    end do
  end subroutine match_masters

  !> DAM at the owners, second round: the final velocities (the put-back-on
  !> of enforced slaves, the matched velocity of touched masters) as forces.
  subroutine dam_forces(ct, r, v_old, force, dt, vmatch, touched, fck, has)
    type(contact_t), intent(inout) :: ct
    type(records_t), intent(in) :: r
    real(rk), intent(in) :: v_old(:, :), force(:, :), dt
    real(rk), intent(in) :: vmatch(:, :, :)
    logical, intent(in) :: touched(:, :)
    real(rk), intent(inout) :: fck(:, :, :)
    logical, intent(inout) :: has(:, :)
    real(rk), allocatable :: vfinal(:, :, :)
    real(rk) :: mass
    integer :: i, k, j, l
    allocate(vfinal, source=vmatch)
    do j = 1, r%n
      i = int(r%id(1, j))
      k = int(r%id(2, j))
      if (r%id(3, j) > int(ct%nall, i8)) then
        ! Friction reaction on a master node (dam_put_back): a momentum,
        ! after the node's own put-back if it is a slave too (key order).
        vfinal(:, i, k) = vfinal(:, i, k) + r%val(:, j) / ct%all_mass(ct%own_contact(i))
      else
        vfinal(:, i, k) = r%val(:, j)
      end if
      has(i, k) = .true.
    end do
    do k = 1, ct%npair
      if (ct%pairs(k)%method /= METHOD_DAM) cycle
      do i = 1, ct%nown
        if (.not. (has(i, k) .or. touched(i, k))) cycle
        has(i, k) = .true.
        l = ct%own_local(i)
        mass = ct%all_mass(ct%own_contact(i))
        fck(:, i, k) = mass * (vfinal(:, i, k) - v_old(:, l)) / dt - force(:, l)
        ct%pairs(k)%partial(6:8) = ct%pairs(k)%partial(6:8) + mass * (vfinal(:, i, k) - &
            v_old(:, l)) - dt * force(:, l)
      end do
    end do
  end subroutine dam_forces

  !> Diagnostics of the step from every part's sums; released nodes from the
  !> owners. Collective.
  subroutine reduce_diagnostics(ct, has, dt)
    type(contact_t), intent(inout) :: ct
    logical, intent(in) :: has(:, :)
    real(rk), intent(in) :: dt
    real(rk) :: sums(8), pen_max
    integer :: k
    do k = 1, ct%npair
      associate(p => ct%pairs(k))
        if (p%method == METHOD_DLM) p%partial(6:8) = dt * p%partial(6:8)
        sums = [p%partial(1:2), p%partial(4:8), &
            real(count(p%was_active .and. .not. has(:, k)), rk)]
        p%was_active = has(:, k)
        call par_sum_array(sums)
        pen_max = par_max(p%partial(3))
        if (p%method == METHOD_DLM) then
          p%diag(1:8) = [sums(1), sums(2), pen_max, sqrt(sums(3) / max(sums(4), tiny(1.0_rk))), &
              sums(8), sums(5:7)]
        else
          p%diag(1:8) = [sums(1), sums(2), pen_max, sqrt(sums(3) / max(sums(4), 1.0_rk)), &
              sums(8), sums(5:7)]
        end if
      end associate
    end do
  end subroutine reduce_diagnostics

  !> A surface's facets, facet normals and areas, segment normals and nodal
  !> areas at x (once per cycle; every segment pair then reads them).
  subroutine geometry_update(x, surf, g)
    real(rk), intent(in) :: x(:, :)
    type(contact_surface_t), intent(in) :: surf
    type(surface_geometry_t), intent(inout) :: g
    integer :: s, i
    if (.not. allocated(g%facets)) allocate(g%facets(3, 3, SEGMENT_FACET_COUNT, surf%nseg), &
        g%normal(3, SEGMENT_FACET_COUNT, surf%nseg), g%area(SEGMENT_FACET_COUNT, surf%nseg), &
        g%quad_normal(3, surf%nseg), g%nodal_area(size(x, 2)))
    do s = 1, surf%nseg
      call segment_facets(x(:, surf%segments(:, s)), g%facets(:, :, :, s))
      do i = 1, SEGMENT_FACET_COUNT
        g%normal(:, i, s) = triangle_unit_normal(g%facets(:, :, i, s))
        g%area(i, s) = norm2(triangle_vector_area(g%facets(:, :, i, s)))
      end do
      g%quad_normal(:, s) = quad_unit_normal(x(:, surf%segments(:, s)))
    end do
    g%nodal_area = 0.0_rk
    call nodal_areas(x, surf, g%nodal_area)
  end subroutine geometry_update


  !> DLM geometry at x^n (the same for both stages, so computed once per
  !> cycle, in the predictor): every overlapping facet pair of facing
  !> segments with its nodes, shares, common normal and penetration. The
  !> facets of a segment pair are projected once on the common plane
  !> (coordinates relative to segment a's centre); the overlap centroid lies
  !> in that plane, and the penetration, a difference of two distances along
  !> the normal, does not depend on where along the normal it lies.
  subroutine dlm_geometry(ct, p)
    type(contact_t), intent(in) :: ct
    type(interface_t), intent(inout) :: p
    real(rk) :: na(3), nb(3), nrm(3), s0, centroid(3), pen, wh, wd, t1(3), t2(3), origin(3)
    real(rk) :: allowance, kept
    real(rk) :: box_a(4, SEGMENT_FACET_COUNT), box_b(4, SEGMENT_FACET_COUNT), seg_a(4), seg_b(4)
    real(rk) :: a2(2, 3, SEGMENT_FACET_COUNT), b2(2, 3, SEGMENT_FACET_COUNT), centre2(2)
    integer :: m, sa, sb, i, j, nodeh, noded
    logical :: a_hits

    call geometry_update(ct%x, p%a, p%ga)
    call geometry_update(ct%x, p%b, p%gb)
    p%nfp = 0
    if (.not. allocated(p%fp_node)) allocate(p%fp_node(2, 64), p%fp_real(FP_REALS, 64), &
        p%fp_key(64))
    associate(ga => p%ga, gb => p%gb)
      do m = 1, size(p%segment_pairs, 2)
        sa = p%segment_pairs(1, m)
        sb = p%segment_pairs(2, m)
        na = ga%quad_normal(:, sa)
        nb = gb%quad_normal(:, sb)
        if (.not. dot_product(na, nb) < FACING) cycle
        ! Hitting side: surface a, or in self-contact the lower segment id.
        a_hits = .true.
        if (p%self) a_hits = p%a%segment_id(sa) < p%b%segment_id(sb)
        if (a_hits) then
          nrm = na - nb
        else
          nrm = nb - na
        end if
        nrm = nrm / norm2(nrm)
        call tangent_basis(nrm, t1, t2)
        origin = 0.25_rk * (ct%x(:, p%a%segments(1, sa)) + ct%x(:, p%a%segments(2, sa)) + &
            ct%x(:, p%a%segments(3, sa)) + ct%x(:, p%a%segments(4, sa)))
        ! Segments whose projections do not meet have no overlap.
        call segment_box(ct%x, p%a%segments(:, sa), origin, t1, t2, seg_a)
        call segment_box(ct%x, p%b%segments(:, sb), origin, t1, t2, seg_b)
        if (.not. boxes_meet(seg_a, seg_b)) cycle
        ! Penetration beyond an allowance is what the velocity form's
        ! recovery removes: ALLOWANCE_SHARE of the audit's tolerance (a
        ! fraction of the segments' size, or the faceting sagitta, the
        ! mismatch of two faceted versions of one curved surface, left
        ! alone), plus the initial penetration the deck kept.
        if (p%spec%penetration_tolerance > 0.0_rk) then
          allowance = ALLOWANCE_SHARE * p%spec%penetration_tolerance
        else
          allowance = max(RECOVERY_ALLOWANCE * sqrt(min(sum(ga%area(:, sa)), &
              sum(gb%area(:, sb)))), ALLOWANCE_SHARE * max(p%lsag_a(sa), p%lsag_b(sb)))
        end if
        call project_facets(ga%facets(:, :, :, sa), origin, t1, t2, a2, box_a)
        call project_facets(gb%facets(:, :, :, sb), origin, t1, t2, b2, box_b)
        do i = 1, SEGMENT_FACET_COUNT
          if (.not. boxes_meet(box_a(:, i), seg_b)) cycle
          do j = 1, SEGMENT_FACET_COUNT
            if (.not. boxes_meet(box_a(:, i), box_b(:, j))) cycle
            if (a_hits) then
              call triangle_overlap_2d(a2(:, :, i), b2(:, :, j), s0, centre2)
            else
              call triangle_overlap_2d(b2(:, :, j), a2(:, :, i), s0, centre2)
            end if
            if (.not. s0 > AREA_TOLERANCE * min(ga%area(i, sa), gb%area(j, sb))) cycle
            centroid = origin + centre2(1) * t1 + centre2(2) * t2
            if (a_hits) then
              nodeh = p%a%segments(FACET_CORNER(i), sa)
              noded = p%b%segments(FACET_CORNER(j), sb)
              pen = plane_offset(ga%facets(:, 1, i, sa), ga%normal(:, i, sa), centroid, nrm) - &
                  plane_offset(gb%facets(:, 1, j, sb), gb%normal(:, j, sb), centroid, nrm)
              wh = covered(ga%normal(:, i, sa), s0, nrm) / ga%nodal_area(nodeh)
              wd = covered(gb%normal(:, j, sb), s0, nrm) / gb%nodal_area(noded)
            else
              nodeh = p%b%segments(FACET_CORNER(j), sb)
              noded = p%a%segments(FACET_CORNER(i), sa)
              pen = plane_offset(gb%facets(:, 1, j, sb), gb%normal(:, j, sb), centroid, nrm) - &
                  plane_offset(ga%facets(:, 1, i, sa), ga%normal(:, i, sa), centroid, nrm)
              wh = covered(gb%normal(:, j, sb), s0, nrm) / gb%nodal_area(nodeh)
              wd = covered(ga%normal(:, i, sa), s0, nrm) / ga%nodal_area(noded)
            end if
            ! The initial penetration the deck kept (contact_initial) is
            ! held, not pushed out.
            kept = max(p%offset(ct%all_of(nodeh)), p%offset(ct%all_of(noded)))
            ! Deeper than half a segment: the far side of a body, not contact.
            if (pen - kept > 0.5_rk * p%size) cycle
            call add_facet_pair(p, nodeh, noded, wh, wd, pen - kept, s0, nrm, &
                max(pen - kept - allowance, 0.0_rk), &
                p%pair_key(m) * 64_i8 + int(8 * (i - 1) + j - 1, i8), pen - kept)
          end do
        end do
      end do
    end associate

  end subroutine dlm_geometry

  !> Append one facet pair to the interface's cache, growing it when full.
  subroutine add_facet_pair(p, nodeh, noded, wh, wd, pen, s0, nrm, excess, key, gate)
    type(interface_t), intent(inout) :: p
    integer, intent(in) :: nodeh, noded
    real(rk), intent(in) :: wh, wd, pen, s0, nrm(3)
    real(rk), intent(in) :: excess !< penetration beyond the recovery allowance (>= 0)
    integer(i8), intent(in) :: key !< global order: segment pair, facet of a, facet of b
    real(rk), intent(in) :: gate !< penetration that gates the pair (the centroid's)
    integer, allocatable :: grown_node(:, :)
    integer(i8), allocatable :: grown_key(:)
    real(rk), allocatable :: grown_real(:, :)
    if (p%nfp == size(p%fp_node, 2)) then
      allocate(grown_node(2, 2 * p%nfp), grown_real(FP_REALS, 2 * p%nfp), grown_key(2 * p%nfp))
      grown_node(:, :p%nfp) = p%fp_node(:, :p%nfp)
      grown_real(:, :p%nfp) = p%fp_real(:, :p%nfp)
      grown_key(:p%nfp) = p%fp_key(:p%nfp)
      call move_alloc(grown_node, p%fp_node)
      call move_alloc(grown_real, p%fp_real)
      call move_alloc(grown_key, p%fp_key)
    end if
    p%nfp = p%nfp + 1
    p%fp_node(:, p%nfp) = [nodeh, noded]
    p%fp_real(:, p%nfp) = [wh, wd, pen, s0, nrm, excess, gate]
    p%fp_key(p%nfp) = key
  end subroutine add_facet_pair

  !> DLM: every overlapping facet pair of facing segments is a 1D contact pair
  !> (geometry from dlm_geometry, forces of the stage).
  subroutine dlm_step(ct, p, k, dt, final, out)
    type(contact_t), intent(in) :: ct
    type(interface_t), intent(inout) :: p
    integer, intent(in) :: k !< the interface's number
    real(rk), intent(in) :: dt !< the stage's step
    logical, intent(in) :: final !< the corrector (geometry cached by the predictor)
    type(records_t), intent(inout) :: out !< the contributions, for the owners
    real(rk), allocatable :: lambda(:), fc(:, :), ft(:, :)
    logical, allocatable :: gated(:)
    real(rk) :: nrm(3), s0, pen, wh, wd
    real(rk) :: mh, md, fh_, fd_, vh, vd, mu, fh, w, sum_force, pen_max
    real(rk) :: pen_sq, area_sum
    integer :: q, i, nodeh, noded, active, sweep

    if (.not. final .or. .not. allocated(p%fp_node)) call dlm_geometry(ct, p)
    allocate(lambda(p%nfp), gated(p%nfp), fc(3, ct%ncn))
    lambda = 0.0_rk
    fc = 0.0_rk
    ! Sweep 1 is the one-pass DLM: every pair from the free (hydro) state.
    ! Later sweeps (Gauss-Seidel, in the fixed pair order) add to each pair
    ! force the correction its residual approach asks for, given the contact
    ! forces of all pairs so far; sum(lambda) stays <= 0 per pair and each
    ! correction is applied equal and opposite, so momentum stays exact.
    do sweep = 1, max(p%spec%sweeps, 1)
      do q = 1, p%nfp
        nodeh = p%fp_node(1, q)
        noded = p%fp_node(2, q)
        wh = p%fp_real(1, q)
        wd = p%fp_real(2, q)
        pen = p%fp_real(3, q)
        nrm = p%fp_real(5:7, q)
        mh = ct%mass(nodeh) * wh
        md = ct%mass(noded) * wd
        mu = mh * md / (mh + md)
        vh = dot_product(ct%v(:, nodeh), nrm)
        vd = dot_product(ct%v(:, noded), nrm)
        w = vh - vd
        if (sweep == 1) then
          fh_ = dot_product(ct%f(:, nodeh), nrm) * wh
          fd_ = dot_product(ct%f(:, noded), nrm) * wd
          ! The gate: the penetration at the overlap centroid (dlm_geometry).
          call dlm_pair_force(p%form, mh, md, fh_, fd_, w, pen, p%fp_real(9, q), dt, &
              recovery_speed(q), fh, gated(q))
        else
          if (.not. gated(q) .or. p%form /= FORM_VELOCITY) cycle
          ! Residual approach at t^n+1 with every contact force so far.
          fh_ = dot_product(ct%f(:, nodeh) + fc(:, nodeh), nrm) * wh
          fd_ = dot_product(ct%f(:, noded) + fc(:, noded), nrm) * wd
          fh = min(lambda(q) + mu * (fd_ / md - fh_ / mh + (recovery_speed(q) - w) / dt), &
              0.0_rk)
        end if
        if (fh == lambda(q)) cycle
        fc(:, nodeh) = fc(:, nodeh) + (fh - lambda(q)) * nrm
        fc(:, noded) = fc(:, noded) - (fh - lambda(q)) * nrm
        lambda(q) = fh
      end do
    end do
    ! Coulomb friction (docs/contact.md, 5.1), from the final normal force
    ! of each pair. Skipped entirely without friction, so frictionless
    ! results are bitwise those of the code before it.
    if (p%spec%friction > 0.0_rk) then
      allocate(ft(3, p%nfp))
      ft = 0.0_rk
      do q = 1, p%nfp
        if (.not. lambda(q) < 0.0_rk) cycle
        nodeh = p%fp_node(1, q)
        noded = p%fp_node(2, q)
        wh = p%fp_real(1, q)
        wd = p%fp_real(2, q)
        nrm = p%fp_real(5:7, q)
        ft(:, q) = dlm_pair_friction(p%spec%friction, ct%mass(nodeh) * wh, &
            ct%mass(noded) * wd, ct%v(:, nodeh), ct%v(:, noded), ct%f(:, nodeh) * wh, &
            ct%f(:, noded) * wd, nrm, dt, lambda(q))
        fc(:, nodeh) = fc(:, nodeh) + ft(:, q)
        fc(:, noded) = fc(:, noded) - ft(:, q)
      end do
    end if
    ! The contributions: one per pair and node (in single-part mode, where
    ! Gauss-Seidel sweeps make the order global, one sum per node).
    if (p%single_part) then
      do i = 1, ct%ncn
        if (any(fc(:, i) /= 0.0_rk)) call add_record(out, ct%all_of(i), k, 0_i8, fc(:, i))
      end do
    else
      do q = 1, p%nfp
        if (lambda(q) == 0.0_rk) cycle
        nrm = p%fp_real(5:7, q)
        if (allocated(ft)) then
          call add_record(out, ct%all_of(p%fp_node(1, q)), k, p%fp_key(q), &
              lambda(q) * nrm + ft(:, q))
          call add_record(out, ct%all_of(p%fp_node(2, q)), k, p%fp_key(q), &
              -(lambda(q) * nrm + ft(:, q)))
        else
          call add_record(out, ct%all_of(p%fp_node(1, q)), k, p%fp_key(q), lambda(q) * nrm)
          call add_record(out, ct%all_of(p%fp_node(2, q)), k, p%fp_key(q), -(lambda(q) * nrm))
        end if
      end do
    end if

    active = 0
    sum_force = 0.0_rk
    pen_max = 0.0_rk
    pen_sq = 0.0_rk
    area_sum = 0.0_rk
    do q = 1, p%nfp
      if (.not. lambda(q) < 0.0_rk) cycle
      pen = p%fp_real(3, q)
      s0 = p%fp_real(4, q)
      active = active + 1
      sum_force = sum_force - lambda(q)
      if (pen > 0.0_rk) then
        pen_max = max(pen_max, pen)
        pen_sq = pen_sq + s0 * pen * pen
      end if
      area_sum = area_sum + s0
    end do
    p%partial(1:5) = [real(active, rk), sum_force, pen_max, pen_sq, area_sum]
    do i = 1, ct%ncn
      p%partial(6:8) = p%partial(6:8) + fc(:, i)
    end do
  contains

    !> Target approach speed of facet pair q in the velocity form: the
    !> separation that removes the fraction p%recovery of its penetration at
    !> t^n over the step (0 for a gap).
    pure real(rk) function recovery_speed(q) result(speed)
      integer, intent(in) :: q
      speed = -p%recovery * p%fp_real(8, q) / dt
    end function recovery_speed

  end subroutine dlm_step

  !> DAM geometry at x^n (once per cycle, in the predictor; both stages use
  !> x^n): the primary pairs within the capture distance of a full step, the
  !> facet overlaps of each slave node's facets with the facets of its primary
  !> segment's neighbourhood (projected on the slave facet's plane), and the
  !> RBF put-back weights.
  subroutine dam_geometry(ct, p, dt)
    type(contact_t), intent(in) :: ct
    type(interface_t), intent(inout) :: p
    real(rk), intent(in) :: dt !< the full step
    real(rk) :: nf(3), s0, centroid(3), t1(3), t2(3), box_s(4), box_m(4), seg_m(4), pos(3, 4)
    real(rk) :: capture
    integer :: q, n, k, e, ss, sm, i, j, c, ncand, nex
    integer :: candidates(64)
    logical :: ok

    call geometry_update(ct%x, p%a, p%ga)
    call geometry_update(ct%x, p%b, p%gb)
    capture = capture_of(p, 2.0_rk * ct%speed, dt)
    call primary_pairs(ct%x, p%b, p%test_pairs, capture, 0.5_rk * p%size, p%primary, &
        p%offset(ct%all_of))
    if (allocated(p%rbf)) deallocate(p%rbf, p%ex_start)
    allocate(p%rbf(4, size(p%primary)), p%ex_start(size(p%primary) + 1))
    if (.not. allocated(p%ex_master)) allocate(p%ex_master(64), p%ex_real(3, 64))
    nex = 0
    associate(gs => p%ga, gm => p%gb)
      do q = 1, size(p%primary)
        p%ex_start(q) = nex + 1
        n = p%primary(q)%node
        do k = 1, 4
          pos(:, k) = ct%x(:, p%b%segments(k, p%primary(q)%segment))
        end do
        if (p%slave_normal) call use_slave_normal(p%a, gs, n, p%primary(q)%normal)
        call rbf_weights(pos, ct%x(:, n), p%primary(q)%normal, p%rbf(:, q), ok)
        if (.not. ok) call bilinear_shape(p%primary(q)%xi, p%primary(q)%eta, p%rbf(:, q))
        call master_neighbourhood(p%b, p%primary(q)%segment, candidates, ncand)
        k = surface_node_index(p%a, int(n, ik))
        do e = p%a%node_start(k), p%a%node_start(k + 1) - 1
          ss = p%a%node_segments(e)
          c = findloc(p%a%segments(:, ss), n, dim=1)
          do i = 2 * c - 1, 2 * c
            nf = gs%normal(:, i, ss)
            call tangent_basis(nf, t1, t2)
            call facet_box(gs%facets(:, :, i, ss), t1, t2, box_s)
            do j = 1, ncand
              sm = candidates(j)
              call segment_box(ct%x, p%b%segments(:, sm), [0.0_rk, 0.0_rk, 0.0_rk], t1, t2, &
                  seg_m)
              if (.not. boxes_meet(box_s, seg_m)) cycle
              do k = 1, SEGMENT_FACET_COUNT
                if (.not. dot_product(nf, gm%normal(:, k, sm)) < FACING) cycle
                call facet_box(gm%facets(:, :, k, sm), t1, t2, box_m)
                if (.not. boxes_meet(box_s, box_m)) cycle
                call triangle_overlap(gs%facets(:, :, i, ss), gm%facets(:, :, k, sm), nf, s0, &
                    centroid)
                if (.not. s0 > AREA_TOLERANCE * min(gs%area(i, ss), gm%area(k, sm))) cycle
                call add_exchange(p%b%segments(FACET_CORNER(k), sm), &
                    covered(gm%normal(:, k, sm), s0, nf) / gm%nodal_area( &
                    p%b%segments(FACET_CORNER(k), sm)), s0 / gs%nodal_area(n), s0)
              end do
            end do
          end do
        end do
      end do
    end associate
    p%ex_start(size(p%primary) + 1) = nex + 1

  contains

    subroutine add_exchange(m, wm, ws, s0)
      integer(ik), intent(in) :: m
      real(rk), intent(in) :: wm, ws, s0
      integer, allocatable :: grown_master(:)
      real(rk), allocatable :: grown_real(:, :)
      if (nex == size(p%ex_master)) then
        allocate(grown_master(2 * nex), grown_real(3, 2 * nex))
        grown_master(:nex) = p%ex_master(:nex)
        grown_real(:, :nex) = p%ex_real(:, :nex)
        call move_alloc(grown_master, p%ex_master)
        call move_alloc(grown_real, p%ex_real)
      end if
      nex = nex + 1
      p%ex_master(nex) = m
      p%ex_real(:, nex) = [wm, ws, s0]
    end subroutine add_exchange

  end subroutine dam_geometry

  !> DAM with normal = 'slave': the contact normal of slave node n becomes the
  !> reverse of its own area-weighted normal (its facets on the slave
  !> surface), kept only where it faces the master (normal . ns < 0). The
  !> slave's hydro force is the pressure on those facets, so the constraint
  !> along that normal leaves no tangential part of it to drive the node
  !> along the interface; with the master facet's normal, on non-matching
  !> curved meshes the mismatch angle (about h/R) leaves a tangential
  !> pressure force that slides slave nodes and shears their zones.
  pure subroutine use_slave_normal(slave, gs, n, normal)
    type(contact_surface_t), intent(in) :: slave
    type(surface_geometry_t), intent(in) :: gs
    integer, intent(in) :: n !< the slave node (local contact index)
    real(rk), intent(inout) :: normal(3) !< the master's normal at the projection
    real(rk) :: ns(3)
    integer :: k, e, s, c, i
    ns = 0.0_rk
    k = surface_node_index(slave, int(n, ik))
    do e = slave%node_start(k), slave%node_start(k + 1) - 1
      s = slave%node_segments(e)
      c = findloc(slave%segments(:, s), n, dim=1)
      do i = 2 * c - 1, 2 * c
        ns = ns + gs%area(i, s) * gs%normal(:, i, s)
      end do
    end do
    if (norm2(ns) > 0.0_rk .and. dot_product(ns, normal) < 0.0_rk) normal = -ns / norm2(ns)
  end subroutine use_slave_normal

  !> DAM at the parts, first round: which slave nodes are enforced, and the
  !> exchange of mass, force and momentum over the facet overlaps of each
  !> enforced slave with the master facets (docs/contact.md, 6), as records
  !> for the owners of both nodes, keyed (slave, entry, side) in the order of
  !> a one-rank run.
  subroutine dam_exchange(ct, p, k, dt, final, out)
    type(contact_t), intent(in) :: ct
    type(interface_t), intent(inout) :: p
    integer, intent(in) :: k !< the interface's number
    real(rk), intent(in) :: dt !< the stage's step
    logical, intent(in) :: final !< the corrector (geometry cached by the predictor)
    type(records_t), intent(inout) :: out !< nv = 10: mass, force, momentum, master normal
    real(rk) :: nrm(3), shape(4), am, vm, as, vs, gfree, wm, ws, s0
    real(rk) :: buf(10)
    integer(i8) :: base
    integer :: q, n, c, e, m
    logical :: also_master

    ! The predictor's step is half the cycle's.
    if (.not. final .or. .not. allocated(p%primary)) call dam_geometry(ct, p, &
        merge(dt, 2.0_rk * dt, final))

    ! Which slave nodes are enforced: the free motion would close the gap.
    p%enforced = .false.
    do q = 1, size(p%primary)
      n = p%primary(q)%node
      nrm = p%primary(q)%normal
      call bilinear_shape(p%primary(q)%xi, p%primary(q)%eta, shape)
      am = 0.0_rk
      vm = 0.0_rk
      do c = 1, 4
        m = p%b%segments(c, p%primary(q)%segment)
        am = am + shape(c) * dot_product(ct%f(:, m), nrm) / ct%mass(m)
        vm = vm + shape(c) * dot_product(ct%v(:, m), nrm)
      end do
      as = dot_product(ct%f(:, n), nrm) / ct%mass(n)
      vs = dot_product(ct%v(:, n), nrm)
      gfree = p%primary(q)%gap + dt * (vs - vm) + 0.5_rk * dt * dt * (as - am)
      ! Release (3.7): the free motion at t^n+1 separates the slave from the
      ! master (tension); a residual penetration does not hold it. This is
      ! the rule of the unilateral rigid wall, so the mirror test holds.
      if (vs - vm + dt * (as - am) > 0.0_rk) cycle
      if (gfree < 0.0_rk) p%enforced(n) = .true.
    end do

    ! Exchange over the cached facet overlaps.
    do q = 1, size(p%primary)
      n = p%primary(q)%node
      if (.not. p%enforced(n)) cycle
      base = int(ct%all_of(n), i8) * 65536_i8
      ! The slave's own sums matter only where it is a master node too.
      also_master = surface_node_index(p%b, int(n, ik)) > 0
      do e = p%ex_start(q), p%ex_start(q + 1) - 1
        m = p%ex_master(e)
        wm = p%ex_real(1, e)
        ws = p%ex_real(2, e)
        s0 = p%ex_real(3, e)
        ! (Values assembled in a fixed-size buffer: an array constructor of
        ! sections is built on the heap.)
        if (also_master) then
          buf(1) = ct%mass(m) * wm
          buf(2:4) = ct%f(:, m) * wm
          buf(5:7) = ct%mass(m) * ct%v(:, m) * wm
          buf(8:10) = 0.0_rk
          call add_record(out, ct%all_of(n), k, base + int(2 * (e - p%ex_start(q)), i8), buf)
        end if
        buf(1) = ct%mass(n) * ws
        buf(2:4) = ct%f(:, n) * ws
        buf(5:7) = ct%mass(n) * ct%v(:, n) * ws
        buf(8:10) = s0 * p%primary(q)%normal
        call add_record(out, ct%all_of(m), k, base + int(2 * (e - p%ex_start(q)) + 1, i8), buf)
      end do
    end do
  end subroutine dam_exchange

  !> DAM at the parts, second round: the put-back-on of each enforced slave's
  !> normal velocity by RBF interpolation of the matched velocities vm of its
  !> master segment's nodes (docs/contact.md, 6); tangential motion is free
  !> (frictionless unless friction is given). vm are the velocities after the
  !> master matching and before any put-back (in self-contact a master node
  !> may be a slave too).
  !> With Coulomb friction (deck friction > 0; docs/contact.md, 6.1) the
  !> slave's tangential velocity relative to the master's interpolated
  !> velocity (the same RBF weights) is reduced by at most friction times
  !> the put-back's normal velocity change, and each node of the master
  !> segment gets the opposite momentum times its weight (the weights sum
  !> to 1): records keyed after every put-back record (key > nall), which
  !> dam_forces adds to the master's velocity as momentum.
  subroutine dam_put_back(ct, p, k, dt, vm, out)
    type(contact_t), intent(in) :: ct
    type(interface_t), intent(inout) :: p
    integer, intent(in) :: k !< the interface's number
    real(rk), intent(in) :: dt !< the stage's step
    real(rk), intent(in) :: vm(:, :) !< (3, ncn) matched velocities of the local set
    type(records_t), intent(inout) :: out !< nv = 3: the slave's final velocity
    real(rk) :: nrm(3), target, pen, pen_max, pen_sq, sum_force, vnew(3), vmi(3), dv(3)
    integer :: q, n, c, active, npen

    active = 0
    npen = 0
    pen_max = 0.0_rk
    pen_sq = 0.0_rk
    sum_force = 0.0_rk
    do q = 1, size(p%primary)
      n = p%primary(q)%node
      if (.not. p%enforced(n)) cycle
      active = active + 1
      nrm = p%primary(q)%normal
      target = 0.0_rk
      do c = 1, 4
        target = target + p%rbf(c, q) * dot_product(vm(:, p%b%segments(c, &
            p%primary(q)%segment)), nrm)
      end do
      vnew = dam_put_back_velocity(vm(:, n), nrm, target)
      if (p%spec%friction > 0.0_rk) then
        vmi = 0.0_rk
        do c = 1, 4
          vmi = vmi + p%rbf(c, q) * vm(:, p%b%segments(c, p%primary(q)%segment))
        end do
        dv = dam_friction_velocity(p%spec%friction, vnew, vmi, nrm, &
            target - dot_product(vm(:, n), nrm))
        vnew = vnew + dv
        do c = 1, 4
          call add_record(out, ct%all_of(p%b%segments(c, p%primary(q)%segment)), k, &
              int(ct%nall, i8) + 4_i8 * int(ct%all_of(n), i8) + int(c - 1, i8), &
              -(ct%mass(n) * p%rbf(c, q)) * dv)
        end do
      end if
      call add_record(out, ct%all_of(n), k, int(ct%all_of(n), i8), vnew)
      sum_force = sum_force + max(dot_product(ct%mass(n) * (vnew - ct%v(:, n)) / dt - &
          ct%f(:, n), nrm), 0.0_rk)
      pen = -p%primary(q)%gap
      if (pen > 0.0_rk) then
        pen_max = max(pen_max, pen)
        pen_sq = pen_sq + pen * pen
        npen = npen + 1
      end if
    end do
    p%partial(1:5) = [real(active, rk), sum_force, pen_max, pen_sq, real(npen, rk)]
  end subroutine dam_put_back

  !> After the velocity update: the work of the contact forces over the step
  !> on the owned nodes (local sum; the caller reduces it).
  subroutine contact_work_update(ct, v_old, v_new, dt, work)
    type(contact_t), intent(inout) :: ct
    real(rk), intent(in) :: v_old(:, :), v_new(:, :)
    real(rk), intent(in) :: dt
    real(rk), intent(out) :: work !< this rank's contact work of the step
    integer :: i, n, k
    work = 0.0_rk
    do i = 1, ct%nown
      n = ct%own_local(i)
      work = work + 0.5_rk * dt * dot_product(ct%fc(:, i), &
          v_old(:, n) + v_new(:, n))
    end do
    do k = 1, ct%npair
      associate(p => ct%pairs(k))
        p%work_step = 0.0_rk
        do i = 1, ct%nown
          n = ct%own_local(i)
          p%work_step = p%work_step + 0.5_rk * dt * dot_product(p%fc_own(:, i), &
              v_old(:, n) + v_new(:, n))
        end do
      end associate
    end do
  end subroutine contact_work_update

  !> Diagnostics of every pair, (CONTACT_DIAG_COUNT, npair), replicated.
  function contact_diagnostics(ct) result(diag)
    type(contact_t), intent(in) :: ct
    real(rk), allocatable :: diag(:, :)
    integer :: k
    allocate(diag(CONTACT_DIAG_COUNT, ct%npair))
    do k = 1, ct%npair
      diag(:, k) = ct%pairs(k)%diag
    end do
  end function contact_diagnostics

  !> End-of-run summary on rank 0: the contact time split (largest over the
  !> ranks) and the local sets against the whole contact surface. Collective.
  subroutine contact_report(ct, loop_seconds)
    type(contact_t), intent(in) :: ct
    real(rk), intent(in) :: loop_seconds !< this rank's time loop without dumps
    real(rk) :: search, enforce, migrate, total, loop, whole, local, wait, audit
    integer :: largest, smallest, k
    search = par_max(ct%search_seconds)
    enforce = par_max(ct%enforce_seconds)
    migrate = par_max(ct%migrate_seconds)
    wait = par_max(ct%wait_seconds)
    audit = par_max(ct%audit_seconds)
    total = par_max(ct%search_seconds + ct%enforce_seconds + ct%migrate_seconds)
    largest = par_max(ct%ncn_max)
    smallest = -par_max(-ct%ncn_max)
    loop = par_max(loop_seconds)
    ! Memory: the static whole-surface data every rank holds, and this part's
    ! working data (local set, local surfaces, geometry and pair caches).
    whole = real(ct%nall, rk) * real(storage_size(ct%all_gid) + storage_size(ct%all_mass) + &
        2 * storage_size(ct%all_owner), rk) / 8.0_rk
    local = real(ct%ncn_max, rk) * real(10 * storage_size(1.0_rk) + storage_size(1), rk) / 8.0_rk
    do k = 1, ct%npair
      associate(p => ct%pairs(k))
        whole = whole + surface_bytes(p%all_a) + surface_bytes(p%all_b)
        local = local + surface_bytes(p%a) + surface_bytes(p%b) + geometry_bytes(p%ga) + &
            geometry_bytes(p%gb)
        if (allocated(p%fp_real)) local = local + real(size(p%fp_real), rk) * 8.0_rk + &
            real(size(p%fp_node), rk) * 4.0_rk + real(size(p%fp_key), rk) * 8.0_rk
        if (allocated(p%ex_real)) local = local + real(size(p%ex_real), rk) * 8.0_rk + &
            real(size(p%ex_master), rk) * 4.0_rk
      end associate
    end do
    whole = par_max(whole)
    local = par_max(local)
    if (par_rank() /= 0) return
    write(output_unit, '(a,3(f10.3,a),f6.1,a)') 'impact3d: contact ', search, &
        ' s search and RCB, ', enforce, ' s enforcement, ', migrate, ' s migration (', &
        100.0_rk * total / max(loop, 1.0e-9_rk), &
        '% of the loop; largest over the ranks)'
    write(output_unit, '(a,f10.3,a,i0,a,f6.1,a)') 'impact3d: contact audit ', audit, ' s (', &
        ct%audits, ' audits, ', 100.0_rk * audit / max(loop, 1.0e-9_rk), &
        '% of the loop; largest over the ranks, not in the contact times above)'
    if (par_size() > 1) write(output_unit, '(a,f10.3,a)') 'impact3d: contact entry wait ', &
        wait, ' s (the other ranks'' hydro: load imbalance; largest over the ranks, not in the '// &
        'contact times)'
    write(output_unit, '(a,i0,a,i0,a,i0,a,i0,a)') 'impact3d: contact local sets ', smallest, &
        ' to ', largest, ' nodes per rank of ', ct%nall, ' contact nodes; ', ct%rebuilds, &
        ' global searches'
    if (ct%balanced_searches > 0) write(output_unit, '(a,f6.3,a,f6.3,a,i0,a,i0,a)') &
        'impact3d: contact pairs per part, largest / mean: ', &
        ct%balance_sum / real(ct%balanced_searches, rk), ' on average, ', ct%balance_worst, &
        ' at worst; ', ct%recuts, ' of ', ct%rebuilds, ' searches re-cut the RCB (load drift)'
    write(output_unit, '(a,f10.3,a,f10.3,a)') 'impact3d: contact memory per rank ', &
        local / 1.0e6_rk, ' MB working set (largest), ', whole / 1.0e6_rk, &
        ' MB whole-surface topology (every rank)'

  contains

    real(rk) function surface_bytes(surf) result(b)
      type(contact_surface_t), intent(in) :: surf
      b = 0.0_rk
      if (.not. allocated(surf%segments)) return
      b = real(size(surf%segments) + size(surf%nodes) + size(surf%node_start) + &
          size(surf%node_segments) + size(surf%neighbours) + size(surf%edge_convex), rk) * 4.0_rk + &
          real(size(surf%segment_id), rk) * 8.0_rk
    end function surface_bytes

    real(rk) function geometry_bytes(g) result(b)
      type(surface_geometry_t), intent(in) :: g
      b = 0.0_rk
      if (.not. allocated(g%facets)) return
      b = real(size(g%facets) + size(g%normal) + size(g%area) + size(g%quad_normal) + &
          size(g%nodal_area), rk) * 8.0_rk
    end function geometry_bytes

  end subroutine contact_report




end module contact_enforce
