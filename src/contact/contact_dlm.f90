!> DLM, the discrete Lagrangian multiplier method (symmetric) of Jia, Gong,
!> Zhang & Liu (J. Comput. Phys. 267 (2014) 247-285), as described in
!> docs/contact.md, section 5: every overlapping facet pair of facing
!> segments is a one-dimensional contact pair with equal and opposite
!> forces. dlm_t is the method (contact_method_t): two rounds a stage, the
!> gated shares of each node (round 1, dlm_cover) and the pair forces (round
!> 2, dlm_step), each a set of records the owners of the nodes sum in key
!> order (contact_records). It holds the cycle's facet pairs.
!>
!> Forms (deck key `form`): with mu = Mh Md/(Mh + Md),
!>   coordinate: fh = mu (Fd/Md - Fh/Mh + (vd - vh)/(dt/2) - pen/(dt^2/2)),
!>   velocity:   fh = mu (Fd/Md - Fh/Mh + (vd - vh - e/dt)/dt), gated by
!>               pen_free > 0, e = recovery * max(pen - allowance, 0): the
!>               approach stopped, and a fraction `recovery` (deck, default
!>               0.2) of the penetration beyond an allowance (docs/contact.md,
!>               9.3) removed per stable step (Baumgarte-type position
!>               feedback; a step cut short to land on a dump time keeps the
!>               stable step's recovery speed, ct%landing; a pair separating
!>               at t^n is not pushed apart faster than it separates).
!>               Without it the one pass, which under-corrects a node whose
!>               neighbours move differently, has nothing to pull a drifting
!>               node back: on the curved Sedov split the ball's valence-3
!>               vertex escaped through the gas
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
!> pen is taken at the overlap's deepest vertex, and the shares of a node's
!> gated pairs are scaled to sum to one (dlm_cover), so that a convex edge or
!> corner is stopped as a whole node (docs/contact.md, 5 and 9.3).
!> fh = min(fh, 0) in every form. Default: velocity. The equal-bars test
!> rejects the coordinate form (15 openings during the contact, interface
!> velocity 11% of v0); velocity and combined both pass it (residual
!> penetration 7.8e-6 and 3.9e-6 cm), but the combined form's push-out
!> velocity r/(2 dt) pumps energy where a large penetration persists (Al on
!> steel at 1 km/s: the run gained more energy than it had and failed), so it
!> stays an option.
module contact_dlm
  use core_kinds, only: rk, i8
  use contact_geometry, only: tangent_basis, segment_box, project_facets, boxes_meet, &
      triangle_overlap_2d, plane_offset, covered, OVERLAP_VERTICES, FACET_CORNER, &
      SEGMENT_FACET_COUNT
  use contact_records, only: records_t, add_record
  use contact_state, only: FACING, FACING_SURFACES, AREA_TOLERANCE, PAIR_SEGMENTS, &
      SURFACE_LEN, interface_t, contact_t, contact_spec_t, contact_method_t, geometry_update, &
      recovery_allowance, recovery_excess, recovery_speed_of, ALLOWANCE_SHARE
  use contact_kernels, only: dlm_pair_force, dlm_pair_friction, KERNEL_COORDINATE, &
      KERNEL_VELOCITY, KERNEL_COMBINED
  implicit none
  private

  !> Default fraction of a facet pair's penetration removed per step in the
  !> velocity form (see dlm_step).
  real(rk), parameter, public :: DLM_DEFAULT_RECOVERY = 0.2_rk

  !> Rounds of a stage and their record layouts: the gated shares (one
  !> value, the node's share of the pair), then the pair forces (a 3-vector).
  integer, parameter :: ROUND_COVER = 1, ROUND_FORCE = 2
  integer, parameter :: COVER_WIDTH = 1, FORCE_WIDTH = 3
  !> Values per owned node after the cover round: the node's summed shares.
  integer, parameter :: COVER_SUM_WIDTH = 1

  !> DLM: the method and its cache of the cycle's facet pairs (on this part).
  type, extends(contact_method_t), public :: dlm_t
    integer :: form = KERNEL_VELOCITY !< KERNEL_COORDINATE, _VELOCITY or _COMBINED
    real(rk) :: recovery = DLM_DEFAULT_RECOVERY !< velocity form: penetration fraction per step
    integer :: nfp = 0 !< facet pairs of the cycle
    integer, allocatable :: fp_node(:, :) !< (2, nfp) hitting and target node
    integer(i8), allocatable :: fp_key(:) !< (nfp) global order of the facet pair
    real(rk), allocatable :: fp_share(:, :) !< (2, nfp) shares of the hitting and target node
    real(rk), allocatable :: fp_normal(:, :) !< (3, nfp) common normal (from the hitting side)
    real(rk), allocatable :: fp_pen(:) !< (nfp) penetration at the overlap's deepest vertex (the gate)
    real(rk), allocatable :: fp_area(:) !< (nfp) overlap area
    real(rk), allocatable :: fp_allowance(:) !< (nfp) the pair's recovery allowance
    logical, allocatable :: fp_gated(:) !< (nfp) the pair's gate in this stage (dlm_cover)
  contains
    procedure, nopass :: pair_kind => dlm_pair_kind
    procedure, nopass :: rounds => dlm_rounds
    procedure, nopass :: record_width => dlm_record_width
    procedure, nopass :: owner_width => dlm_owner_width
    procedure :: configure => dlm_configure
    procedure, nopass :: sides => dlm_sides
    procedure :: reverse_pass => dlm_no
    procedure :: enforces_b => dlm_yes
    procedure :: localized => dlm_localized
    procedure :: part_round => dlm_part_round
    procedure :: owner_round => dlm_owner_round
    procedure, nopass :: pen_rms => dlm_pen_rms
    procedure :: bytes => dlm_bytes
  end type dlm_t

contains

  pure integer function dlm_pair_kind()
    dlm_pair_kind = PAIR_SEGMENTS
  end function dlm_pair_kind

  pure integer function dlm_rounds()
    dlm_rounds = ROUND_FORCE
  end function dlm_rounds

  pure integer function dlm_record_width(r)
    integer, intent(in) :: r
    dlm_record_width = merge(COVER_WIDTH, FORCE_WIDTH, r == ROUND_COVER)
  end function dlm_record_width

  pure integer function dlm_owner_width(r)
    integer, intent(in) :: r
    dlm_owner_width = merge(COVER_SUM_WIDTH, 0, r == ROUND_COVER)
  end function dlm_owner_width

  !> The deck's form and recovery; with sweeps > 1 the Gauss-Seidel over all
  !> pairs is sequential, on part 0.
  subroutine dlm_configure(this, spec, reverse, single_part)
    class(dlm_t), intent(inout) :: this
    type(contact_spec_t), intent(in) :: spec
    logical, intent(in) :: reverse
    logical, intent(out) :: single_part
    select case (spec%form)
    case ('coordinate')
      this%form = KERNEL_COORDINATE
    case ('combined')
      this%form = KERNEL_COMBINED
    case default
      this%form = KERNEL_VELOCITY
    end select
    this%recovery = DLM_DEFAULT_RECOVERY
    if (spec%recovery >= 0.0_rk) this%recovery = spec%recovery
    single_part = spec%sweeps > 1 .and. .not. reverse
  end subroutine dlm_configure

  !> Symmetric: the deck's sides as they are.
  pure subroutine dlm_sides(spec, side_a, side_b)
    type(contact_spec_t), intent(in) :: spec
    character(len=SURFACE_LEN), intent(out) :: side_a, side_b
    side_a = spec%surface_a
    side_b = spec%surface_b
  end subroutine dlm_sides

  pure logical function dlm_no(this)
    class(dlm_t), intent(in) :: this
    dlm_no = .false.
  end function dlm_no

  pure logical function dlm_yes(this)
    class(dlm_t), intent(in) :: this
    dlm_yes = .true.
  end function dlm_yes

  !> The facet pairs are recomputed in the next predictor.
  subroutine dlm_localized(this, ct, p)
    class(dlm_t), intent(inout) :: this
    type(contact_t), intent(in) :: ct
    type(interface_t), intent(inout) :: p
  end subroutine dlm_localized

  subroutine dlm_part_round(this, ct, p, k, r, dt, final, inflow, out)
    class(dlm_t), intent(inout) :: this
    type(contact_t), intent(in) :: ct
    type(interface_t), intent(inout) :: p
    integer, intent(in) :: k, r
    real(rk), intent(in) :: dt
    logical, intent(in) :: final
    real(rk), intent(in) :: inflow(:, :)
    type(records_t), intent(inout) :: out
    if (r == ROUND_COVER) then
      call dlm_cover(this, ct, p, k, dt, final, out)
    else
      call dlm_step(this, ct, p, k, dt, inflow(1, :), out)
    end if
  end subroutine dlm_part_round

  !> The owners: each node's shares summed (round 1), the pair forces summed
  !> (round 2), in key order.
  subroutine dlm_owner_round(this, ct, p, r, rec, v_old, force, dt, values, fc, has)
    class(dlm_t), intent(inout) :: this
    type(contact_t), intent(in) :: ct
    type(interface_t), intent(inout) :: p
    integer, intent(in) :: r
    type(records_t), intent(in) :: rec
    real(rk), intent(in) :: v_old(:, :), force(:, :), dt
    real(rk), intent(out) :: values(:, :)
    real(rk), intent(inout) :: fc(:, :)
    logical, intent(inout) :: has(:)
    integer :: j, i
    if (r == ROUND_COVER) then
      values = 0.0_rk
      do j = 1, rec%n
        i = int(rec%id(1, j))
        values(:, i) = values(:, i) + rec%val(:, j)
      end do
    else
      do j = 1, rec%n
        i = int(rec%id(1, j))
        fc(:, i) = fc(:, i) + rec%val(:, j)
        has(i) = .true.
      end do
    end if
  end subroutine dlm_owner_round

  !> Over the overlap area.
  pure real(rk) function dlm_pen_rms(pen_sq, weight)
    real(rk), intent(in) :: pen_sq, weight
    dlm_pen_rms = sqrt(pen_sq / max(weight, tiny(1.0_rk)))
  end function dlm_pen_rms

  pure real(rk) function dlm_bytes(this)
    class(dlm_t), intent(in) :: this
    dlm_bytes = 0.0_rk
    if (allocated(this%fp_node)) dlm_bytes = real(9 * size(this%fp_pen), rk) * 8.0_rk + &
        real(size(this%fp_node), rk) * 4.0_rk + real(size(this%fp_key), rk) * 8.0_rk
  end function dlm_bytes

  !> DLM geometry at x^n (the same for both stages, so computed once per
  !> cycle, in the predictor): every overlapping facet pair of facing
  !> segments with its nodes, shares, common normal and penetration. The
  !> facets of a segment pair are projected once on the common plane
  !> (coordinates relative to segment a's centre); the overlap centroid lies
  !> in that plane, and the penetration, a difference of two distances along
  !> the normal, does not depend on where along the normal it lies.
  subroutine dlm_geometry(dl, ct, p)
    type(dlm_t), intent(inout) :: dl
    type(contact_t), intent(in) :: ct
    type(interface_t), intent(inout) :: p
    real(rk) :: na(3), nb(3), nrm(3), s0, centroid(3), pen, wh, wd, t1(3), t2(3), origin(3)
    real(rk) :: allowance, kept, poly(2, OVERLAP_VERTICES), deepest, corner(3)
    integer :: npoly, v
    real(rk) :: box_a(4, SEGMENT_FACET_COUNT), box_b(4, SEGMENT_FACET_COUNT), seg_a(4), seg_b(4)
    real(rk) :: a2(2, 3, SEGMENT_FACET_COUNT), b2(2, 3, SEGMENT_FACET_COUNT), centre2(2)
    integer :: m, sa, sb, i, j, nodeh, noded
    logical :: a_hits

    call geometry_update(ct%x, p%a, p%ga)
    call geometry_update(ct%x, p%b, p%gb)
    dl%nfp = 0
    if (.not. allocated(dl%fp_node)) allocate(dl%fp_node(2, 64), dl%fp_share(2, 64), &
        dl%fp_normal(3, 64), dl%fp_pen(64), dl%fp_area(64), dl%fp_allowance(64), dl%fp_gated(64), &
        dl%fp_key(64))
    associate(ga => p%ga, gb => p%gb)
      do m = 1, size(p%pairs, 2)
        sa = p%pairs(1, m)
        sb = p%pairs(2, m)
        na = ga%quad_normal(:, sa)
        nb = gb%quad_normal(:, sb)
        if (.not. dot_product(na, nb) < merge(FACING, FACING_SURFACES, p%self)) cycle
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
        allowance = recovery_allowance(p%spec%penetration_tolerance, sum(ga%area(:, sa)), &
            sum(gb%area(:, sb)), max(p%lsag_a(sa), p%lsag_b(sb)))
        call project_facets(ga%facets(:, :, :, sa), origin, t1, t2, a2, box_a)
        call project_facets(gb%facets(:, :, :, sb), origin, t1, t2, b2, box_b)
        do i = 1, SEGMENT_FACET_COUNT
          if (.not. boxes_meet(box_a(:, i), seg_b)) cycle
          do j = 1, SEGMENT_FACET_COUNT
            if (.not. boxes_meet(box_a(:, i), box_b(:, j))) cycle
            if (a_hits) then
              call triangle_overlap_2d(a2(:, :, i), b2(:, :, j), s0, centre2, poly, npoly)
            else
              call triangle_overlap_2d(b2(:, :, j), a2(:, :, i), s0, centre2, poly, npoly)
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
            ! The penetration of the pair is taken at the overlap's deepest
            ! vertex (the two facets' planes differ linearly over the
            ! overlap, so a vertex holds the extreme): at a convex edge or
            ! corner that meets the other surface the centroid lies up the
            ! slope and let the edge sink by the slope times its distance
            ! (docs/contact.md, 9.3).
            deepest = pen
            do v = 1, npoly
              corner = origin + poly(1, v) * t1 + poly(2, v) * t2
              if (a_hits) then
                deepest = max(deepest, plane_offset(ga%facets(:, 1, i, sa), ga%normal(:, i, sa), &
                    corner, nrm) - plane_offset(gb%facets(:, 1, j, sb), gb%normal(:, j, sb), &
                    corner, nrm))
              else
                deepest = max(deepest, plane_offset(gb%facets(:, 1, j, sb), gb%normal(:, j, sb), &
                    corner, nrm) - plane_offset(ga%facets(:, 1, i, sa), ga%normal(:, i, sa), &
                    corner, nrm))
              end if
            end do
            pen = deepest
            ! The initial penetration the deck kept (contact_initial) is
            ! held, not pushed out.
            kept = max(p%loffset(nodeh), p%loffset(noded))
            ! Deeper than half a segment: the far side of a body, not contact.
            ! The segment is the smaller of the two here, not the surfaces'
            ! median: a surface given by blocks takes in the large graded
            ! faces far from the impact, and a median of 18 mm let a
            ! penetration run's 0.5 mm rod facets take target faces 9 mm
            ! away for contact and push them out.
            if (pen - kept > 0.5_rk * min(p%size, sqrt(min(sum(ga%area(:, sa)), &
                sum(gb%area(:, sb)))))) cycle
            call add_facet_pair(dl, nodeh, noded, wh, wd, pen - kept, s0, nrm, allowance, &
                p%pair_key(m) * 64_i8 + int(8 * (i - 1) + j - 1, i8))
          end do
        end do
      end do
    end associate

  end subroutine dlm_geometry

  !> Append one facet pair to the interface's cache, growing it when full.
  subroutine add_facet_pair(dl, nodeh, noded, wh, wd, pen, s0, nrm, allowance, key)
    type(dlm_t), intent(inout) :: dl
    integer, intent(in) :: nodeh, noded
    real(rk), intent(in) :: wh, wd !< the shares of the hitting and target node
    real(rk), intent(in) :: pen !< penetration at the overlap's deepest vertex (also the gate)
    real(rk), intent(in) :: s0, nrm(3) !< overlap area, common normal
    real(rk), intent(in) :: allowance !< the pair's recovery allowance
    integer(i8), intent(in) :: key !< global order: segment pair, facet of a, facet of b
    integer :: n
    if (dl%nfp == size(dl%fp_node, 2)) then
      n = 2 * dl%nfp
      call grow_int2(dl%fp_node, n)
      call grow_real2(dl%fp_share, n)
      call grow_real2(dl%fp_normal, n)
      call grow_real1(dl%fp_pen, n)
      call grow_real1(dl%fp_area, n)
      call grow_real1(dl%fp_allowance, n)
      call grow_logical1(dl%fp_gated, n)
      call grow_key(dl%fp_key, n)
    end if
    dl%nfp = dl%nfp + 1
    dl%fp_node(:, dl%nfp) = [nodeh, noded]
    dl%fp_share(:, dl%nfp) = [wh, wd]
    dl%fp_pen(dl%nfp) = pen
    dl%fp_area(dl%nfp) = s0
    dl%fp_normal(:, dl%nfp) = nrm
    dl%fp_allowance(dl%nfp) = allowance
    dl%fp_key(dl%nfp) = key

  contains

    subroutine grow_int2(a, n)
      integer, allocatable, intent(inout) :: a(:, :)
      integer, intent(in) :: n
      integer, allocatable :: b(:, :)
      allocate(b(size(a, 1), n))
      b(:, :size(a, 2)) = a
      call move_alloc(b, a)
    end subroutine grow_int2

    subroutine grow_real2(a, n)
      real(rk), allocatable, intent(inout) :: a(:, :)
      integer, intent(in) :: n
      real(rk), allocatable :: b(:, :)
      allocate(b(size(a, 1), n))
      b(:, :size(a, 2)) = a
      call move_alloc(b, a)
    end subroutine grow_real2

    subroutine grow_real1(a, n)
      real(rk), allocatable, intent(inout) :: a(:)
      integer, intent(in) :: n
      real(rk), allocatable :: b(:)
      allocate(b(n))
      b(:size(a)) = a
      call move_alloc(b, a)
    end subroutine grow_real1

    subroutine grow_logical1(a, n)
      logical, allocatable, intent(inout) :: a(:)
      integer, intent(in) :: n
      logical, allocatable :: b(:)
      allocate(b(n))
      b(:size(a)) = a
      call move_alloc(b, a)
    end subroutine grow_logical1

    subroutine grow_key(a, n)
      integer(i8), allocatable, intent(inout) :: a(:)
      integer, intent(in) :: n
      integer(i8), allocatable :: b(:)
      allocate(b(n))
      b(:size(a)) = a
      call move_alloc(b, a)
    end subroutine grow_key

  end subroutine add_facet_pair

  !> DLM, first round of a stage: the geometry (in the predictor), each facet
  !> pair's gate, and the shares of the gated pairs of every node, one record
  !> per pair and node for the owners to sum (docs/contact.md, 5: the shares
  !> of a node's gated pairs are scaled to sum to one, so that the node's
  !> whole mass takes part in stopping it; a node at a convex edge or corner
  !> touches the other surface with a sliver of its area only, and with the
  !> raw shares its approach was stopped in proportion to that sliver).
  subroutine dlm_cover(dl, ct, p, k, dt, final, out)
    type(dlm_t), intent(inout) :: dl
    type(contact_t), intent(in) :: ct
    type(interface_t), intent(inout) :: p
    integer, intent(in) :: k !< the interface's number
    real(rk), intent(in) :: dt !< the stage's step
    logical, intent(in) :: final !< the corrector (geometry cached by the predictor)
    type(records_t), intent(inout) :: out !< per gated pair and node: its share
    real(rk) :: nrm(3), wh, wd, mh, md, fh, w
    integer :: q, nodeh, noded

    if (.not. final .or. .not. allocated(dl%fp_node)) call dlm_geometry(dl, ct, p)
    do q = 1, dl%nfp
      nodeh = dl%fp_node(1, q)
      noded = dl%fp_node(2, q)
      wh = dl%fp_share(1, q)
      wd = dl%fp_share(2, q)
      nrm = dl%fp_normal(:, q)
      mh = ct%mass(nodeh) * wh
      md = ct%mass(noded) * wd
      w = dot_product(ct%v(:, nodeh), nrm) - dot_product(ct%v(:, noded), nrm)
      ! The gate: the penetration at the overlap's deepest vertex (dlm_geometry).
      call dlm_pair_force(dl%form, mh, md, dot_product(ct%f(:, nodeh), nrm) * wh, &
          dot_product(ct%f(:, noded), nrm) * wd, w, dl%fp_pen(q), dl%fp_pen(q), dt, 0.0_rk, &
          fh, dl%fp_gated(q))
      if (.not. dl%fp_gated(q)) cycle
      call add_record(out, nodeh, k, dl%fp_key(q), [wh])
      call add_record(out, noded, k, dl%fp_key(q), [wd])
    end do
  end subroutine dlm_cover

  !> DLM: every overlapping facet pair of facing segments is a 1D contact pair
  !> (geometry and gates from dlm_cover, forces of the stage).
  subroutine dlm_step(dl, ct, p, k, dt, cover, out)
    type(dlm_t), intent(inout) :: dl
    type(contact_t), intent(in) :: ct
    type(interface_t), intent(inout) :: p
    integer, intent(in) :: k !< the interface's number
    real(rk), intent(in) :: dt !< the stage's step
    !> (ncn) per local node, the sum of its shares over the gated pairs of
    !> the interface (all parts; 0: in none)
    real(rk), intent(in) :: cover(:)
    type(records_t), intent(inout) :: out !< the contributions, for the owners
    real(rk), allocatable :: lambda(:), fc(:, :), ft(:, :)
    logical, allocatable :: gated(:)
    real(rk) :: nrm(3), s0, pen, wh, wd
    real(rk) :: mh, md, fh_, fd_, vh, vd, mu, fh, w, sum_force, pen_max
    real(rk) :: pen_sq, area_sum
    integer :: q, i, nodeh, noded, active, sweep

    allocate(lambda(dl%nfp), gated(dl%nfp), fc(3, ct%ncn))
    lambda = 0.0_rk
    fc = 0.0_rk
    ! Sweep 1 is the one-pass DLM: every pair from the free (hydro) state.
    ! Later sweeps (Gauss-Seidel, in the fixed pair order) add to each pair
    ! force the correction its residual approach asks for, given the contact
    ! forces of all pairs so far; sum(lambda) stays <= 0 per pair and each
    ! correction is applied equal and opposite, so momentum stays exact.
    do sweep = 1, max(p%spec%sweeps, 1)
      do q = 1, dl%nfp
        nodeh = dl%fp_node(1, q)
        noded = dl%fp_node(2, q)
        wh = share(1, q)
        wd = share(2, q)
        pen = dl%fp_pen(q)
        nrm = dl%fp_normal(:, q)
        mh = ct%mass(nodeh) * wh
        md = ct%mass(noded) * wd
        mu = mh * md / (mh + md)
        vh = dot_product(ct%v(:, nodeh), nrm)
        vd = dot_product(ct%v(:, noded), nrm)
        w = vh - vd
        if (sweep == 1) then
          fh_ = dot_product(ct%f(:, nodeh), nrm) * wh
          fd_ = dot_product(ct%f(:, noded), nrm) * wd
          ! The gate was decided in dlm_cover (the one its shares count).
          call dlm_pair_force(dl%form, mh, md, fh_, fd_, w, pen, dl%fp_pen(q), dt, &
              recovery_speed(q, w), fh, gated(q), dl%fp_gated(q))
        else
          if (.not. gated(q) .or. dl%form /= KERNEL_VELOCITY) cycle
          ! Residual approach at t^n+1 with every contact force so far.
          fh_ = dot_product(ct%f(:, nodeh) + fc(:, nodeh), nrm) * wh
          fd_ = dot_product(ct%f(:, noded) + fc(:, noded), nrm) * wd
          fh = min(lambda(q) + mu * (fd_ / md - fh_ / mh + (recovery_speed(q, w) - w) / dt), &
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
      allocate(ft(3, dl%nfp))
      ft = 0.0_rk
      do q = 1, dl%nfp
        if (.not. lambda(q) < 0.0_rk) cycle
        nodeh = dl%fp_node(1, q)
        noded = dl%fp_node(2, q)
        wh = share(1, q)
        wd = share(2, q)
        nrm = dl%fp_normal(:, q)
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
        if (any(fc(:, i) /= 0.0_rk)) call add_record(out, i, k, 0_i8, fc(:, i))
      end do
    else
      do q = 1, dl%nfp
        if (lambda(q) == 0.0_rk) cycle
        nrm = dl%fp_normal(:, q)
        if (allocated(ft)) then
          call add_record(out, dl%fp_node(1, q), k, dl%fp_key(q), &
              lambda(q) * nrm + ft(:, q))
          call add_record(out, dl%fp_node(2, q), k, dl%fp_key(q), &
              -(lambda(q) * nrm + ft(:, q)))
        else
          call add_record(out, dl%fp_node(1, q), k, dl%fp_key(q), lambda(q) * nrm)
          call add_record(out, dl%fp_node(2, q), k, dl%fp_key(q), -(lambda(q) * nrm))
        end if
      end do
    end if

    active = 0
    sum_force = 0.0_rk
    pen_max = 0.0_rk
    pen_sq = 0.0_rk
    area_sum = 0.0_rk
    do q = 1, dl%nfp
      if (.not. lambda(q) < 0.0_rk) cycle
      pen = dl%fp_pen(q)
      s0 = dl%fp_area(q)
      active = active + 1
      sum_force = sum_force - lambda(q)
      if (pen > 0.0_rk) then
        pen_max = max(pen_max, pen)
        pen_sq = pen_sq + s0 * pen * pen
      end if
      area_sum = area_sum + s0
    end do
    p%sums%active = real(active, rk)
    p%sums%force = sum_force
    p%sums%pen_max = pen_max
    p%sums%pen_sq = pen_sq
    p%sums%weight = area_sum
    do i = 1, ct%ncn
      p%sums%dmom = p%sums%dmom + fc(:, i)
    end do
    ! A momentum: the forces over the step.
    p%sums%dmom = dt * p%sums%dmom
  contains

    !> Target approach speed of facet pair q in the velocity form: the
    !> separation that removes the fraction dl%recovery of its penetration at
    !> t^n over the step (0 for a gap). A pair deeper than the audit's
    !> tolerance (its allowance / ALLOWANCE_SHARE) that already separates at
    !> t^n (w < 0) is not pushed apart faster than it separates: its
    !> penetration shrinks already, and the push only adds kinetic energy
    !> (docs/contact.md, 9.3: on the penetration problem's folded nose rim,
    !> pairs 0.5-0.9 mm deep by their facets' planes while no node was,
    !> separating at 150 m/s, were pushed apart at 950 m/s: +80 J of
    !> contact work in 3.5 us). Within the tolerance the recovery is the
    !> drift correction the method needs and is left whole.
    pure real(rk) function recovery_speed(q, w) result(speed)
      integer, intent(in) :: q
      real(rk), intent(in) :: w !< the pair's approach speed at t^n
      speed = -recovery_speed_of(dl%recovery, recovery_excess(dl%fp_pen(q), &
          dl%fp_allowance(q)), ct%landing, dt, ct%speed)
      ! Beyond the tolerance: pen > allowance / share.
      if (w < 0.0_rk .and. ALLOWANCE_SHARE * dl%fp_pen(q) > dl%fp_allowance(q)) &
          speed = max(speed, w)
    end function recovery_speed

    !> Share c of facet pair q (c = 1 hitting, 2 target node), scaled by the
    !> node's cover: its gated shares then sum to one.
    pure real(rk) function share(c, q)
      integer, intent(in) :: c, q
      integer :: node
      node = dl%fp_node(c, q)
      share = dl%fp_share(c, q)
      if (cover(node) > 0.0_rk) share = share / cover(node)
    end function share

  end subroutine dlm_step

end module contact_dlm
