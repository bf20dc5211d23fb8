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
!> Parallel contact by RCB (DESIGN.md 5, CONTACT.md 5). The mesh partition
!> does not follow the surfaces, so contact work is decomposed on its own:
!> * At each global search (every few cycles, when the territory margin may be
!>   used up) a recursive coordinate bisection of the owned contact nodes,
!>   weighted by the pairs each node keyed at the last search, gives every
!>   rank a part (a region). Pairs belong to the part of their key node: a DLM
!>   segment pair to the part of its a-segment's first node, a DAM test pair
!>   to the part of its slave node. The ranks owning the segments' zones send
!>   the key items to their part and each segment, with its corners, to every
!>   part its territory (grown, for DLM, by the largest a-segment) may reach;
!>   each part runs the bucket search on what it received and finds exactly
!>   its pairs of the whole search (search_on_parts). Nothing is replicated
!>   but the static surface topology. A part's local set is the segments of
!>   its pairs plus the rings of neighbours the geometry reads (nodal areas,
!>   the DAM master neighbourhood), numbered by global id.
!> * Each stage, mesh owners send x^n, v^n and f of the local sets' nodes to
!>   the parts (point to point), parts run DLM or DAM on their pairs and send
!>   back one record per contribution, keyed by (interface, global pair
!>   order); owners sum the records in key order, which is the order of a
!>   one-rank run, so results are bitwise independent of the rank count.
!>   DAM needs a second round: the owners' matched master velocities go back
!>   to the parts for the put-back-on of the slaves.
!> * DLM with sweeps > 1 (Gauss-Seidel over all pairs) is sequential: every
!>   pair of such an interface goes to part 0, which sends node sums.
!> Nodes far from any pair belong to no local set and cost nothing.
!>
!> Contact index space. The nodes of all contact surfaces, sorted by global
!> id, are numbered 1..nall (the global surfaces all_a, all_b use it); the
!> local set of a part is numbered 1..ncn in the same order, and its
!> surfaces a, b and pair lists use local numbers, so the order of every loop
!> follows global ids.
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
      search_interval, find_key, sort_real, sort_unique, sort_by_key
  use contact_rbf, only: rbf_weights
  use parallel_env, only: par_sum_array, par_max, par_rank, par_size
  use parallel_exchange, only: par_exchange, par_exchange_counts
  use parallel_rcb, only: rcb_t, rcb_build, rcb_part_of, rcb_parts_of_box
  implicit none
  private
  public :: contact_setup, contact_apply, contact_work_update, contact_diagnostics
  public :: contact_report

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

  !> One contact pair (interface).
  type, public :: interface_t
    type(contact_spec_t), public :: spec
    integer :: method = METHOD_DLM
    integer :: form = FORM_VELOCITY
    logical :: self = .false.
    logical :: single_part = .false. !< every pair on part 0 (DLM sweeps > 1)
    type(contact_surface_t) :: all_a, all_b !< whole surfaces, contact index (b = master for DAM)
    type(contact_surface_t) :: a, b !< this part's local surfaces, local index
    real(rk) :: size = 0.0_rk !< median segment size of both surfaces
    real(rk) :: margin = 0.0_rk !< territory margin in use
    integer, allocatable :: segment_pairs(:, :) !< DLM: (2, n) local segment of a, of b
    integer(i8), allocatable :: pair_key(:) !< DLM: (n) global order of each local segment pair
    integer, allocatable :: test_pairs(:, :) !< DAM: (2, n) local slave node, master segment
    integer, allocatable :: home_a(:), home_b(:) !< segments of all_a, all_b homed on this rank
    integer, allocatable :: home_a_node(:, :), home_b_node(:, :) !< (4, n) their local mesh nodes
    integer, allocatable :: own_slave(:) !< DAM: owned nodes of all_a (surface node index)
    logical, allocatable :: was_active(:) !< (nown) owned node carried contact force last step
    integer :: nfp = 0 !< DLM facet pairs of the cycle
    integer, allocatable :: fp_node(:, :) !< (2, nfp) hitting and target node
    integer(i8), allocatable :: fp_key(:) !< (nfp) global order of the facet pair
    real(rk), allocatable :: fp_real(:, :) !< (7, nfp) shares wh, wd, pen, s0, normal
    type(surface_geometry_t) :: ga, gb !< geometry of a and b at x^n
    type(primary_pair_t), allocatable :: primary(:) !< DAM: the cycle's primary pairs
    real(rk), allocatable :: rbf(:, :) !< DAM: (4, nprimary) put-back weights
    integer, allocatable :: ex_start(:) !< DAM: (nprimary + 1) exchange entries of a pair
    integer, allocatable :: ex_master(:) !< DAM: master node of an exchange entry
    real(rk), allocatable :: ex_real(:, :) !< DAM: (3, nex) shares wm, ws and overlap s0
    logical, allocatable :: enforced(:) !< DAM: (ncn) local slave enforced this stage
    real(rk) :: partial(CONTACT_DIAG_COUNT) = 0.0_rk !< this part's diagnostic sums
    real(rk), public :: diag(CONTACT_DIAG_COUNT) = 0.0_rk !< last step's diagnostics
    logical, public :: warned = .false. !< the penetration warning was given
  end type interface_t

  !> One interface's pairs from the global search, and the segments of the
  !> whole surfaces a part reads (during a rebuild).
  type :: selection_t
    integer, allocatable :: pairs(:, :) !< (2, n) DLM: segments a, b; DAM: node, segment
    logical, allocatable :: mark_a(:), mark_b(:) !< (nseg) segment in the local set
  end type selection_t

  !> A list of integers (one per interface).
  type :: int_list_t
    integer, allocatable :: v(:)
  end type int_list_t

  !> All contact of a run.
  type, public :: contact_t
    integer :: npair = 0
    type(interface_t), allocatable :: pairs(:)
    ! Every contact node (static, on every rank).
    integer :: nall = 0 !< contact nodes of all surfaces
    integer(i8), allocatable :: all_gid(:) !< (nall) global ids, ascending
    real(rk), allocatable :: all_mass(:) !< (nall) nodal masses (fixed)
    integer, allocatable :: all_owner(:) !< (nall) rank owning the node in the mesh
    ! Owned contact nodes of this rank.
    integer :: nown = 0
    integer, allocatable :: own_contact(:) !< (nown) contact index, ascending
    integer, allocatable :: own_local(:) !< (nown) local mesh node index
    integer, allocatable :: own_of(:) !< (nall) owned index of a contact node, 0 if not owned
    logical, allocatable :: key_capable(:) !< (nown) the node can key pairs (DLM first
                                           !< corner of an a-segment, DAM slave node)
    integer(i8), allocatable :: key_weight(:) !< (nown) RCB weight: pairs keyed at the last search
    real(rk), allocatable :: xs(:, :) !< (3, nall) positions the part's search received
    real(rk), allocatable :: fc(:, :) !< (3, nown) contact force of the stage
    ! This rank's RCB part.
    integer :: ncn = 0 !< nodes of the local set
    integer, allocatable :: all_of(:) !< (ncn) their contact index, ascending
    real(rk), allocatable :: mass(:) !< (ncn)
    real(rk), allocatable :: x(:, :), v(:, :), f(:, :) !< (3, ncn) x^n, v^n, f of the stage
    ! Migration plan (rebuilt with the RCB).
    integer, allocatable :: recv_count(:) !< (nranks) local nodes sent by each owner
    integer, allocatable :: recv_local(:) !< (ncn) local node of each, by owner
    integer, allocatable :: send_count(:) !< (nranks) owned nodes sent to each part
    integer, allocatable :: send_own(:) !< owned index of each, by part
    integer(i8) :: next_search = 0 !< cycle of the next global search and RCB
    real(rk) :: speed = 0.0_rk !< largest contact node speed at t^n (all ranks)
    integer :: rebuilds = 0 !< global searches (RCB rebuilds) so far
    integer :: ncn_max = 0 !< largest local set of this rank so far
    real(rk) :: search_seconds = 0.0_rk, enforce_seconds = 0.0_rk, migrate_seconds = 0.0_rk
    type(records_t) :: kept(3) !< record buffers (DLM, DAM exchange, DAM put-back) between stages
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

  !> The segments each rank homes: those of its owned zones, whose four
  !> corners it holds (owned or ghost nodes; ghosts move exactly as their
  !> owners). Also the owned nodes that can key pairs, the first RCB weights.
  subroutine segment_homes(ct, mesh)
    type(contact_t), intent(inout) :: ct
    type(mesh_t), intent(in) :: mesh
    integer(i8), allocatable :: zone_key(:)
    integer, allocatable :: perm(:)
    integer :: k, i, n, s

    zone_key = mesh%zone_gid(:mesh%nzone_owned)
    call sort_by_key(zone_key, perm)
    zone_key = zone_key(perm)
    allocate(ct%key_capable(ct%nown))
    ct%key_capable = .false.
    do k = 1, ct%npair
      associate(p => ct%pairs(k))
        call homes_of(p%all_a, p%home_a, p%home_a_node)
        call homes_of(p%all_b, p%home_b, p%home_b_node)
        if (p%method == METHOD_DLM) then
          do s = 1, p%all_a%nseg
            i = ct%own_of(p%all_a%segments(1, s))
            if (i > 0) ct%key_capable(i) = .true.
          end do
          allocate(p%own_slave(0))
        else
          p%own_slave = pack([(n, n = 1, p%all_a%nnode)], ct%own_of(p%all_a%nodes) > 0)
          do n = 1, size(p%own_slave)
            ct%key_capable(ct%own_of(p%all_a%nodes(p%own_slave(n)))) = .true.
          end do
        end if
      end associate
    end do
    ct%key_weight = merge(1_i8, 0_i8, ct%key_capable)
    ! Filled by each search with what the part receives, read nowhere else.
    allocate(ct%xs(3, ct%nall))

  contains

    subroutine homes_of(surf, home, node)
      type(contact_surface_t), intent(in) :: surf
      integer, allocatable, intent(out) :: home(:), node(:, :)
      integer :: j, z, c, m, count
      allocate(home(surf%nseg), node(4, surf%nseg))
      count = 0
      do j = 1, surf%nseg
        ! segment_id = 6 (zone - 1) + face
        z = find_key(zone_key, (surf%segment_id(j) - 1_i8) / 6_i8 + 1_i8)
        if (z == 0) cycle
        z = perm(z)
        count = count + 1
        home(count) = j
        do c = 1, 4
          m = 1
          do while (mesh%node_gid(mesh%zone_node(m, z)) /= ct%all_gid(surf%segments(c, j)))
            m = m + 1
            if (m > 8) error stop 'contact: a segment corner is not a node of its zone'
          end do
          node(c, count) = mesh%zone_node(m, z)
        end do
      end do
      home = home(:count)
      node = node(:, :count)
    end subroutine homes_of

  end subroutine segment_homes

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
    rebuilt = cycle >= ct%next_search .or. .not. allocated(ct%all_of)
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

  !> Search of every interface on the RCB parts, this part's pairs and local
  !> set, and the migration plan (the local surfaces follow in
  !> contact_localize, once the local set's positions have arrived). Collective.
  subroutine contact_rebuild(ct, x_old, dt, cycle, sel)
    type(contact_t), intent(inout) :: ct
    real(rk), intent(in) :: x_old(:, :), dt
    integer(i8), intent(in) :: cycle
    type(selection_t), allocatable, intent(out) :: sel(:)
    integer(i8), allocatable :: request(:), wanted(:)
    integer, allocatable :: fill(:)
    logical, allocatable :: in_set(:)
    type(rcb_t) :: rcb
    integer :: k, i, c, m, n, every, every_min, nranks, r, s, e, j

    nranks = par_size()
    ct%rebuilds = ct%rebuilds + 1
    every_min = huge(1)
    do k = 1, ct%npair
      associate(p => ct%pairs(k))
        p%margin = p%spec%search_margin
        if (.not. p%margin > 0.0_rk) p%margin = 0.5_rk * p%size
        every = p%spec%search_every
        if (every == 0) every = search_interval(p%margin, capture_of(p, 2.0_rk * ct%speed, dt), &
            2.0_rk * ct%speed, dt, 1.2_rk, 50)
        every_min = min(every_min, every)
      end associate
    end do
    ct%next_search = cycle + int(every_min, i8)

    ! RCB of the owned contact nodes, weighted by the pairs each keyed at the
    ! last search (the search of the parts needs the parts first).
    call rcb_build(x_old(:, ct%own_local), ct%key_weight, ct%all_gid(ct%own_contact), &
        nranks, rcb)
    allocate(sel(ct%npair))
    call search_on_parts(ct, x_old, rcb, sel)
    call count_keys(ct, sel)

    ! The segments this part's pairs read.
    allocate(in_set(ct%nall))
    in_set = .false.
    do k = 1, ct%npair
      associate(p => ct%pairs(k))
        allocate(sel(k)%mark_a(p%all_a%nseg), sel(k)%mark_b(p%all_b%nseg))
        sel(k)%mark_a = .false.
        sel(k)%mark_b = .false.
        if (p%method == METHOD_DLM) then
          do m = 1, size(sel(k)%pairs, 2)
            sel(k)%mark_a(sel(k)%pairs(1, m)) = .true.
            sel(k)%mark_b(sel(k)%pairs(2, m)) = .true.
          end do
          ! Nodal areas need every segment of every node.
          call add_ring(p%all_a, sel(k)%mark_a)
          call add_ring(p%all_b, sel(k)%mark_b)
        else
          do m = 1, size(sel(k)%pairs, 2)
            n = surface_node_index(p%all_a, int(sel(k)%pairs(1, m), ik))
            do e = p%all_a%node_start(n), p%all_a%node_start(n + 1) - 1
              sel(k)%mark_a(p%all_a%node_segments(e)) = .true.
            end do
            sel(k)%mark_b(sel(k)%pairs(2, m)) = .true.
          end do
          ! The master neighbourhood, and the nodal areas of its nodes.
          call add_ring(p%all_b, sel(k)%mark_b)
          call add_ring(p%all_b, sel(k)%mark_b)
        end if
        do s = 1, p%all_a%nseg
          if (sel(k)%mark_a(s)) in_set(p%all_a%segments(:, s)) = .true.
        end do
        do s = 1, p%all_b%nseg
          if (sel(k)%mark_b(s)) in_set(p%all_b%segments(:, s)) = .true.
        end do
      end associate
    end do

    ! The local set, by ascending global id.
    ct%all_of = pack([(c, c = 1, ct%nall)], in_set)
    ct%ncn = size(ct%all_of)
    ct%ncn_max = max(ct%ncn_max, ct%ncn)
    ct%mass = ct%all_mass(ct%all_of)
    if (allocated(ct%x)) deallocate(ct%x, ct%v, ct%f)
    allocate(ct%x(3, ct%ncn), ct%v(3, ct%ncn), ct%f(3, ct%ncn))

    ! Migration plan: each owner learns which of its nodes each part needs.
    allocate(fill(nranks))
    if (allocated(ct%recv_count)) deallocate(ct%recv_count, ct%send_count)
    allocate(ct%recv_count(nranks), ct%send_count(nranks))
    ct%recv_count = 0
    do i = 1, ct%ncn
      r = ct%all_owner(ct%all_of(i))
      ct%recv_count(r + 1) = ct%recv_count(r + 1) + 1
    end do
    fill(1) = 0
    do r = 2, nranks
      fill(r) = fill(r - 1) + ct%recv_count(r - 1)
    end do
    if (allocated(ct%recv_local)) deallocate(ct%recv_local)
    allocate(ct%recv_local(ct%ncn), request(ct%ncn))
    do i = 1, ct%ncn
      r = ct%all_owner(ct%all_of(i)) + 1
      fill(r) = fill(r) + 1
      ct%recv_local(fill(r)) = i
      request(fill(r)) = int(ct%all_of(i), i8)
    end do
    call par_exchange_counts(ct%recv_count, ct%send_count)
    call par_exchange(request, ct%recv_count, wanted, ct%send_count)
    if (allocated(ct%send_own)) deallocate(ct%send_own)
    ! (The receive buffer may be longer than what arrived.)
    allocate(ct%send_own(sum(ct%send_count)))
    do j = 1, size(ct%send_own)
      ct%send_own(j) = ct%own_of(wanted(j))
    end do
  end subroutine contact_rebuild

  !> The local surfaces and pair lists of this part from the local set's
  !> positions x^n (just gathered); edge flags from the same positions.
  subroutine contact_localize(ct, sel)
    type(contact_t), intent(inout) :: ct
    type(selection_t), intent(in) :: sel(:)
    integer, allocatable :: l_of(:), seg_a(:), seg_b(:)
    integer :: k, i, m

    allocate(l_of(ct%nall))
    l_of = 0
    do i = 1, ct%ncn
      l_of(ct%all_of(i)) = i
    end do
    do k = 1, ct%npair
      associate(p => ct%pairs(k), pairs => sel(k)%pairs)
        call local_surface(p%all_a, sel(k)%mark_a, l_of, ct%x, p%a, seg_a)
        call local_surface(p%all_b, sel(k)%mark_b, l_of, ct%x, p%b, seg_b)
        if (p%method == METHOD_DLM) then
          p%segment_pairs = reshape([(seg_a(pairs(1, m)), seg_b(pairs(2, m)), &
              m = 1, size(pairs, 2))], [2, size(pairs, 2)])
          ! The global order of a segment pair: the search lists them by (a, b).
          p%pair_key = [(int(pairs(1, m) - 1, i8) * int(p%all_b%nseg, i8) + &
              int(pairs(2, m), i8), m = 1, size(pairs, 2))]
        else
          p%test_pairs = reshape([(l_of(pairs(1, m)), seg_b(pairs(2, m)), &
              m = 1, size(pairs, 2))], [2, size(pairs, 2)])
        end if
        call geometry_free(p%ga)
        call geometry_free(p%gb)
        if (allocated(p%primary)) deallocate(p%primary)
        if (allocated(p%enforced)) deallocate(p%enforced)
        allocate(p%enforced(ct%ncn))
        p%enforced = .false.
      end associate
    end do
  end subroutine contact_localize

  !> The global search, on the parts. Segment homes (the ranks owning the
  !> segments' zones) send each segment with its corner positions x^n to the
  !> parts it may reach; a part searches its keys (DLM: the a-segments whose
  !> first node is in its region; DAM: the slave nodes in its region) against
  !> the segments received. A DAM pair (n, b) needs n inside b's territory, so
  !> b goes to every part whose region meets the territory; a DLM pair (a, b)
  !> needs a's box to meet b's territory, and a's box lies within the largest
  !> a-segment extent of its first node, so b goes to the parts its territory
  !> grown by that extent meets. Each part finds exactly its pairs of the
  !> whole search, in the same order. Collective.
  subroutine search_on_parts(ct, x_old, rcb, sel)
    type(contact_t), intent(inout) :: ct
    real(rk), intent(in) :: x_old(:, :)
    type(rcb_t), intent(in) :: rcb
    type(selection_t), intent(inout) :: sel(:)
    !> A shipped item: interface, kind, index, four corners (a node: one).
    integer, parameter :: REC = 15
    integer, parameter :: KEY_SEGMENT = 1, CANDIDATE = 2, KEY_NODE = 3
    real(rk), allocatable :: send(:), recv(:)
    integer, allocatable :: count(:), recv_count(:), fill(:), parts(:), nlist(:, :)
    type(int_list_t), allocatable :: keys(:), cands(:)
    real(rk) :: ext(ct%npair), lo(3), hi(3), grow, slack, corners(3, 4)
    integer :: k, j, s, i, n, part, np, pass, nranks, q, kind, idx

    nranks = par_size()
    allocate(count(nranks), recv_count(nranks), fill(nranks), parts(nranks))
    ! The largest a-segment extent of each DLM interface.
    do k = 1, ct%npair
      ext(k) = 0.0_rk
      associate(p => ct%pairs(k))
        if (p%method == METHOD_DLM) then
          do j = 1, size(p%home_a)
            corners = x_old(:, p%home_a_node(:, j))
            ext(k) = max(ext(k), maxval(maxval(corners, dim=2) - minval(corners, dim=2)))
          end do
        end if
      end associate
      ext(k) = par_max(ext(k))
    end do

    ! Two passes over the items: count per part, then fill.
    do pass = 1, 2
      if (pass == 1) then
        count = 0
      else
        allocate(send(REC * sum(count)))
        fill(1) = 0
        do part = 2, nranks
          fill(part) = fill(part - 1) + count(part - 1)
        end do
      end if
      do k = 1, ct%npair
        associate(p => ct%pairs(k))
          if (p%method == METHOD_DLM) then
            do j = 1, size(p%home_a)
              s = p%home_a(j)
              part = 0
              if (.not. p%single_part) part = rcb_part_of(rcb, x_old(:, p%home_a_node(1, j)), &
                  ct%all_gid(p%all_a%segments(1, s)))
              call emit(part, k, KEY_SEGMENT, s, x_old(:, p%home_a_node(:, j)))
            end do
            grow = p%margin + ext(k)
          else
            do j = 1, size(p%own_slave)
              i = ct%own_of(p%all_a%nodes(p%own_slave(j)))
              corners = 0.0_rk
              corners(:, 1) = x_old(:, ct%own_local(i))
              part = rcb_part_of(rcb, corners(:, 1), ct%all_gid(ct%own_contact(i)))
              call emit(part, k, KEY_NODE, p%own_slave(j), corners)
            end do
            grow = p%margin
          end if
          do j = 1, size(p%home_b)
            corners = x_old(:, p%home_b_node(:, j))
            if (p%single_part) then
              call emit(0, k, CANDIDATE, p%home_b(j), corners)
              cycle
            end if
            ! Conservative by a few roundings: more candidates change nothing.
            slack = 1.0e-10_rk * (grow + maxval(abs(corners)))
            lo = minval(corners, dim=2) - grow - slack
            hi = maxval(corners, dim=2) + grow + slack
            call rcb_parts_of_box(rcb, lo, hi, parts, np)
            do q = 1, np
              call emit(parts(q), k, CANDIDATE, p%home_b(j), corners)
            end do
          end do
        end associate
      end do
    end do
    call par_exchange_counts(REC * count, recv_count)
    call par_exchange(send, REC * count, recv, recv_count)

    ! Keys and candidates of each interface, ascending; their positions.
    allocate(nlist(2, ct%npair), keys(ct%npair), cands(ct%npair))
    nlist = 0
    n = sum(recv_count) / REC
    do pass = 1, 2
      do j = 1, n
        k = nint(recv(REC * (j - 1) + 1))
        kind = nint(recv(REC * (j - 1) + 2))
        idx = nint(recv(REC * (j - 1) + 3))
        q = merge(2, 1, kind == CANDIDATE)
        nlist(q, k) = nlist(q, k) + 1
        if (pass == 1) cycle
        corners = reshape(recv(REC * (j - 1) + 4:REC * j), [3, 4])
        associate(p => ct%pairs(k))
          select case (kind)
          case (KEY_SEGMENT)
            keys(k)%v(nlist(1, k)) = idx
            ct%xs(:, p%all_a%segments(:, idx)) = corners
          case (KEY_NODE)
            keys(k)%v(nlist(1, k)) = idx
            ct%xs(:, p%all_a%nodes(idx)) = corners(:, 1)
          case default
            cands(k)%v(nlist(2, k)) = idx
            ct%xs(:, p%all_b%segments(:, idx)) = corners
          end select
        end associate
      end do
      if (pass == 1) then
        do k = 1, ct%npair
          allocate(keys(k)%v(nlist(1, k)), cands(k)%v(nlist(2, k)))
        end do
        nlist = 0
      end if
    end do

    do k = 1, ct%npair
      associate(p => ct%pairs(k))
        call sort_int(keys(k)%v)
        call sort_int(cands(k)%v)
        if (p%method == METHOD_DLM) then
          call segment_pair_search(ct%xs, p%all_a, p%all_b, p%self, p%margin, sel(k)%pairs, &
              keys(k)%v, cands(k)%v)
        else
          call bucket_search(ct%xs, p%all_a, p%all_b, p%self, p%margin, sel(k)%pairs, &
              keys(k)%v, cands(k)%v)
          if (p%self) call keep_lower_side(p%all_a, sel(k)%pairs)
        end if
      end associate
    end do

  contains

    subroutine emit(to, k, kind, idx, corners)
      integer, intent(in) :: to, k, kind, idx
      real(rk), intent(in) :: corners(3, 4)
      integer :: at
      if (pass == 1) then
        count(to + 1) = count(to + 1) + 1
        return
      end if
      fill(to + 1) = fill(to + 1) + 1
      at = REC * (fill(to + 1) - 1)
      send(at + 1:at + 3) = real([k, kind, idx], rk)
      send(at + 4:at + REC) = reshape(corners, [12])
    end subroutine emit

  end subroutine search_on_parts

  !> Ascending sort of a short integer list (via the 64-bit merge sort).
  subroutine sort_int(v)
    integer, intent(inout) :: v(:)
    integer, allocatable :: perm(:)
    call sort_by_key(int(v, i8), perm)
    v = v(perm)
  end subroutine sort_int

  !> Weights of the next RCB: each owned node's pairs keyed at this search
  !> (counted at the owners), plus one for a node that can key pairs.
  subroutine count_keys(ct, sel)
    type(contact_t), intent(inout) :: ct
    type(selection_t), intent(in) :: sel(:)
    integer(i8), allocatable :: send(:), recv(:)
    integer, allocatable :: count(:), recv_count(:), fill(:)
    integer :: k, m, c, pass, nranks, r, j
    nranks = par_size()
    allocate(count(nranks), recv_count(nranks), fill(nranks))
    do pass = 1, 2
      if (pass == 1) then
        count = 0
      else
        allocate(send(sum(count)))
        fill(1) = 0
        do r = 2, nranks
          fill(r) = fill(r - 1) + count(r - 1)
        end do
      end if
      do k = 1, ct%npair
        do m = 1, size(sel(k)%pairs, 2)
          c = key_node(ct%pairs(k), sel(k)%pairs(:, m))
          r = ct%all_owner(c) + 1
          if (pass == 1) then
            count(r) = count(r) + 1
          else
            fill(r) = fill(r) + 1
            send(fill(r)) = int(c, i8)
          end if
        end do
      end do
    end do
    call par_exchange_counts(count, recv_count)
    call par_exchange(send, count, recv, recv_count)
    ct%key_weight = merge(1_i8, 0_i8, ct%key_capable)
    do j = 1, sum(recv_count)
      m = ct%own_of(recv(j))
      ct%key_weight(m) = ct%key_weight(m) + 1_i8
    end do
  end subroutine count_keys

  !> The contact node that decides the part of a pair: DLM, the first corner
  !> of its a-segment; DAM, its slave node.
  pure integer function key_node(p, pair) result(c)
    type(interface_t), intent(in) :: p
    integer, intent(in) :: pair(2)
    if (p%method == METHOD_DLM) then
      c = p%all_a%segments(1, pair(1))
    else
      c = pair(1)
    end if
  end function key_node

  !> Forget a surface's cached geometry (its size changes with the local set).
  subroutine geometry_free(g)
    type(surface_geometry_t), intent(inout) :: g
    if (allocated(g%facets)) deallocate(g%facets, g%normal, g%area, g%quad_normal, g%nodal_area)
  end subroutine geometry_free

  !> x^n, v^n and f of the local set from the mesh owners.
  subroutine gather_nodes(ct, x_old, v_old, force)
    type(contact_t), intent(inout) :: ct
    real(rk), intent(in) :: x_old(:, :), v_old(:, :), force(:, :)
    real(rk), allocatable :: send(:), recv(:)
    integer :: j, l, i
    allocate(send(9 * size(ct%send_own)))
    do j = 1, size(ct%send_own)
      l = ct%own_local(ct%send_own(j))
      send(9 * j - 8:9 * j - 6) = x_old(:, l)
      send(9 * j - 5:9 * j - 3) = v_old(:, l)
      send(9 * j - 2:9 * j) = force(:, l)
    end do
    call par_exchange(send, 9 * ct%send_count, recv, 9 * ct%recv_count)
    do j = 1, ct%ncn
      i = ct%recv_local(j)
      ct%x(:, i) = recv(9 * j - 8:9 * j - 6)
      ct%v(:, i) = recv(9 * j - 5:9 * j - 3)
      ct%f(:, i) = recv(9 * j - 2:9 * j)
    end do
  end subroutine gather_nodes

  !> Owned values (3, nown, npair) to the local sets (3, ncn, npair).
  subroutine scatter_nodes(ct, owned, local)
    type(contact_t), intent(in) :: ct
    real(rk), intent(in) :: owned(:, :, :)
    real(rk), allocatable, intent(out) :: local(:, :, :)
    real(rk), allocatable :: send(:), recv(:)
    integer :: j, nv, k, i
    nv = 3 * ct%npair
    allocate(send(nv * size(ct%send_own)), local(3, ct%ncn, ct%npair))
    do j = 1, size(ct%send_own)
      do k = 1, ct%npair
        send(nv * (j - 1) + 3 * k - 2:nv * (j - 1) + 3 * k) = owned(:, ct%send_own(j), k)
      end do
    end do
    call par_exchange(send, nv * ct%send_count, recv, nv * ct%recv_count)
    do j = 1, ct%ncn
      i = ct%recv_local(j)
      do k = 1, ct%npair
        local(:, i, k) = recv(nv * (j - 1) + 3 * k - 2:nv * (j - 1) + 3 * k)
      end do
    end do
  end subroutine scatter_nodes

  !> DAM at the owners, first round: the exchanged mass, force and momentum
  !> of the owned nodes summed in key order, then the velocities: free, and
  !> for master nodes the matched normal component (CONTACT.md 3.3-3.5).
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
        vn = dot_product(pbar(:, i, k) + dt * fbar(:, i, k), unit) / mbar(i, k)
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
      vfinal(:, i, k) = r%val(:, j)
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
          p%diag = [sums(1), sums(2), pen_max, sqrt(sums(3) / max(sums(4), tiny(1.0_rk))), &
              sums(8), sums(5:7)]
        else
          p%diag = [sums(1), sums(2), pen_max, sqrt(sums(3) / max(sums(4), 1.0_rk)), &
              sums(8), sums(5:7)]
        end if
      end associate
    end do
  end subroutine reduce_diagnostics

  !> Capture tolerance: the deck's, or twice the closing distance of one step.
  pure real(rk) function capture_of(p, speed, dt) result(capture)
    type(interface_t), intent(in) :: p
    real(rk), intent(in) :: speed, dt
    capture = p%spec%capture
    if (.not. capture > 0.0_rk) capture = max(2.0_rk * speed * dt, 1.0e-3_rk * p%size)
  end function capture_of

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
    real(rk) :: box_a(4, SEGMENT_FACET_COUNT), box_b(4, SEGMENT_FACET_COUNT), seg_a(4), seg_b(4)
    real(rk) :: a2(2, 3, SEGMENT_FACET_COUNT), b2(2, 3, SEGMENT_FACET_COUNT), centre2(2)
    integer :: m, sa, sb, i, j, nodeh, noded
    logical :: a_hits

    call geometry_update(ct%x, p%a, p%ga)
    call geometry_update(ct%x, p%b, p%gb)
    p%nfp = 0
    if (.not. allocated(p%fp_node)) allocate(p%fp_node(2, 64), p%fp_real(7, 64), p%fp_key(64))
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
            call add_facet_pair(p, nodeh, noded, wh, wd, pen, s0, nrm, &
                p%pair_key(m) * 64_i8 + int(8 * (i - 1) + j - 1, i8))
          end do
        end do
      end do
    end associate
  end subroutine dlm_geometry

  !> Append one facet pair to the interface's cache, growing it when full.
  subroutine add_facet_pair(p, nodeh, noded, wh, wd, pen, s0, nrm, key)
    type(interface_t), intent(inout) :: p
    integer, intent(in) :: nodeh, noded
    real(rk), intent(in) :: wh, wd, pen, s0, nrm(3)
    integer(i8), intent(in) :: key !< global order: segment pair, facet of a, facet of b
    integer, allocatable :: grown_node(:, :)
    integer(i8), allocatable :: grown_key(:)
    real(rk), allocatable :: grown_real(:, :)
    if (p%nfp == size(p%fp_node, 2)) then
      allocate(grown_node(2, 2 * p%nfp), grown_real(7, 2 * p%nfp), grown_key(2 * p%nfp))
      grown_node(:, :p%nfp) = p%fp_node(:, :p%nfp)
      grown_real(:, :p%nfp) = p%fp_real(:, :p%nfp)
      grown_key(:p%nfp) = p%fp_key(:p%nfp)
      call move_alloc(grown_node, p%fp_node)
      call move_alloc(grown_real, p%fp_real)
      call move_alloc(grown_key, p%fp_key)
    end if
    p%nfp = p%nfp + 1
    p%fp_node(:, p%nfp) = [nodeh, noded]
    p%fp_real(:, p%nfp) = [wh, wd, pen, s0, nrm]
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
    real(rk), allocatable :: lambda(:), fc(:, :)
    logical, allocatable :: gated(:)
    real(rk) :: nrm(3), s0, pen, wh, wd
    real(rk) :: mh, md, fh_, fd_, vh, vd, mu, fh, pen_free, w, target, sum_force, pen_max
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
        call add_record(out, ct%all_of(p%fp_node(1, q)), k, p%fp_key(q), lambda(q) * nrm)
        call add_record(out, ct%all_of(p%fp_node(2, q)), k, p%fp_key(q), -(lambda(q) * nrm))
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

  !> DAM at the parts, first round: which slave nodes are enforced, and the
  !> exchange of mass, force and momentum over the facet overlaps of each
  !> enforced slave with the master facets (CONTACT.md 3.3-3.5), as records
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
  !> master segment's nodes (CONTACT.md 3.6); tangential motion is free
  !> (frictionless). vm are the velocities after the master matching and
  !> before any put-back (in self-contact a master node may be a slave too).
  subroutine dam_put_back(ct, p, k, dt, vm, out)
    type(contact_t), intent(in) :: ct
    type(interface_t), intent(inout) :: p
    integer, intent(in) :: k !< the interface's number
    real(rk), intent(in) :: dt !< the stage's step
    real(rk), intent(in) :: vm(:, :) !< (3, ncn) matched velocities of the local set
    type(records_t), intent(inout) :: out !< nv = 3: the slave's final velocity
    real(rk) :: nrm(3), target, pen, pen_max, pen_sq, sum_force, vnew(3)
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
      vnew = vm(:, n) + (target - dot_product(vm(:, n), nrm)) * nrm
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
  function contact_work_update(ct, v_old, v_new, dt) result(work)
    type(contact_t), intent(in) :: ct
    real(rk), intent(in) :: v_old(:, :), v_new(:, :)
    real(rk), intent(in) :: dt
    real(rk) :: work
    integer :: i, n
    work = 0.0_rk
    do i = 1, ct%nown
      n = ct%own_local(i)
      work = work + 0.5_rk * dt * dot_product(ct%fc(:, i), &
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

  !> End-of-run summary on rank 0: the contact time split (largest over the
  !> ranks) and the local sets against the whole contact surface. Collective.
  subroutine contact_report(ct, loop_seconds)
    type(contact_t), intent(in) :: ct
    real(rk), intent(in) :: loop_seconds !< this rank's time loop without dumps
    real(rk) :: search, enforce, migrate, total, loop, whole, local
    integer :: largest, smallest, k
    search = par_max(ct%search_seconds)
    enforce = par_max(ct%enforce_seconds)
    migrate = par_max(ct%migrate_seconds)
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
    write(output_unit, '(a,i0,a,i0,a,i0,a,i0,a)') 'impact3d: contact local sets ', smallest, &
        ' to ', largest, ' nodes per rank of ', ct%nall, ' contact nodes; ', ct%rebuilds, &
        ' global searches'
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
