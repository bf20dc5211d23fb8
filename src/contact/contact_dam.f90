!> DAM, the discrete accurate matching method (master-slave) of Jia, Gong,
!> Zhang & Liu (J. Comput. Phys. 267 (2014) 247-285), as described in
!> docs/contact.md, section 6. On each RCB part: the facet overlaps of each
!> slave node with the master facets around its primary segment
!> (dam_geometry), which slaves are enforced and the exchange of mass, force
!> and momentum over the overlaps (dam_exchange), and the put-back-on of the
!> slaves' normal velocity (dam_put_back). At the owners of the nodes: the
!> matched normal velocity of touched master nodes (match_masters) and the
!> final velocities as contact forces (dam_forces). dam_t is the method
!> (contact_method_t): round 1 the exchange at the parts and the matching at
!> the owners, round 2 the put-back at the parts and the final velocities at
!> the owners; contact_enforce runs the rounds and moves the records between
!> parts and owners. dam_t holds the cycle's primary pairs, exchange entries
!> and put-back weights, and the owners' matched velocities between rounds.
module contact_dam
  use core_kinds, only: rk, ik, i8
  use contact_geometry, only: tangent_basis, segment_box, facet_box, boxes_meet, &
      triangle_overlap, covered, bilinear_shape, FACET_CORNER, SEGMENT_FACET_COUNT
  use contact_surface, only: contact_surface_t, surface_node_index, master_neighbourhood
  use contact_records, only: records_t, add_record
  use contact_search, only: primary_pairs
  use contact_rbf, only: rbf_weights
  use contact_search, only: primary_pair_t
  use contact_state, only: FACING, AREA_TOLERANCE, PAIR_NODE_SEGMENT, SURFACE_LEN, &
      surface_geometry_t, interface_t, contact_t, contact_spec_t, contact_method_t, capture_of, &
      geometry_update, recovery_allowance, recovery_excess, recovery_speed_of
  use contact_kernels, only: dam_merged_normal_velocity, dam_put_back_velocity, &
      dam_friction_velocity
  implicit none
  private

  !> Rounds of a stage and their record layouts: the exchange (mass, force
  !> (3), momentum (3), master normal weighted by the overlap (3)), then the
  !> put-back (a slave's final velocity, or a momentum for a master).
  integer, parameter :: ROUND_MATCH = 1, ROUND_PUT_BACK = 2
  integer, parameter :: EXCHANGE_WIDTH = 10, PUT_BACK_WIDTH = 3
  !> Values per owned node after the matching: velocity (3), matching
  !> normal (3), slave mass merged (1).
  integer, parameter :: MATCHED_WIDTH = 7
  !> Fraction of a slave's penetration beyond its allowance removed per
  !> cycle (the put-back's separating speed; docs/contact.md, 6, step 4):
  !> DLM's default recovery.
  real(rk), parameter :: DAM_RECOVERY = 0.2_rk

  !> DAM: the method and its caches on this part.
  type, extends(contact_method_t), public :: dam_t
    logical :: slave_normal = .false. !< the slave node's own normal (deck normal = 'slave')
    logical :: symmetric = .false. !< a reverse pass with the sides swapped (deck)
    type(primary_pair_t), allocatable :: primary(:) !< the cycle's primary pairs
    real(rk), allocatable :: rbf(:, :) !< (4, nprimary) put-back weights
    real(rk), allocatable :: excess(:) !< (nprimary) penetration beyond the allowance at x^n
    real(rk), allocatable :: recover(:) !< (nprimary) the stage's separating speed
    integer, allocatable :: ex_start(:) !< (nprimary + 1) exchange entries of a pair
    integer, allocatable :: ex_master(:) !< master node of an exchange entry
    real(rk), allocatable :: ex_real(:, :) !< (3, nex) shares wm, ws and overlap s0
    logical, allocatable :: enforced(:) !< (ncn) local slave enforced this stage
    ! The owners, between the rounds.
    real(rk), allocatable :: vmatch(:, :) !< (MATCHED_WIDTH, nown) matched velocities
    logical, allocatable :: touched(:) !< (nown) master node matched
  contains
    procedure, nopass :: pair_kind => dam_pair_kind
    procedure, nopass :: rounds => dam_rounds
    procedure, nopass :: record_width => dam_record_width
    procedure, nopass :: owner_width => dam_owner_width
    procedure :: configure => dam_configure
    procedure, nopass :: sides => dam_sides
    procedure :: reverse_pass => dam_reverse_pass
    procedure :: enforces_b => dam_no
    procedure :: localized => dam_localized
    procedure :: part_round => dam_part_round
    procedure :: owner_round => dam_owner_round
    procedure, nopass :: pen_rms => dam_pen_rms
    procedure :: bytes => dam_bytes
  end type dam_t

contains

  pure integer function dam_pair_kind()
    dam_pair_kind = PAIR_NODE_SEGMENT
  end function dam_pair_kind

  pure integer function dam_rounds()
    dam_rounds = ROUND_PUT_BACK
  end function dam_rounds

  pure integer function dam_record_width(r)
    integer, intent(in) :: r
    dam_record_width = merge(EXCHANGE_WIDTH, PUT_BACK_WIDTH, r == ROUND_MATCH)
  end function dam_record_width

  pure integer function dam_owner_width(r)
    integer, intent(in) :: r
    dam_owner_width = merge(MATCHED_WIDTH, 0, r == ROUND_MATCH)
  end function dam_owner_width

  !> The deck's normal and symmetric; a reverse pass takes its slave's own
  !> normal (the deck master's): the first pass's master edges and corners
  !> lead there, and the normal at an edge's projection tilts toward the
  !> edge and would move the slave along the surface (docs/contact.md, 6.2).
  subroutine dam_configure(this, spec, reverse, single_part)
    class(dam_t), intent(inout) :: this
    type(contact_spec_t), intent(in) :: spec
    logical, intent(in) :: reverse
    logical, intent(out) :: single_part
    this%slave_normal = spec%normal == 'slave' .or. reverse
    this%symmetric = spec%symmetric .and. .not. reverse
    single_part = .false.
  end subroutine dam_configure

  !> Side a is the slave: the deck's surface_a unless master = 'a'.
  pure subroutine dam_sides(spec, side_a, side_b)
    type(contact_spec_t), intent(in) :: spec
    character(len=SURFACE_LEN), intent(out) :: side_a, side_b
    side_a = spec%surface_a
    side_b = spec%surface_b
    if (spec%master == 'a') then
      side_a = spec%surface_b
      side_b = spec%surface_a
    end if
  end subroutine dam_sides

  pure logical function dam_reverse_pass(this)
    class(dam_t), intent(in) :: this
    dam_reverse_pass = this%symmetric
  end function dam_reverse_pass

  !> One pass enforces slaves only.
  pure logical function dam_no(this)
    class(dam_t), intent(in) :: this
    dam_no = .false.
  end function dam_no

  !> A new local set: the primary pairs follow in the next predictor.
  subroutine dam_localized(this, ct, p)
    class(dam_t), intent(inout) :: this
    type(contact_t), intent(in) :: ct
    type(interface_t), intent(inout) :: p
    if (allocated(this%primary)) deallocate(this%primary)
    if (allocated(this%enforced)) deallocate(this%enforced)
    allocate(this%enforced(ct%ncn))
    this%enforced = .false.
  end subroutine dam_localized

  subroutine dam_part_round(this, ct, p, k, r, dt, final, inflow, out)
    class(dam_t), intent(inout) :: this
    type(contact_t), intent(in) :: ct
    type(interface_t), intent(inout) :: p
    integer, intent(in) :: k, r
    real(rk), intent(in) :: dt
    logical, intent(in) :: final
    real(rk), intent(in) :: inflow(:, :)
    type(records_t), intent(inout) :: out
    if (r == ROUND_MATCH) then
      call dam_exchange(this, ct, p, k, dt, final, out)
    else
      call dam_put_back(this, ct, p, k, dt, inflow(1:3, :), inflow(4:6, :), inflow(7, :), out)
    end if
  end subroutine dam_part_round

  subroutine dam_owner_round(this, ct, p, r, rec, v_old, force, dt, values, fc, has)
    class(dam_t), intent(inout) :: this
    type(contact_t), intent(in) :: ct
    type(interface_t), intent(inout) :: p
    integer, intent(in) :: r
    type(records_t), intent(in) :: rec
    real(rk), intent(in) :: v_old(:, :), force(:, :), dt
    real(rk), intent(out) :: values(:, :)
    real(rk), intent(inout) :: fc(:, :)
    logical, intent(inout) :: has(:)
    if (r == ROUND_MATCH) then
      if (allocated(this%vmatch)) deallocate(this%vmatch, this%touched)
      allocate(this%vmatch(MATCHED_WIDTH, ct%nown), this%touched(ct%nown))
      call match_masters(ct, rec, v_old, force, dt, this%vmatch, this%touched)
      values = this%vmatch
    else
      call dam_forces(ct, p, rec, v_old, force, dt, this%vmatch, this%touched, fc, has)
    end if
  end subroutine dam_owner_round

  !> Over the penetrating slaves.
  pure real(rk) function dam_pen_rms(pen_sq, weight)
    real(rk), intent(in) :: pen_sq, weight
    dam_pen_rms = sqrt(pen_sq / max(weight, 1.0_rk))
  end function dam_pen_rms

  pure real(rk) function dam_bytes(this)
    class(dam_t), intent(in) :: this
    dam_bytes = 0.0_rk
    if (allocated(this%ex_real)) dam_bytes = real(size(this%ex_real), rk) * 8.0_rk + &
        real(size(this%ex_master), rk) * 4.0_rk
  end function dam_bytes

  !> DAM geometry at x^n (once per cycle, in the predictor; both stages use
  !> x^n): the primary pairs within the capture distance of a full step, the
  !> facet overlaps of each slave node's facets with the facets of its primary
  !> segment's neighbourhood (projected on the slave facet's plane), and the
  !> RBF put-back weights.
  subroutine dam_geometry(m_, ct, p, dt)
    type(dam_t), intent(inout) :: m_
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
    call primary_pairs(ct%x, p%b, p%pairs, capture, 0.5_rk * p%size, m_%primary, &
        p%loffset)
    if (allocated(m_%rbf)) deallocate(m_%rbf, m_%ex_start, m_%excess, m_%recover)
    allocate(m_%rbf(4, size(m_%primary)), m_%ex_start(size(m_%primary) + 1), &
        m_%excess(size(m_%primary)), m_%recover(size(m_%primary)))
    if (.not. allocated(m_%ex_master)) allocate(m_%ex_master(64), m_%ex_real(3, 64))
    nex = 0
    associate(gs => p%ga, gm => p%gb)
      do q = 1, size(m_%primary)
        m_%ex_start(q) = nex + 1
        n = m_%primary(q)%node
        do k = 1, 4
          pos(:, k) = ct%x(:, p%b%segments(k, m_%primary(q)%segment))
        end do
        ! Penetration beyond the initial offset the deck kept and the
        ! allowance (the slave's nodal area against the master segment's).
        m_%excess(q) = recovery_excess(-m_%primary(q)%gap - p%loffset(n), &
            recovery_allowance(p%spec%penetration_tolerance, gs%nodal_area(n), &
            sum(gm%area(:, m_%primary(q)%segment)), p%lsag_b(m_%primary(q)%segment)))
        if (m_%slave_normal) call use_slave_normal(p%a, gs, n, m_%primary(q)%normal)
        call rbf_weights(pos, ct%x(:, n), m_%primary(q)%normal, m_%rbf(:, q), ok)
        if (.not. ok) call bilinear_shape(m_%primary(q)%xi, m_%primary(q)%eta, m_%rbf(:, q))
        call master_neighbourhood(p%b, m_%primary(q)%segment, candidates, ncand)
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
    m_%ex_start(size(m_%primary) + 1) = nex + 1

  contains

    subroutine add_exchange(m, wm, ws, s0)
      integer(ik), intent(in) :: m
      real(rk), intent(in) :: wm, ws, s0
      integer, allocatable :: grown_master(:)
      real(rk), allocatable :: grown_real(:, :)
      if (nex == size(m_%ex_master)) then
        allocate(grown_master(2 * nex), grown_real(3, 2 * nex))
        grown_master(:nex) = m_%ex_master(:nex)
        grown_real(:, :nex) = m_%ex_real(:, :nex)
        call move_alloc(grown_master, m_%ex_master)
        call move_alloc(grown_real, m_%ex_real)
      end if
      nex = nex + 1
      m_%ex_master(nex) = m
      m_%ex_real(:, nex) = [wm, ws, s0]
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
  subroutine dam_exchange(m_, ct, p, k, dt, final, out)
    type(dam_t), intent(inout) :: m_
    type(contact_t), intent(in) :: ct
    type(interface_t), intent(inout) :: p
    integer, intent(in) :: k !< the interface's number
    real(rk), intent(in) :: dt !< the stage's step
    logical, intent(in) :: final !< the corrector (geometry cached by the predictor)
    type(records_t), intent(inout) :: out !< nv = 10: mass, force, momentum, master normal
    real(rk) :: nrm(3), shape(4), am, vm, as, vs, gfree, wm, ws, s0, step
    real(rk) :: buf(10)
    integer(i8) :: base
    integer :: q, n, c, e, m
    logical :: also_master

    ! The predictor's step is half the cycle's.
    if (.not. final .or. .not. allocated(m_%primary)) call dam_geometry(m_, ct, p, &
        merge(dt, 2.0_rk * dt, final))

    ! Which slave nodes are enforced: the free motion would close the gap,
    ! or leave it deeper than the allowance. A slave beyond its allowance is
    ! put back with the separating speed that removes DAM_RECOVERY of the
    ! excess over the cycle (taken over the stable step, as DLM's recovery:
    ! a short landing step does not fling it out).
    step = merge(dt, 2.0_rk * dt, final)
    m_%enforced = .false.
    do q = 1, size(m_%primary)
      n = m_%primary(q)%node
      m_%recover(q) = recovery_speed_of(DAM_RECOVERY, m_%excess(q), ct%landing, step, &
          ct%speed)
      nrm = m_%primary(q)%normal
      call bilinear_shape(m_%primary(q)%xi, m_%primary(q)%eta, shape)
      am = 0.0_rk
      vm = 0.0_rk
      do c = 1, 4
        m = p%b%segments(c, m_%primary(q)%segment)
        am = am + shape(c) * dot_product(ct%f(:, m), nrm) / ct%mass(m)
        vm = vm + shape(c) * dot_product(ct%v(:, m), nrm)
      end do
      as = dot_product(ct%f(:, n), nrm) / ct%mass(n)
      vs = dot_product(ct%v(:, n), nrm)
      gfree = m_%primary(q)%gap + dt * (vs - vm) + 0.5_rk * dt * dt * (as - am)
      ! Release (3.7): the free motion at t^n+1 separates the slave from the
      ! master (tension); a residual penetration does not hold it. This is
      ! the rule of the unilateral rigid wall, so the mirror test holds.
      if (vs - vm + dt * (as - am) > m_%recover(q)) cycle
      if (gfree < 0.0_rk .or. m_%excess(q) > 0.0_rk) m_%enforced(n) = .true.
    end do

    ! Exchange over the cached facet overlaps.
    do q = 1, size(m_%primary)
      n = m_%primary(q)%node
      if (.not. m_%enforced(n)) cycle
      base = int(ct%all_of(n), i8) * 65536_i8
      ! The slave's own sums matter only where it is a master node too.
      also_master = surface_node_index(p%b, int(n, ik)) > 0
      do e = m_%ex_start(q), m_%ex_start(q + 1) - 1
        m = m_%ex_master(e)
        wm = m_%ex_real(1, e)
        ws = m_%ex_real(2, e)
        s0 = m_%ex_real(3, e)
        ! (Values assembled in a fixed-size buffer: an array constructor of
        ! sections is built on the heap.)
        if (also_master) then
          buf(1) = ct%mass(m) * wm
          buf(2:4) = ct%f(:, m) * wm
          buf(5:7) = ct%mass(m) * ct%v(:, m) * wm
          buf(8:10) = 0.0_rk
          call add_record(out, n, k, base + int(2 * (e - m_%ex_start(q)), i8), buf)
        end if
        buf(1) = ct%mass(n) * ws
        buf(2:4) = ct%f(:, n) * ws
        buf(5:7) = ct%mass(n) * ct%v(:, n) * ws
        buf(8:10) = s0 * m_%primary(q)%normal
        call add_record(out, m, k, base + int(2 * (e - m_%ex_start(q)) + 1, i8), buf)
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
  subroutine dam_put_back(m_, ct, p, k, dt, vm, um, merged, out)
    type(dam_t), intent(inout) :: m_
    type(contact_t), intent(in) :: ct
    type(interface_t), intent(inout) :: p
    integer, intent(in) :: k !< the interface's number
    real(rk), intent(in) :: dt !< the stage's step
    real(rk), intent(in) :: vm(:, :) !< (3, ncn) matched velocities of the local set
    real(rk), intent(in) :: um(:, :) !< (3, ncn) their matching normals (0: not matched)
    !> (ncn) the slave mass each master merged (sum of w_s M_s over its slaves; 0: none)
    real(rk), intent(in) :: merged(:)
    type(records_t), intent(inout) :: out !< nv = 3: the slave's final velocity
    real(rk) :: nrm(3), target, pen, pen_max, pen_sq, sum_force, vnew(3), vmi(3), dv(3)
    real(rk) :: defect(3), vput(3)
    integer, allocatable :: group(:)
    real(rk), allocatable :: share(:)
    integer :: ngroup
    integer :: q, n, c, e, active, npen

    allocate(group(16), share(16))
    active = 0
    npen = 0
    pen_max = 0.0_rk
    pen_sq = 0.0_rk
    sum_force = 0.0_rk
    do q = 1, size(m_%primary)
      n = m_%primary(q)%node
      if (.not. m_%enforced(n)) cycle
      active = active + 1
      nrm = m_%primary(q)%normal
      target = 0.0_rk
      do c = 1, 4
        target = target + m_%rbf(c, q) * dot_product(vm(:, p%b%segments(c, &
            m_%primary(q)%segment)), nrm)
      end do
      target = target + m_%recover(q)
      vnew = dam_put_back_velocity(vm(:, n), nrm, target)
      vput = vnew
      ! A slave whose motion is prescribed (a rigid platen's node in a
      ! reverse pass) keeps its velocity (dam_forces), so it takes no
      ! friction and gives none: its reaction, its scaled mass
      ! (RIGID_MASS_FACTOR) times a velocity bounded only by round-off,
      ! crushed the folding tube's top ring in cycle 3. The friction of that
      ! patch is the other pass's, where the deformable side is the slave.
      if (p%spec%friction > 0.0_rk .and. .not. ct%rigid(n)) then
        vmi = 0.0_rk
        do c = 1, 4
          vmi = vmi + m_%rbf(c, q) * vm(:, p%b%segments(c, m_%primary(q)%segment))
        end do
        dv = dam_friction_velocity(p%spec%friction, vnew, vmi, nrm, &
            target - dot_product(vm(:, n), nrm))
        vnew = vnew + dv
        do c = 1, 4
          call add_record(out, p%b%segments(c, m_%primary(q)%segment), k, &
              int(ct%nall, i8) + 4_i8 * int(ct%all_of(n), i8) + int(c - 1, i8), &
              -(ct%mass(n) * m_%rbf(c, q)) * dv)
        end do
      end if
      call add_record(out, n, k, int(ct%all_of(n), i8), vnew)
      ! Momentum (docs/contact.md, 6, step 4b): each master's matched change is
      ! the sum over its slaves of w m_s (v_s - v_m).u u (w the exchange
      ! weight, u the master's merged normal, v_m its matched velocity); the
      ! slave's own change is m_s (vnew - v_s), along its own normal and
      ! with the RBF weights. What the two leave over (the defect) is taken
      ! off the slave and its masters as one velocity change of them all,
      ! each master with the part of its mass this slave merged into it, so
      ! together they gain no momentum, and a defect the same for all the
      ! slaves of a patch moves slaves and masters alike, leaving the
      ! relative velocities the matching set. In self-contact a slave is a
      ! master too: its matched velocity vm(n) is where its put-back starts,
      ! so the same defect applies (without it the folding tube's closed
      ! fold gained +1.7e-5, 1.2% of the platen's input; with it the
      ! self-contact work is <= 0 at every step).
      defect = ct%mass(n) * (vput - vm(:, n))
      ngroup = 0
      if (m_%ex_start(q + 1) > m_%ex_start(q)) then
        do e = m_%ex_start(q), m_%ex_start(q + 1) - 1
          c = m_%ex_master(e)
          defect = defect + (m_%ex_real(2, e) * ct%mass(n) * dot_product(vm(:, n) - &
              vm(:, c), um(:, c))) * um(:, c)
          ! The master's mass in this group: its part of M(m) in
          ! proportion to the slave mass this slave merged into it.
          if (merged(c) > 0.0_rk) then
            call join_group(c, ct%mass(c) * m_%ex_real(2, e) * ct%mass(n) / merged(c))
          else
            call join_group(c, ct%mass(c))
          end if
        end do
      else
        ! No facet overlap (the slave beside the master's edge), so
        ! nothing was exchanged: the group is the primary segment.
        do c = 1, 4
          call join_group(p%b%segments(c, m_%primary(q)%segment), &
              ct%mass(p%b%segments(c, m_%primary(q)%segment)))
        end do
      end if
      call join_group(n, ct%mass(n))
      dv = -defect / sum(share(:ngroup))
      do c = 1, ngroup
        call add_record(out, group(c), k, 5_i8 * int(ct%nall, i8) + &
            65536_i8 * int(ct%all_of(n), i8) + int(c - 1, i8), share(c) * dv)
      end do
      sum_force = sum_force + max(dot_product(ct%mass(n) * (vnew - ct%v(:, n)) / dt - &
          ct%f(:, n), nrm), 0.0_rk)
      pen = -m_%primary(q)%gap
      if (pen > 0.0_rk) then
        pen_max = max(pen_max, pen)
        pen_sq = pen_sq + pen * pen
        npen = npen + 1
      end if
    end do
    p%sums%active = real(active, rk)
    p%sums%force = sum_force
    p%sums%pen_max = pen_max
    p%sums%pen_sq = pen_sq
    p%sums%weight = real(npen, rk)

  contains

    !> Add mass to node's share of the group (a new member if it is not one).
    subroutine join_group(node, mass)
      integer, intent(in) :: node
      real(rk), intent(in) :: mass
      integer, allocatable :: grown(:)
      real(rk), allocatable :: grown_share(:)
      integer :: i
      do i = 1, ngroup
        if (group(i) == node) then
          share(i) = share(i) + mass
          return
        end if
      end do
      if (ngroup == size(group)) then
        allocate(grown(2 * ngroup), grown_share(2 * ngroup))
        grown(:ngroup) = group(:ngroup)
        grown_share(:ngroup) = share(:ngroup)
        call move_alloc(grown, group)
        call move_alloc(grown_share, share)
      end if
      ngroup = ngroup + 1
      group(ngroup) = node
      share(ngroup) = mass
    end subroutine join_group

  end subroutine dam_put_back

  !> DAM at the owners, first round: the exchanged mass, force and momentum
  !> of the owned nodes summed in key order, then the velocities: free, and
  !> for master nodes the matched normal component (docs/contact.md, 6).
  subroutine match_masters(ct, r, v_old, force, dt, vmatch, touched)
    type(contact_t), intent(in) :: ct
    type(records_t), intent(in) :: r
    real(rk), intent(in) :: v_old(:, :), force(:, :), dt
    !> (1:3) velocity, (4:6) matching normal, (7) slave mass merged
    real(rk), intent(out) :: vmatch(:, :)
    logical, intent(out) :: touched(:)
    real(rk), allocatable :: mbar(:), fbar(:, :), pbar(:, :), nmaster(:, :)
    real(rk) :: unit(3), vn, mass
    integer :: i, j, l
    allocate(mbar(ct%nown), fbar(3, ct%nown), pbar(3, ct%nown), nmaster(3, ct%nown))
    touched = .false.
    do i = 1, ct%nown
      l = ct%own_local(i)
      mass = ct%own_mass(i)
      mbar(i) = mass
      fbar(:, i) = force(:, l)
      pbar(:, i) = mass * v_old(:, l)
    end do
    nmaster = 0.0_rk
    do j = 1, r%n
      i = int(r%id(1, j))
      mbar(i) = mbar(i) + r%val(1, j)
      fbar(:, i) = fbar(:, i) + r%val(2:4, j)
      pbar(:, i) = pbar(:, i) + r%val(5:7, j)
      if (mod(r%id(3, j), 2_i8) == 1_i8) then
        nmaster(:, i) = nmaster(:, i) + r%val(8:10, j)
        touched(i) = .true.
      end if
    end do
    do i = 1, ct%nown
      l = ct%own_local(i)
      mass = ct%own_mass(i)
      vmatch(1:3, i) = v_old(:, l) + dt * force(:, l) / mass
      vmatch(4:7, i) = 0.0_rk
      if (.not. touched(i)) cycle
      if (.not. norm2(nmaster(:, i)) > 0.0_rk) cycle
      unit = nmaster(:, i) / norm2(nmaster(:, i))
      vn = dam_merged_normal_velocity(mbar(i), pbar(:, i), fbar(:, i), unit, dt)
      vmatch(1:3, i) = vmatch(1:3, i) + (vn - dot_product(vmatch(1:3, i), unit)) * unit
      vmatch(4:6, i) = unit
      vmatch(7, i) = mbar(i) - mass
    end do
  end subroutine match_masters

  !> DAM at the owners, second round: the final velocities (the put-back-on
  !> of enforced slaves, the matched velocity of touched masters) as forces.
  subroutine dam_forces(ct, p, r, v_old, force, dt, vmatch, touched, fck, has)
    type(contact_t), intent(in) :: ct
    type(interface_t), intent(inout) :: p
    type(records_t), intent(in) :: r
    real(rk), intent(in) :: v_old(:, :), force(:, :), dt
    real(rk), intent(in) :: vmatch(:, :)
    logical, intent(in) :: touched(:)
    real(rk), intent(inout) :: fck(:, :)
    logical, intent(inout) :: has(:)
    real(rk), allocatable :: vfinal(:, :)
    real(rk) :: mass
    integer :: i, j, l
    allocate(vfinal, source=vmatch(1:3, :))
    do j = 1, r%n
      i = int(r%id(1, j))
      if (r%id(3, j) > int(ct%nall, i8)) then
        ! Friction reaction on a master node (dam_put_back): a momentum,
        ! after the node's own put-back if it is a slave too (key order).
        vfinal(:, i) = vfinal(:, i) + r%val(:, j) / ct%own_mass(i)
      else
        vfinal(:, i) = r%val(:, j)
      end if
      has(i) = .true.
    end do
    do i = 1, ct%nown
      if (.not. (has(i) .or. touched(i))) cycle
      if (ct%own_rigid(i)) cycle
      has(i) = .true.
      l = ct%own_local(i)
      mass = ct%own_mass(i)
      fck(:, i) = mass * (vfinal(:, i) - v_old(:, l)) / dt - force(:, l)
      p%sums%dmom = p%sums%dmom + mass * (vfinal(:, i) - v_old(:, l)) - dt * force(:, l)
    end do
  end subroutine dam_forces

end module contact_dam
