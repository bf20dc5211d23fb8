!> The contact's step limit at impact (docs/contact.md, 4.2).
!>
!> Both methods stop an approach on the velocities at t^n+1: the pair's
!> relative normal velocity at the end of the step is zero (or the
!> recovery's small separating speed). Positions advance with the mean of
!> v^n and v^n+1, so a node that meets the other surface within a step at
!> approach speed w still closes w dt / 2 of the gap after the contact has
!> taken hold: a node that was at gap g at t^n ends at g - w dt / 2. At 5 km/s
!> with a 0.05 us step that is 1.2e-2 cm, more than twice the audit's
!> tolerance, and the recovery then takes several cycles to put it back.
!>
!> So the cycle's step is limited by every node of the part's pairs that
!> approaches a segment from outside (gap g >= 0 at t^n) to dt <= 2 (g + a)
!> / w, a the pair's recovery allowance (0.4 of the audit's tolerance): an
!> impacting node ends at most a inside, which the recovery leaves alone.
!> A node already inside sets no limit: the contact holds it, and what it
!> is deeper than a is the recovery's business. (Taking nodes down to the
!> allowance's depth in too cut most steps of a rod on a plate, DAM: a
!> node resting where the recovery leaves it, at about a, with a small
!> residual approach, set 2 (g + a) / w near zero, 40 of 93 cycles.) Nor
!> does a node moving away, or one whose projection falls outside the
!> segment. The limit never cuts the step below IMPACT_FLOOR of the planned
!> step. The gap is taken to the segment's mean plane at x^n; the limit is a
!> minimum over pairs, so it does not depend on how the pairs are spread
!> over the parts and ranks.
module contact_impact
  use core_kinds, only: rk
  use contact_state, only: contact_t, interface_t, PAIR_SEGMENTS, recovery_allowance
  use contact_geometry, only: quad_unit_normal
  use mesh_geometry, only: cross
  implicit none
  private
  public :: impact_step_limit

  !> The impact limit never cuts a step below this share of the planned one:
  !> at 5 km/s with the Al-on-steel decks' tolerance it asks about 1/6.
  real(rk), parameter, public :: IMPACT_FLOOR = 0.1_rk
  !> A projection within this share of an edge's length outside it is on it.
  real(rk), parameter :: EDGE_SHARE = 1.0e-6_rk

  !> A local surface's segments at x^n, for the limit.
  type :: segment_data_t
    real(rk), allocatable :: normal(:, :), centre(:, :), velocity(:, :) !< (3, nseg)
    real(rk), allocatable :: allowance(:) !< (nseg) recovery allowance
  end type segment_data_t

contains

  !> The step this rank's part of the contact allows at t^n (huge: no
  !> limit), from the local set's x^n and v^n and every interface's pairs.
  !> Local: the caller takes the minimum over the ranks. Each segment's
  !> plane, mean velocity and allowance are taken once (a segment is in
  !> many pairs); a node then costs a few products until it is found to
  !> approach from outside.
  function impact_step_limit(ct) result(limit)
    type(contact_t), intent(in) :: ct
    real(rk) :: limit
    type(segment_data_t) :: da, db
    integer :: k, m, c
    limit = huge(1.0_rk)
    do k = 1, ct%npair
      associate(p => ct%pairs(k))
        if (.not. allocated(p%pairs)) cycle
        if (size(p%pairs, 2) == 0) cycle
        call segment_data(p, p%b%segments, db)
        if (p%method%pair_kind() == PAIR_SEGMENTS) then
          call segment_data(p, p%a%segments, da)
          do m = 1, size(p%pairs, 2)
            do c = 1, 4
              call node_limit(p%a%segments(c, p%pairs(1, m)), p%b%segments(:, p%pairs(2, m)), &
                  db, p%pairs(2, m))
              call node_limit(p%b%segments(c, p%pairs(2, m)), p%a%segments(:, p%pairs(1, m)), &
                  da, p%pairs(1, m))
            end do
          end do
        else
          do m = 1, size(p%pairs, 2)
            call node_limit(p%pairs(1, m), p%b%segments(:, p%pairs(2, m)), db, p%pairs(2, m))
          end do
        end if
      end associate
    end do

  contains

    !> Outward unit normal, centre, mean velocity and recovery allowance of
    !> every segment of a local surface at x^n.
    subroutine segment_data(p, segments, d)
      type(interface_t), intent(in) :: p
      integer, intent(in) :: segments(:, :)
      type(segment_data_t), intent(out) :: d
      real(rk) :: corners(3, 4), area(3), size_
      integer :: s, n
      n = size(segments, 2)
      allocate(d%normal(3, n), d%centre(3, n), d%velocity(3, n), d%allowance(n))
      do s = 1, n
        corners = ct%x(:, segments(:, s))
        d%normal(:, s) = quad_unit_normal(corners)
        d%centre(:, s) = 0.25_rk * sum(corners, dim=2)
        d%velocity(:, s) = 0.25_rk * sum(ct%v(:, segments(:, s)), dim=2)
        area = 0.5_rk * cross(corners(:, 3) - corners(:, 1), corners(:, 4) - corners(:, 2))
        size_ = norm2(area)
        d%allowance(s) = recovery_allowance(p%spec%penetration_tolerance, size_, size_, 0.0_rk)
      end do
    end subroutine segment_data

    !> The limit of local node n against segment s (local corners seg).
    subroutine node_limit(n, seg, d, s)
      integer, intent(in) :: n, seg(4), s
      type(segment_data_t), intent(in) :: d
      real(rk) :: edge(3), corner(3), next(3), g, w, a, side
      integer :: j
      if (.not. limit > 0.0_rk) return
      ! Approach speed along the segment's outward normal (> 0: closing).
      w = -dot_product(ct%v(:, n) - d%velocity(:, s), d%normal(:, s))
      if (.not. w > 0.0_rk) return
      g = dot_product(ct%x(:, n) - d%centre(:, s), d%normal(:, s))
      if (g < 0.0_rk) return
      a = d%allowance(s)
      ! (Not limit * w: that overflows while limit is huge. And once this
      ! test is passed, 2 (g + a) / w < limit cannot overflow.)
      if (2.0_rk * (g + a) / limit >= w) return
      if (any(seg == n)) return
      ! The node's projection lies on the segment: left of every edge, the
      ! corners running counter-clockwise about the outward normal. A node
      ! above an edge counts for both segments (EDGE_SHARE of the edge's
      ! length: round-off must not leave it in neither).
      do j = 1, 4
        corner = ct%x(:, seg(j))
        next = ct%x(:, seg(modulo(j, 4) + 1))
        edge = next - corner
        side = dot_product(cross(edge, ct%x(:, n) - corner), d%normal(:, s))
        if (side < -EDGE_SHARE * dot_product(edge, edge)) return
      end do
      limit = 2.0_rk * (g + a) / w
    end subroutine node_limit

  end function impact_step_limit

end module contact_impact
