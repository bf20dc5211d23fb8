!> Contact enforcement: DAM (discrete accurate matching, master-slave) and DLM
!> (discrete Lagrangian multiplier, symmetric) of Jia, Gong, Zhang & Liu
!> (J. Comput. Phys. 267 (2014) 247-285), as written in CONTACT.md sections 3-4.
!> This is the narrow interface between the hydro state and contact.
!>
!> Where it sits. In each stage, after the hydro forces f of the stage are
!> known and before v = v^n + h (f + fc)/m (h = dt/2 in the predictor, dt in
!> the corrector): contact_apply returns the contact force fc of every owned
!> contact node, added to the node force, so the boundary conditions
!> re-imposed by the velocity update come after it. CONTACT.md 4b puts contact
!> in the corrector only; the rigid wall acts in both stages, and a contact
!> that skips the predictor lets the half-step geometry interpenetrate, so the
!> contact pressure lags half a step and the mirror test fails (2e-3 of the
!> body size on a Taylor rod). The predictor call does no search; only the
!> corrector's forces do work and give the diagnostics.
!> Both methods are expressed as a contact force: DLM's pair forces directly,
!> DAM's corrected velocities v' as fc = m (v' - v^n)/dt - f. The work of the
!> contact forces over the step (trapezoid velocity) is the contact work of
!> the energy balance.
!>
!> Replicated contact (until the RCB decomposition): the positions x^n,
!> velocities v^n and forces f of all contact nodes are gathered from their
!> owners (one sum-reduction of exact zeros and one owner value, so bitwise
!> the owner's value on every rank); every rank then runs the same search and
!> enforcement in the same order and keeps the results of its owned nodes.
!> Results are bitwise independent of the rank count.
!>
!> Contact index space. The nodes of all contact surfaces, sorted by global
!> id, are numbered 1..ncn; the surfaces are rebuilt in this numbering, so all
!> contact arrays are (3, ncn) and the order of every loop is fixed by global
!> ids.
!>
!> Closing condition (both methods, CONTACT.md sections 3.7 and 4). A pair is
!> enforced when the free motion (hydro forces only) would close its gap by
!> the end of the step: pen_free = pen + dt w + dt^2/2 (ah - ad) > 0, w the
!> approach velocity and ah - ad the relative free acceleration along the
!> normal. Otherwise the pair is released (tension, or opening faster than the
!> other side follows). The same rule gives release and re-contact in DAM and
!> DLM.
!>
!> DLM forms (deck key `form`): with mu = Mh Md/(Mh + Md),
!>   coordinate: fh = mu (Fd/Md - Fh/Mh + (vd - vh)/(dt/2) - pen/(dt^2/2)),
!>   velocity:   fh = mu (Fd/Md - Fh/Mh + (vd - vh)/dt), gated by pen_free > 0,
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
  use mesh_global, only: global_mesh_t, NAME_LEN
  use mesh_local, only: mesh_t
  use contact_geometry, only: segment_facets, corner_areas, quad_unit_normal, &
      triangle_unit_normal, triangle_overlap, triangle_overlap_2d, triangle_vector_area, SEGMENT_FACET_COUNT, &
      FACET_CORNER, tangent_basis
  use contact_surface, only: contact_surface_t, surface_build, surface_from_segments, &
      surface_update_edges, surface_node_index, set_names_of
  use contact_search, only: bucket_search, primary_pairs, primary_pair_t, segment_pair_search, &
      search_interval, find_key, sort_real
  use contact_rbf, only: rbf_weights
  use parallel_env, only: par_sum_array
  implicit none
  private
  public :: contact_setup, contact_apply, contact_work_update, contact_diagnostics

  integer, parameter, public :: METHOD_DAM = 1, METHOD_DLM = 2
  integer, parameter, public :: FORM_COORDINATE = 1, FORM_VELOCITY = 2, FORM_COMBINED = 3
  !> Diagnostic columns per contact pair.
  !> active: enforced pairs (DLM facet pairs, DAM slave nodes); force: total
  !> normal force; pen_max, pen_rms: largest and RMS penetration at t^n;
  !> released: nodes in contact last step and not now; dmom: momentum the
  !> contact forces added over the step (zero to round-off for DLM).
  integer, parameter, public :: CONTACT_DIAG_COUNT = 8
  character(len=*), parameter, public :: CONTACT_DIAG_NAMES(CONTACT_DIAG_COUNT) = [ &
      character(len=12) :: 'active', 'force', 'pen_max', 'pen_rms', 'released', &
      'dmom_x', 'dmom_y', 'dmom_z']
  !> Facets facing each other: n_a . n_b below this.
  real(rk), parameter :: FACING = -0.2_rk
  !> Overlaps smaller than this fraction of the smaller facet's area are
  !> ignored: slivers between facets of neighbouring nodes that coincide in
  !> one projection but not in the slightly tilted common plane of another
  !> segment pair (relative size tilt x penetration / zone, ~1e-12 on the
  !> mirror test). They carry less than this share of a node's force.
  real(rk), parameter :: AREA_TOLERANCE = 1.0e-8_rk

  !> Length of a contact surface's list of face-set names.
  integer, parameter, public :: SURFACE_LEN = 256

  !> One &contact group as read from the deck.
  type, public :: contact_spec_t
    character(len=NAME_LEN) :: name = ''
    character(len=SURFACE_LEN) :: surface_a = '' !< face sets (names, blank or comma separated)
    character(len=SURFACE_LEN) :: surface_b = '' !< face sets (= surface_a: self-contact)
    character(len=8) :: method = '' !< 'dam' or 'dlm'
    character(len=1) :: master = 'b' !< DAM master side
    character(len=12) :: form = 'velocity' !< DLM: coordinate, velocity, combined
    real(rk) :: capture = 0.0_rk !< largest open gap treated as contact (0 = automatic)
    real(rk) :: penetration_warning = huge(1.0_rk) !< warn above this penetration
    real(rk) :: search_margin = 0.0_rk !< territory margin (0 = automatic)
    integer :: search_every = 0 !< cycles between global searches (0 = automatic)
    integer :: sweeps = 1 !< DLM: Gauss-Seidel sweeps of the pair forces (1 = one pass)
  end type contact_spec_t

  !> Geometry of one surface at x^n, computed once per cycle (in the
  !> predictor; both stages use x^n) and shared by every segment pair.
  type :: surface_geometry_t
    real(rk), allocatable :: facets(:, :, :, :) !< (3, 3, SEGMENT_FACET_COUNT, nseg)
    real(rk), allocatable :: normal(:, :, :) !< (3, SEGMENT_FACET_COUNT, nseg) facet unit normals
    real(rk), allocatable :: area(:, :) !< (SEGMENT_FACET_COUNT, nseg) facet areas
    real(rk), allocatable :: quad_normal(:, :) !< (3, nseg) segment unit normals
    real(rk), allocatable :: nodal_area(:) !< (ncn) dual-cell areas of the surface's nodes
  end type surface_geometry_t

  !> One contact pair (interface) in contact-index space.
  type, public :: interface_t
    type(contact_spec_t), public :: spec
    integer :: method = METHOD_DLM
    integer :: form = FORM_VELOCITY
    logical :: self = .false.
    type(contact_surface_t) :: a, b !< b = master for DAM
    real(rk) :: size = 0.0_rk !< median segment size of both surfaces
    real(rk) :: margin = 0.0_rk !< territory margin in use
    integer(i8) :: next_search = 0 !< cycle of the next global search
    integer, allocatable :: segment_pairs(:, :) !< DLM: (2, n) segment of a, of b
    integer, allocatable :: test_pairs(:, :) !< DAM: (2, n) slave node, master segment
    logical, allocatable :: was_active(:) !< (ncn) node carried contact force last step
    integer :: nfp = 0 !< DLM facet pairs of the cycle
    integer, allocatable :: fp_node(:, :) !< (2, nfp) hitting and target node
    real(rk), allocatable :: fp_real(:, :) !< (7, nfp) shares wh, wd, pen, s0, normal
    type(surface_geometry_t) :: ga, gb !< geometry of a and b at x^n
    type(primary_pair_t), allocatable :: primary(:) !< DAM: the cycle's primary pairs
    real(rk), allocatable :: rbf(:, :) !< DAM: (4, nprimary) put-back weights
    integer, allocatable :: ex_start(:) !< DAM: (nprimary + 1) exchange entries of a pair
    integer, allocatable :: ex_master(:) !< DAM: master node of an exchange entry
    real(rk), allocatable :: ex_real(:, :) !< DAM: (3, nex) shares wm, ws and overlap s0
    real(rk), public :: diag(CONTACT_DIAG_COUNT) = 0.0_rk !< last step's diagnostics
    logical, public :: warned = .false. !< the penetration warning was given
  end type interface_t

  !> All contact of a run.
  type, public :: contact_t
    integer :: npair = 0
    type(interface_t), allocatable :: pairs(:)
    integer :: ncn = 0 !< contact nodes
    integer(i8), allocatable :: gid(:) !< (ncn) their global ids, ascending
    real(rk), allocatable :: mass(:) !< (ncn) nodal masses (fixed)
    integer :: nown = 0 !< owned contact nodes of this rank
    integer, allocatable :: own_contact(:) !< (nown) contact index
    integer, allocatable :: own_local(:) !< (nown) local node index
    real(rk), allocatable :: x(:, :), v(:, :), f(:, :) !< (3, ncn) replicated x^n, v^n, f
    real(rk), allocatable :: fc(:, :) !< (3, ncn) contact force of the step
    integer, allocatable :: pair_of_node(:) !< scratch
    real(rk) :: search_seconds = 0.0_rk, enforce_seconds = 0.0_rk
  end type contact_t

contains

  !> Build the contact surfaces in contact-index space, the owned-node map and
  !> the nodal masses. Problems go to status (group, key, reason).
  subroutine contact_setup(specs, global, mesh, node_mass, ct, status)
    type(contact_spec_t), intent(in) :: specs(:)
    type(global_mesh_t), intent(in) :: global
    type(mesh_t), intent(in) :: mesh
    real(rk), intent(in) :: node_mass(:) !< (nnode local) nodal masses
    type(contact_t), intent(inout) :: ct
    type(status_t), intent(inout) :: status
    type(contact_surface_t), allocatable :: raw_a(:), raw_b(:)
    integer(i8), allocatable :: all(:)
    real(rk), allocatable :: xc(:, :), packed(:, :)
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
    ct%ncn = size(all)
    call move_alloc(all, ct%gid)
    allocate(xc(3, ct%ncn))
    xc = global%coordinates(:, ct%gid)
    do k = 1, ct%npair
      call renumber(raw_a(k), ct%pairs(k)%a)
      call renumber(raw_b(k), ct%pairs(k)%b)
      ct%pairs(k)%size = 0.5_rk * (median_size(xc, ct%pairs(k)%a) + &
          median_size(xc, ct%pairs(k)%b))
      allocate(ct%pairs(k)%was_active(ct%ncn))
      ct%pairs(k)%was_active = .false.
    end do

    ! Owned contact nodes of this rank.
    ct%nown = 0
    allocate(ct%own_contact(mesh%nnode_owned), ct%own_local(mesh%nnode_owned))
    do n = 1, mesh%nnode_owned
      i = find_key(ct%gid, mesh%node_gid(n))
      if (i == 0) cycle
      ct%nown = ct%nown + 1
      ct%own_contact(ct%nown) = i
      ct%own_local(ct%nown) = n
    end do
    allocate(packed(1, ct%ncn))
    packed = 0.0_rk
    do i = 1, ct%nown
      packed(1, ct%own_contact(i)) = node_mass(ct%own_local(i))
    end do
    call par_sum_array(packed(1, :))
    ct%mass = packed(1, :)
    allocate(ct%x(3, ct%ncn), ct%v(3, ct%ncn), ct%f(3, ct%ncn), ct%fc(3, ct%ncn))

  contains

    subroutine renumber(raw, surf)
      type(contact_surface_t), intent(in) :: raw
      type(contact_surface_t), intent(inout) :: surf
      integer(ik), allocatable :: segments(:, :)
      integer :: s, c
      allocate(segments(4, raw%nseg))
      do s = 1, raw%nseg
        do c = 1, 4
          segments(c, s) = int(find_key(ct%gid, int(raw%segments(c, s), i8)), ik)
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
    call sort_real(sizes)
    h = sizes((surf%nseg + 1) / 2)
  end function median_size

  !> Contact forces of the step for the owned nodes: force(:, local) += fc.
  !> x_old, v_old: positions and velocities at t^n; force: hydro corrector force.
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
    real(rk), allocatable :: packed(:)
    real(rk) :: t0, t1
    integer :: i, k, c

    if (ct%npair == 0) return
    ! Gather x^n, v^n and f of all contact nodes (replicated).
    allocate(packed(9 * ct%ncn))
    packed = 0.0_rk
    do i = 1, ct%nown
      c = 9 * (ct%own_contact(i) - 1)
      packed(c + 1:c + 3) = x_old(:, ct%own_local(i))
      packed(c + 4:c + 6) = v_old(:, ct%own_local(i))
      packed(c + 7:c + 9) = force(:, ct%own_local(i))
    end do
    call par_sum_array(packed)
    do c = 1, ct%ncn
      ct%x(:, c) = packed(9 * c - 8:9 * c - 6)
      ct%v(:, c) = packed(9 * c - 5:9 * c - 3)
      ct%f(:, c) = packed(9 * c - 2:9 * c)
    end do
    ct%fc = 0.0_rk

    do k = 1, ct%npair
      t0 = wall_clock()
      call search_if_due(ct, ct%pairs(k), dt, cycle)
      t1 = wall_clock()
      ct%search_seconds = ct%search_seconds + (t1 - t0)
      select case (ct%pairs(k)%method)
      case (METHOD_DLM)
        call dlm_step(ct, ct%pairs(k), dt, final)
      case (METHOD_DAM)
        call dam_step(ct, ct%pairs(k), dt, final)
      end select
      ct%enforce_seconds = ct%enforce_seconds + (wall_clock() - t1)
    end do

    do i = 1, ct%nown
      force(:, ct%own_local(i)) = force(:, ct%own_local(i)) + ct%fc(:, ct%own_contact(i))
    end do
  end subroutine contact_apply

  !> Global search when due: margin and interval from the relative speed.
  subroutine search_if_due(ct, p, dt, cycle)
    type(contact_t), intent(in) :: ct
    type(interface_t), intent(inout) :: p
    real(rk), intent(in) :: dt
    integer(i8), intent(in) :: cycle
    real(rk) :: speed
    integer :: every, i
    if (cycle < p%next_search .and. allocated(p%segment_pairs)) return
    p%margin = p%spec%search_margin
    if (.not. p%margin > 0.0_rk) p%margin = 0.5_rk * p%size
    speed = 0.0_rk
    do i = 1, ct%ncn
      speed = max(speed, norm2(ct%v(:, i)))
    end do
    speed = 2.0_rk * speed
    every = p%spec%search_every
    if (every == 0) every = search_interval(p%margin, capture_of(p, speed, dt), speed, dt, &
        1.2_rk, 50)
    p%next_search = cycle + int(every, i8)
    call surface_update_edges(p%b, ct%x)
    if (p%self) call surface_update_edges(p%a, ct%x)
    call segment_pair_search(ct%x, p%a, p%b, p%self, p%margin, p%segment_pairs)
    if (p%method == METHOD_DAM) then
      call bucket_search(ct%x, p%a, p%b, p%self, p%margin, p%test_pairs)
      if (p%self) call keep_lower_side(p%a, p%test_pairs)
    end if
  end subroutine search_if_due

  !> DAM self-contact: a node is the slave of a segment only from the side
  !> with the lower segment ids (its lowest segment id below the segment's),
  !> so each pair of facing sides is matched once, as two surfaces would be
  !> (both sides as slaves would exchange everything twice).
  subroutine keep_lower_side(surf, pairs)
    type(contact_surface_t), intent(in) :: surf
    integer, allocatable, intent(inout) :: pairs(:, :) !< (2, n) node, segment
    integer(i8) :: lowest
    integer :: m, kept, k
    kept = 0
    do m = 1, size(pairs, 2)
      k = surface_node_index(surf, int(pairs(1, m), ik))
      lowest = minval(surf%segment_id(surf%node_segments(surf%node_start(k): &
          surf%node_start(k + 1) - 1)))
      if (.not. lowest < surf%segment_id(pairs(2, m))) cycle
      kept = kept + 1
      pairs(:, kept) = pairs(:, m)
    end do
    pairs = pairs(:, :kept)
  end subroutine keep_lower_side

  !> Capture tolerance: the deck's, or twice the closing distance of one step.
  pure real(rk) function capture_of(p, speed, dt) result(capture)
    type(interface_t), intent(in) :: p
    real(rk), intent(in) :: speed, dt
    capture = p%spec%capture
    if (.not. capture > 0.0_rk) capture = max(2.0_rk * speed * dt, 1.0e-3_rk * p%size)
  end function capture_of

  !> Nodal (dual-cell) areas of a surface's nodes, indexed by contact index.
  subroutine nodal_areas(x, surf, area)
    real(rk), intent(in) :: x(:, :)
    type(contact_surface_t), intent(in) :: surf
    real(rk), intent(inout) :: area(:) !< (ncn), zeroed here on the surface nodes
    real(rk) :: corner(4)
    integer :: s, c
    do s = 1, surf%nseg
      area(surf%segments(:, s)) = 0.0_rk
    end do
    do s = 1, surf%nseg
      call corner_areas(x(:, surf%segments(:, s)), corner)
      do c = 1, 4
        area(surf%segments(c, s)) = area(surf%segments(c, s)) + corner(c)
      end do
    end do
  end subroutine nodal_areas

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

  !> Bounding box of a segment's corners projected on the plane spanned by
  !> t1, t2 (its facets' centre and midpoints lie inside it), relative to origin.
  pure subroutine segment_box(x, corners, origin, t1, t2, box)
    real(rk), intent(in) :: x(:, :), origin(3), t1(3), t2(3)
    integer(ik), intent(in) :: corners(4)
    real(rk), intent(out) :: box(4)
    real(rk) :: u, w
    integer :: c
    box = [huge(1.0_rk), -huge(1.0_rk), huge(1.0_rk), -huge(1.0_rk)]
    do c = 1, 4
      u = dot_product(x(:, corners(c)) - origin, t1)
      w = dot_product(x(:, corners(c)) - origin, t2)
      box = [min(box(1), u), max(box(2), u), min(box(3), w), max(box(4), w)]
    end do
  end subroutine segment_box

  !> A segment's facets projected on the plane spanned by t1, t2 (relative to
  !> origin) and their bounding boxes.
  pure subroutine project_facets(facets, origin, t1, t2, f2, box)
    real(rk), intent(in) :: facets(3, 3, SEGMENT_FACET_COUNT), origin(3), t1(3), t2(3)
    real(rk), intent(out) :: f2(2, 3, SEGMENT_FACET_COUNT), box(4, SEGMENT_FACET_COUNT)
    integer :: i, v
    do i = 1, SEGMENT_FACET_COUNT
      do v = 1, 3
        f2(1, v, i) = dot_product(facets(:, v, i) - origin, t1)
        f2(2, v, i) = dot_product(facets(:, v, i) - origin, t2)
      end do
      box(:, i) = [minval(f2(1, :, i)), maxval(f2(1, :, i)), minval(f2(2, :, i)), &
          maxval(f2(2, :, i))]
    end do
  end subroutine project_facets


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
    real(rk) :: box_a(4, SEGMENT_FACET_COUNT), box_b(4, SEGMENT_FACET_COUNT), seg_a(4), seg_b(4)
    real(rk) :: a2(2, 3, SEGMENT_FACET_COUNT), b2(2, 3, SEGMENT_FACET_COUNT), centre2(2)
    integer :: m, sa, sb, i, j, nodeh, noded
    logical :: a_hits

    call geometry_update(ct%x, p%a, p%ga)
    call geometry_update(ct%x, p%b, p%gb)
    p%nfp = 0
    if (.not. allocated(p%fp_node)) allocate(p%fp_node(2, 64), p%fp_real(7, 64))
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
            ! Deeper than half a segment: the far side of a body, not contact.
            if (pen > 0.5_rk * p%size) cycle
            call add_facet_pair(p, nodeh, noded, wh, wd, pen, s0, nrm)
          end do
        end do
      end do
    end associate
  end subroutine dlm_geometry

  !> Append one facet pair to the interface's cache, growing it when full.
  subroutine add_facet_pair(p, nodeh, noded, wh, wd, pen, s0, nrm)
    type(interface_t), intent(inout) :: p
    integer, intent(in) :: nodeh, noded
    real(rk), intent(in) :: wh, wd, pen, s0, nrm(3)
    integer, allocatable :: grown_node(:, :)
    real(rk), allocatable :: grown_real(:, :)
    if (p%nfp == size(p%fp_node, 2)) then
      allocate(grown_node(2, 2 * p%nfp), grown_real(7, 2 * p%nfp))
      grown_node(:, :p%nfp) = p%fp_node(:, :p%nfp)
      grown_real(:, :p%nfp) = p%fp_real(:, :p%nfp)
      call move_alloc(grown_node, p%fp_node)
      call move_alloc(grown_real, p%fp_real)
    end if
    p%nfp = p%nfp + 1
    p%fp_node(:, p%nfp) = [nodeh, noded]
    p%fp_real(:, p%nfp) = [wh, wd, pen, s0, nrm]
  end subroutine add_facet_pair

  !> DLM: every overlapping facet pair of facing segments is a 1D contact pair
  !> (geometry from dlm_geometry, forces of the stage).
  subroutine dlm_step(ct, p, dt, final)
    type(contact_t), intent(inout) :: ct
    type(interface_t), intent(inout) :: p
    real(rk), intent(in) :: dt !< the stage's step
    logical, intent(in) :: final !< the corrector: update the diagnostics
    real(rk), allocatable :: lambda(:), fc(:, :)
    logical, allocatable :: gated(:), active_node(:)
    real(rk) :: nrm(3), s0, pen, wh, wd
    real(rk) :: mh, md, fh_, fd_, vh, vd, mu, fh, pen_free, w, target, sum_force, pen_max
    real(rk) :: pen_sq, momentum(3), area_sum
    integer :: q, i, nodeh, noded, active, released, sweep

    if (.not. final .or. .not. allocated(p%fp_node)) call dlm_geometry(ct, p)
    allocate(lambda(p%nfp), gated(p%nfp), fc(3, ct%ncn), active_node(ct%ncn))
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
          pen_free = pen + dt * w + 0.5_rk * dt * dt * (fh_ / mh - fd_ / md)
          gated(q) = pen_free > 0.0_rk .or. p%form == FORM_COORDINATE
          select case (p%form)
          case (FORM_COORDINATE)
            fh = mu * (fd_ / md - fh_ / mh - w / (0.5_rk * dt) - pen / (0.5_rk * dt * dt))
          case (FORM_VELOCITY)
            fh = 0.0_rk
            if (gated(q)) fh = mu * (fd_ / md - fh_ / mh - w / dt)
          case default
            fh = 0.0_rk
            if (gated(q)) then
              target = -max(pen + 0.5_rk * dt * w, 0.0_rk) / dt
              fh = mu * (fd_ / md - fh_ / mh + (target - w) / dt)
            end if
          end select
          fh = min(fh, 0.0_rk)
        else
          if (.not. gated(q) .or. p%form /= FORM_VELOCITY) cycle
          ! Residual approach at t^n+1 with every contact force so far.
          fh_ = dot_product(ct%f(:, nodeh) + fc(:, nodeh), nrm) * wh
          fd_ = dot_product(ct%f(:, noded) + fc(:, noded), nrm) * wd
          fh = min(lambda(q) + mu * (fd_ / md - fh_ / mh - w / dt), 0.0_rk)
        end if
        if (fh == lambda(q)) cycle
        fc(:, nodeh) = fc(:, nodeh) + (fh - lambda(q)) * nrm
        fc(:, noded) = fc(:, noded) - (fh - lambda(q)) * nrm
        lambda(q) = fh
      end do
    end do
    ct%fc = ct%fc + fc

    active_node = .false.
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
      active_node(p%fp_node(:, q)) = .true.
      if (pen > 0.0_rk) then
        pen_max = max(pen_max, pen)
        pen_sq = pen_sq + s0 * pen * pen
      end if
      area_sum = area_sum + s0
    end do
    if (.not. final) return
    released = count(p%was_active .and. .not. active_node)
    p%was_active = active_node
    momentum = 0.0_rk
    do i = 1, ct%ncn
      momentum = momentum + fc(:, i)
    end do
    p%diag = [real(active, rk), sum_force, pen_max, &
        sqrt(pen_sq / max(area_sum, tiny(1.0_rk))), real(released, rk), dt * momentum]
  end subroutine dlm_step

  !> Bounding box (min t1, max t1, min t2, max t2) of a facet projected on the
  !> plane spanned by t1, t2.
  pure subroutine facet_box(facet, t1, t2, box)
    real(rk), intent(in) :: facet(3, 3), t1(3), t2(3)
    real(rk), intent(out) :: box(4)
    real(rk) :: u(3), w(3)
    integer :: k
    do k = 1, 3
      u(k) = dot_product(facet(:, k), t1)
      w(k) = dot_product(facet(:, k), t2)
    end do
    box = [minval(u), maxval(u), minval(w), maxval(w)]
  end subroutine facet_box

  !> Two projected boxes overlap (with a relative margin for round-off; the
  !> exact clip decides).
  pure logical function boxes_meet(a, b)
    real(rk), intent(in) :: a(4), b(4)
    real(rk) :: pad
    pad = 1.0e-9_rk * max(a(2) - a(1), a(4) - a(3), b(2) - b(1), b(4) - b(3))
    boxes_meet = a(1) <= b(2) + pad .and. b(1) <= a(2) + pad .and. a(3) <= b(4) + pad .and. &
        b(3) <= a(4) + pad
  end function boxes_meet

  !> The part of a facet's own area that an overlap s0, measured in the plane
  !> normal to nrm, covers: s0 times the facet's area over its projected area.
  !> Divided by the nodal area it is the node's share carried by the overlap;
  !> the shares of a node fully covered sum to one to round-off even when its
  !> facets are not normal to nrm (a warped or tilted surface), so that a
  !> matching interface acts exactly on whole nodes.
  pure real(rk) function covered(facet_normal, s0, nrm) result(area)
    real(rk), intent(in) :: facet_normal(3), s0, nrm(3)
    real(rk) :: projected
    projected = abs(dot_product(facet_normal, nrm))
    area = s0
    if (projected > 0.0_rk) area = s0 / projected
  end function covered

  !> Distance along nrm from point c to the plane through q with normal n
  !> (c + t nrm lies on the plane).
  pure real(rk) function plane_offset(q, n, c, nrm) result(t)
    real(rk), intent(in) :: q(3), n(3), c(3), nrm(3)
    real(rk) :: denominator
    denominator = dot_product(nrm, n)
    t = 0.0_rk
    if (abs(denominator) > 1.0e-3_rk) t = dot_product(q - c, n) / denominator
  end function plane_offset

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
    real(rk) :: speed, capture
    integer :: q, n, k, e, ss, sm, i, j, c, ncand, nex
    integer :: candidates(64)
    logical :: ok

    call geometry_update(ct%x, p%a, p%ga)
    call geometry_update(ct%x, p%b, p%gb)
    speed = 0.0_rk
    do i = 1, ct%ncn
      speed = max(speed, norm2(ct%v(:, i)))
    end do
    capture = capture_of(p, 2.0_rk * speed, dt)
    call primary_pairs(ct%x, p%b, p%test_pairs, capture, 0.5_rk * p%size, p%primary)
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

  !> DAM: exchange of mass, force and momentum over the facet overlaps of each
  !> enforced slave node with the master facets (CONTACT.md 3.3-3.5), then the
  !> put-back-on of the slave's normal velocity by RBF interpolation of the
  !> new velocities of its master segment's nodes (3.6). Tangential motion is
  !> free (frictionless). The corrected velocities become contact forces.
  subroutine dam_step(ct, p, dt, final)
    type(contact_t), intent(inout) :: ct
    type(interface_t), intent(inout) :: p
    real(rk), intent(in) :: dt !< the stage's step
    logical, intent(in) :: final !< the corrector: update the diagnostics
    real(rk), allocatable :: mbar(:), fbar(:, :), pbar(:, :), nmaster(:, :), vnew(:, :)
    logical, allocatable :: enforced(:), touched(:)
    real(rk) :: nrm(3), shape(4), am, vm, as, vs, gfree, wm, ws, s0
    real(rk) :: target, pen, pen_max, pen_sq, sum_force, momentum(3), unit(3), vn
    integer :: q, n, k, e, i, m, active, released, npen

    ! The predictor's step is half the cycle's.
    if (.not. final .or. .not. allocated(p%primary)) call dam_geometry(ct, p, &
        merge(dt, 2.0_rk * dt, final))
    allocate(mbar(ct%ncn), fbar(3, ct%ncn), pbar(3, ct%ncn), nmaster(3, ct%ncn))
    allocate(vnew(3, ct%ncn), enforced(ct%ncn), touched(ct%ncn))

    ! Which slave nodes are enforced: the free motion would close the gap.
    enforced = .false.
    do q = 1, size(p%primary)
      n = p%primary(q)%node
      nrm = p%primary(q)%normal
      call bilinear_shape(p%primary(q)%xi, p%primary(q)%eta, shape)
      am = 0.0_rk
      vm = 0.0_rk
      do k = 1, 4
        m = p%b%segments(k, p%primary(q)%segment)
        am = am + shape(k) * dot_product(ct%f(:, m), nrm) / ct%mass(m)
        vm = vm + shape(k) * dot_product(ct%v(:, m), nrm)
      end do
      as = dot_product(ct%f(:, n), nrm) / ct%mass(n)
      vs = dot_product(ct%v(:, n), nrm)
      gfree = p%primary(q)%gap + dt * (vs - vm) + 0.5_rk * dt * dt * (as - am)
      ! Release (3.7): the free motion at t^n+1 separates the slave from the
      ! master (tension); a residual penetration does not hold it. This is
      ! the rule of the unilateral rigid wall, so the mirror test holds.
      if (vs - vm + dt * (as - am) > 0.0_rk) cycle
      if (gfree < 0.0_rk) enforced(n) = .true.
    end do

    ! Exchange over the cached facet overlaps.
    mbar = ct%mass
    fbar = ct%f
    do i = 1, ct%ncn
      pbar(:, i) = ct%mass(i) * ct%v(:, i)
    end do
    nmaster = 0.0_rk
    touched = .false.
    do q = 1, size(p%primary)
      n = p%primary(q)%node
      if (.not. enforced(n)) cycle
      do e = p%ex_start(q), p%ex_start(q + 1) - 1
        m = p%ex_master(e)
        wm = p%ex_real(1, e)
        ws = p%ex_real(2, e)
        s0 = p%ex_real(3, e)
        mbar(n) = mbar(n) + ct%mass(m) * wm
        mbar(m) = mbar(m) + ct%mass(n) * ws
        fbar(:, n) = fbar(:, n) + ct%f(:, m) * wm
        fbar(:, m) = fbar(:, m) + ct%f(:, n) * ws
        pbar(:, n) = pbar(:, n) + ct%mass(m) * ct%v(:, m) * wm
        pbar(:, m) = pbar(:, m) + ct%mass(n) * ct%v(:, n) * ws
        nmaster(:, m) = nmaster(:, m) + s0 * p%primary(q)%normal
        touched(m) = .true.
      end do
    end do

    ! Free velocities, then the matched normal components of the master nodes.
    do i = 1, ct%ncn
      vnew(:, i) = ct%v(:, i) + dt * ct%f(:, i) / ct%mass(i)
    end do
    do m = 1, ct%ncn
      if (.not. touched(m)) cycle
      if (.not. norm2(nmaster(:, m)) > 0.0_rk) cycle
      unit = nmaster(:, m) / norm2(nmaster(:, m))
      vn = dot_product(pbar(:, m) + dt * fbar(:, m), unit) / mbar(m)
      vnew(:, m) = vnew(:, m) + (vn - dot_product(vnew(:, m), unit)) * unit
    end do

    ! Put-back-on: the slave's normal velocity from its master nodes.
    active = 0
    npen = 0
    pen_max = 0.0_rk
    pen_sq = 0.0_rk
    sum_force = 0.0_rk
    do q = 1, size(p%primary)
      n = p%primary(q)%node
      if (.not. enforced(n)) cycle
      active = active + 1
      nrm = p%primary(q)%normal
      target = 0.0_rk
      do k = 1, 4
        target = target + p%rbf(k, q) * dot_product(vnew(:, p%b%segments(k, &
            p%primary(q)%segment)), nrm)
      end do
      vnew(:, n) = vnew(:, n) + (target - dot_product(vnew(:, n), nrm)) * nrm
      pen = -p%primary(q)%gap
      if (pen > 0.0_rk) then
        pen_max = max(pen_max, pen)
        pen_sq = pen_sq + pen * pen
        npen = npen + 1
      end if
    end do

    ! The corrected velocities as contact forces.
    momentum = 0.0_rk
    do i = 1, ct%ncn
      if (.not. (enforced(i) .or. touched(i))) cycle
      ct%fc(:, i) = ct%fc(:, i) + ct%mass(i) * (vnew(:, i) - ct%v(:, i)) / dt - ct%f(:, i)
      momentum = momentum + ct%mass(i) * (vnew(:, i) - ct%v(:, i)) - dt * ct%f(:, i)
    end do
    do q = 1, size(p%primary)
      n = p%primary(q)%node
      if (enforced(n)) sum_force = sum_force + max(dot_product(ct%mass(n) * &
          (vnew(:, n) - ct%v(:, n)) / dt - ct%f(:, n), p%primary(q)%normal), 0.0_rk)
    end do
    if (.not. final) return
    released = count(p%was_active .and. .not. (enforced .or. touched))
    p%was_active = enforced .or. touched
    p%diag = [real(active, rk), sum_force, pen_max, &
        sqrt(pen_sq / real(max(npen, 1), rk)), real(released, rk), momentum]
  end subroutine dam_step

  !> Bilinear shape functions of a segment at natural coordinates (xi, eta).
  pure subroutine bilinear_shape(xi, eta, shape)
    real(rk), intent(in) :: xi, eta
    real(rk), intent(out) :: shape(4)
    shape(1) = 0.25_rk * (1.0_rk - xi) * (1.0_rk - eta)
    shape(2) = 0.25_rk * (1.0_rk + xi) * (1.0_rk - eta)
    shape(3) = 0.25_rk * (1.0_rk + xi) * (1.0_rk + eta)
    shape(4) = 0.25_rk * (1.0_rk - xi) * (1.0_rk + eta)
  end subroutine bilinear_shape

  !> A master segment and every segment sharing a node with it, ascending.
  subroutine master_neighbourhood(surf, s, list, n)
    type(contact_surface_t), intent(in) :: surf
    integer, intent(in) :: s
    integer, intent(out) :: list(:)
    integer, intent(out) :: n
    integer :: c, k, e, t, i
    n = 0
    do c = 1, 4
      k = surface_node_index(surf, surf%segments(c, s))
      do e = surf%node_start(k), surf%node_start(k + 1) - 1
        t = surf%node_segments(e)
        if (any(list(:n) == t)) cycle
        if (n == size(list)) exit
        n = n + 1
        list(n) = t
      end do
    end do
    ! ascending
    do i = 2, n
      t = list(i)
      k = i - 1
      do while (k >= 1)
        if (list(k) <= t) exit
        list(k + 1) = list(k)
        k = k - 1
      end do
      list(k + 1) = t
    end do
  end subroutine master_neighbourhood

  !> After the velocity update: the work of the contact forces over the step
  !> on the owned nodes (local sum; the caller reduces it).
  function contact_work_update(ct, v_old, v_new, dt) result(work)
    type(contact_t), intent(in) :: ct
    real(rk), intent(in) :: v_old(:, :), v_new(:, :)
    real(rk), intent(in) :: dt
    real(rk) :: work
    integer :: i, n
    work = 0.0_rk
    do i = 1, ct%nown
      n = ct%own_local(i)
      work = work + 0.5_rk * dt * dot_product(ct%fc(:, ct%own_contact(i)), &
          v_old(:, n) + v_new(:, n))
    end do
  end function contact_work_update

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

  !> Sort ascending and drop repeats.
  subroutine sort_unique(a)
    integer(i8), allocatable, intent(inout) :: a(:)
    integer(i8) :: t
    integer :: i, j, n, gap
    n = size(a)
    gap = n / 2
    do while (gap > 0)
      do i = gap + 1, n
        t = a(i)
        j = i
        do while (j > gap)
          if (a(j - gap) <= t) exit
          a(j) = a(j - gap)
          j = j - gap
        end do
        a(j) = t
      end do
      gap = gap / 2
    end do
    j = 0
    do i = 1, n
      if (j > 0) then
        if (a(i) == a(j)) cycle
      end if
      j = j + 1
      a(j) = a(i)
    end do
    a = a(:j)
  end subroutine sort_unique



end module contact_enforce
