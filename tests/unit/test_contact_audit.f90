!> The penetration audit (contact_audit): the point-triangle kernel on hand
!> cases, then the signed distance of the audit against brute force on
!> closed surfaces (every triangle tried; inside from the winding number,
!> the sum of the triangles' solid angles over 4 pi), the free-boundary and
!> self-contact rules, a hemisphere ending on a symmetry plane against the
!> whole sphere, the sagitta estimate on a sphere, and the audit of a part of
!> a surface (what a rank holds on several ranks) against the whole.
program test_contact_audit
  use core_kinds, only: rk, ik, i8
  use check, only: check_true, check_close, check_summary
  use contact_surface, only: contact_surface_t, surface_from_segments
  use contact_audit, only: audit_gaps, segment_metrics, closest_on_triangle, FEATURE_FACE
  implicit none
  real(rk), parameter :: PI = acos(-1.0_rk)

  call kernel_cases()
  call closed_surface(.false.)
  call closed_surface(.true.)
  call mirrored_hemisphere()
  call open_plate()
  call self_sheets()
  call self_vfold()
  call sphere_sagitta()
  call near_part()
  call check_summary()

contains

  pure function cross(a, b) result(c)
    real(rk), intent(in) :: a(3), b(3)
    real(rk) :: c(3)
    c = [a(2) * b(3) - a(3) * b(2), a(3) * b(1) - a(1) * b(3), a(1) * b(2) - a(2) * b(1)]
  end function cross

  !> Hand cases on the triangle (0,0,0), (1,0,0), (0,1,0).
  subroutine kernel_cases()
    real(rk) :: a(3), b(3), c(3), q(3)
    integer :: f
    a = [0.0_rk, 0.0_rk, 0.0_rk]
    b = [1.0_rk, 0.0_rk, 0.0_rk]
    c = [0.0_rk, 1.0_rk, 0.0_rk]
    call closest_on_triangle([0.25_rk, 0.25_rk, -0.5_rk], a, b, c, q, f)
    call check_true('kernel: above the interior -> face', f == FEATURE_FACE .and. &
        all(abs(q - [0.25_rk, 0.25_rk, 0.0_rk]) < 1e-15_rk))
    call closest_on_triangle([-1.0_rk, -2.0_rk, 3.0_rk], a, b, c, q, f)
    call check_true('kernel: beyond vertex a -> vertex a (feature 4)', f == 4 .and. &
        all(q == a))
    call closest_on_triangle([2.0_rk, -0.1_rk, 0.0_rk], a, b, c, q, f)
    call check_true('kernel: beyond vertex b (feature 5)', f == 5 .and. all(q == b))
    call closest_on_triangle([0.5_rk, -1.0_rk, 0.3_rk], a, b, c, q, f)
    call check_true('kernel: beside edge ab (feature 1)', f == 1 .and. &
        all(abs(q - [0.5_rk, 0.0_rk, 0.0_rk]) < 1e-15_rk))
    call closest_on_triangle([1.0_rk, 1.0_rk, 0.0_rk], a, b, c, q, f)
    call check_true('kernel: beside edge bc (feature 2)', f == 2 .and. &
        all(abs(q - [0.5_rk, 0.5_rk, 0.0_rk]) < 1e-15_rk))
    call closest_on_triangle([-1.0_rk, 0.5_rk, 0.0_rk], a, b, c, q, f)
    call check_true('kernel: beside edge ca (feature 3)', f == 3 .and. &
        all(abs(q - [0.0_rk, 0.5_rk, 0.0_rk]) < 1e-15_rk))
    call closest_on_triangle([-0.1_rk, 3.0_rk, 0.0_rk], a, b, c, q, f)
    call check_true('kernel: beyond vertex c (feature 6)', f == 6 .and. all(q == c))
  end subroutine kernel_cases

  !> The surface of the unit cube [0,1]^3, n x n segments a face, outward
  !> order; optionally mapped onto the sphere of radius 0.5 about the centre.
  subroutine cube_surface(n, on_sphere, x, surf)
    integer, intent(in) :: n
    logical, intent(in) :: on_sphere
    real(rk), allocatable, intent(out) :: x(:, :)
    type(contact_surface_t), intent(out) :: surf
    integer(ik), allocatable :: seg(:, :), id(:, :, :)
    integer(i8), allocatable :: sid(:)
    integer :: i, j, k, face, ns, nnode, axis, side
    real(rk) :: c(3)
    ! Node ids on a (n+1)^3 lattice, only the boundary ones used.
    allocate(id(0:n, 0:n, 0:n), x(3, (n + 1)**3))
    nnode = 0
    do k = 0, n
      do j = 0, n
        do i = 0, n
          nnode = nnode + 1
          id(i, j, k) = int(nnode, ik)
          x(:, nnode) = [real(i, rk), real(j, rk), real(k, rk)] / real(n, rk)
          if (on_sphere) then
            c = x(:, nnode) - 0.5_rk
            if (norm2(c) > 0.0_rk) x(:, nnode) = 0.5_rk + 0.5_rk * c / norm2(c)
          end if
        end do
      end do
    end do
    allocate(seg(4, 6 * n * n), sid(6 * n * n))
    ns = 0
    do face = 1, 6
      axis = (face + 1) / 2
      side = mod(face + 1, 2) * n
      do j = 0, n - 1
        do i = 0, n - 1
          ns = ns + 1
          sid(ns) = int(ns, i8)
          select case (axis)
          case (1)
            seg(:, ns) = [id(side, i, j), id(side, i + 1, j), id(side, i + 1, j + 1), &
                id(side, i, j + 1)]
          case (2)
            seg(:, ns) = [id(j, side, i), id(j, side, i + 1), id(j + 1, side, i + 1), &
                id(j + 1, side, i)]
          case default
            seg(:, ns) = [id(i, j, side), id(i + 1, j, side), id(i + 1, j + 1, side), &
                id(i, j + 1, side)]
          end select
          ! Outward: the lattice order is counter-clockwise about +axis.
          if (side == 0) seg(:, ns) = seg([1, 4, 3, 2], ns)
        end do
      end do
    end do
    call surface_from_segments(seg, sid, x, surf)
  end subroutine cube_surface

  !> Brute force: (distance to the nearest triangle, winding number).
  subroutine brute(x, surf, p, dist, winding)
    real(rk), intent(in) :: x(:, :), p(3)
    type(contact_surface_t), intent(in) :: surf
    real(rk), intent(out) :: dist, winding
    real(rk) :: a(3), b(3), c(3), q(3), la, lb, lc, omega
    integer :: s, k, f
    dist = huge(1.0_rk)
    winding = 0.0_rk
    do s = 1, surf%nseg
      c = 0.25_rk * sum(x(:, surf%segments(:, s)), dim=2)
      do k = 1, 4
        a = x(:, surf%segments(k, s))
        b = x(:, surf%segments(mod(k, 4) + 1, s))
        call closest_on_triangle(p, a, b, c, q, f)
        dist = min(dist, norm2(p - q))
        ! Solid angle (Van Oosterom & Strackee, IEEE TBME 30 (1983) 125).
        la = norm2(a - p)
        lb = norm2(b - p)
        lc = norm2(c - p)
        omega = 2.0_rk * atan2(dot_product(a - p, cross(b - p, c - p)), la * lb * lc + &
            dot_product(a - p, b - p) * lc + dot_product(a - p, c - p) * lb + &
            dot_product(b - p, c - p) * la)
        winding = winding + omega / (4.0_rk * PI)
      end do
    end do
  end subroutine brute

  !> Points scattered about a closed surface (cube or sphere) audited as the
  !> nodes of a second surface: distance equal to brute force to round-off,
  !> inside exactly where the winding number is 1.
  subroutine closed_surface(on_sphere)
    logical, intent(in) :: on_sphere
    real(rk), allocatable :: x(:, :), xq(:, :), gap(:), inward(:, :)
    integer, allocatable :: hit(:)
    type(contact_surface_t) :: target, probes
    integer(ik), allocatable :: seg(:, :)
    integer(i8), allocatable :: sid(:)
    integer :: npt, i, nn, bad_sign, bad_dist, ninside
    real(rk) :: r(3), dist, winding, reach
    character(len=16) :: label
    label = 'cube'
    if (on_sphere) label = 'sphere'
    call cube_surface(6, on_sphere, x, target)
    nn = size(x, 2)
    ! Probe points: a deterministic scatter in [-0.2, 1.2]^3 near the surface.
    npt = 2000
    allocate(xq(3, nn + 4 * npt))
    xq(:, :nn) = x
    allocate(seg(4, npt), sid(npt))
    do i = 1, 4 * npt
      r = [frac(0.7548776662466927_rk * i), frac(0.5698402909980532_rk * i), &
          frac(0.3141592653589793_rk * i + 0.1_rk)]
      xq(:, nn + i) = -0.2_rk + 1.4_rk * r
    end do
    do i = 1, npt
      seg(:, i) = int(nn + [4 * i - 3, 4 * i - 2, 4 * i - 1, 4 * i], ik)
      sid(i) = int(i, i8)
    end do
    call surface_from_segments(seg, sid, xq, probes)
    allocate(gap(probes%nnode), hit(probes%nnode), inward(3, probes%nnode))
    reach = 0.5_rk
    call audit_gaps(xq, probes, target, .false., reach, [(.true., i = 1, probes%nnode)], &
        gap, hit, inward)
    bad_sign = 0
    bad_dist = 0
    ninside = 0
    do i = 1, probes%nnode
      call brute(xq, target, xq(:, probes%nodes(i)), dist, winding)
      if (dist >= reach) then
        if (gap(i) /= reach) bad_dist = bad_dist + 1
        cycle
      end if
      if (abs(abs(gap(i)) - dist) > 1.0e-14_rk) bad_dist = bad_dist + 1
      if (abs(winding) > 0.5_rk) ninside = ninside + 1
      ! Points within 1e-12 of the surface may take either sign.
      if (dist > 1.0e-12_rk .and. (gap(i) < 0.0_rk) .neqv. (abs(winding) > 0.5_rk)) &
          bad_sign = bad_sign + 1
    end do
    call check_true('audit '//trim(label)//': distance = brute force at every probe', &
        bad_dist == 0)
    call check_true('audit '//trim(label)//': inside = winding number at every probe', &
        bad_sign == 0)
    call check_true('audit '//trim(label)//': probes inside and outside', ninside > 100 &
        .and. ninside < probes%nnode - 100)
  end subroutine closed_surface

  !> The upper half (z >= 0.5) of the cubed sphere, which ends on the plane
  !> z = 0.5 (the lattice's middle row maps onto it), audited with that plane
  !> as a symmetry plane: for probes with z >= 0.5 the distance and the sign
  !> must be those of the whole sphere (its mirror image), by brute force.
  !> Without the plane the audit calls probes beside the rim outside (the
  !> free-boundary rule), so the same comparison must then find wrong signs:
  !> the case tests the mirroring.
  subroutine mirrored_hemisphere()
    real(rk), allocatable :: x(:, :), xq(:, :), gap(:), inward(:, :)
    integer, allocatable :: hit(:)
    type(contact_surface_t) :: whole, half, probes
    integer(ik), allocatable :: seg(:, :), hseg(:, :)
    integer(i8), allocatable :: sid(:), hid(:)
    integer :: npt, i, nn, s, nh, bad_sign(2), bad_dist(2), ninside, pass
    real(rk) :: r(3), dist, winding, reach, plane(4, 1)
    call cube_surface(6, .true., x, whole)
    ! A waist at the plane, mirror-symmetric about it: x and y scaled about
    ! the axis by 1 + |z - 0.5|, so the surface meets the plane at an angle
    ! (45 degrees for the equator's radius 0.5) and nodes on the plane near
    ! the rim have the rim as nearest feature, sideways of its facets.
    do i = 1, size(x, 2)
      x(1:2, i) = 0.5_rk + (x(1:2, i) - 0.5_rk) * (1.0_rk + abs(x(3, i) - 0.5_rk))
    end do
    allocate(hseg(4, whole%nseg), hid(whole%nseg))
    nh = 0
    do s = 1, whole%nseg
      if (any(x(3, whole%segments(:, s)) < 0.5_rk - 1.0e-12_rk)) cycle
      nh = nh + 1
      hseg(:, nh) = whole%segments(:, s)
      hid(nh) = int(nh, i8)
    end do
    call surface_from_segments(hseg(:, :nh), hid(:nh), x, half)
    nn = size(x, 2)
    npt = 2000
    allocate(xq(3, nn + 4 * npt), seg(4, npt), sid(npt))
    xq(:, :nn) = x
    do i = 1, 4 * npt
      r = [frac(0.7548776662466927_rk * i), frac(0.5698402909980532_rk * i), &
          frac(0.3141592653589793_rk * i + 0.1_rk)]
      ! Every other probe on the plane, as the nodes on a symmetry plane are.
      if (mod(i, 2) == 0) r(3) = 0.0_rk
      xq(:, nn + i) = [-0.2_rk + 1.4_rk * r(1), -0.2_rk + 1.4_rk * r(2), 0.5_rk + 0.7_rk * r(3)]
    end do
    do i = 1, npt
      seg(:, i) = int(nn + [4 * i - 3, 4 * i - 2, 4 * i - 1, 4 * i], ik)
      sid(i) = int(i, i8)
    end do
    call surface_from_segments(seg, sid, xq, probes)
    allocate(gap(probes%nnode), hit(probes%nnode), inward(3, probes%nnode))
    reach = 0.5_rk
    plane(:, 1) = [0.0_rk, 0.0_rk, 1.0_rk, 0.5_rk]
    bad_sign = 0
    bad_dist = 0
    ninside = 0
    do pass = 1, 2
      if (pass == 1) then
        call audit_gaps(xq, probes, half, .false., reach, [(.true., i = 1, probes%nnode)], &
            gap, hit, inward, plane)
      else
        call audit_gaps(xq, probes, half, .false., reach, [(.true., i = 1, probes%nnode)], &
            gap, hit, inward)
      end if
      do i = 1, probes%nnode
        call brute(xq, whole, xq(:, probes%nodes(i)), dist, winding)
        if (dist >= reach) cycle
        if (abs(abs(gap(i)) - dist) > 1.0e-14_rk) bad_dist(pass) = bad_dist(pass) + 1
        if (pass == 1 .and. abs(winding) > 0.5_rk) ninside = ninside + 1
        if (dist > 1.0e-12_rk .and. (gap(i) < 0.0_rk) .neqv. (abs(winding) > 0.5_rk)) &
            bad_sign(pass) = bad_sign(pass) + 1
      end do
    end do
    call check_true('hemisphere on a symmetry plane: distance = whole sphere''s', &
        bad_dist(1) == 0)
    call check_true('hemisphere on a symmetry plane: inside = whole sphere''s winding number', &
        bad_sign(1) == 0)
    call check_true('hemisphere on a symmetry plane: probes inside and outside', &
        ninside > 100 .and. ninside < probes%nnode - 100)
    call check_true('hemisphere without the plane: the rim''s probes get the wrong sign', &
        bad_sign(2) > 0)
  end subroutine mirrored_hemisphere

  pure real(rk) function frac(v)
    real(rk), intent(in) :: v
    frac = v - aint(v)
  end function frac

  !> An open plate z = 0 on [0,1]^2 (normal +z): a point below its interior
  !> is inside; one beside its free edge and below the plane is beside it.
  subroutine open_plate()
    real(rk) :: x(3, 9 + 8)
    integer(ik) :: seg(4, 4), pseg(4, 2)
    integer(i8) :: sid(4), psid(2)
    type(contact_surface_t) :: plate, probes
    real(rk) :: gap(8), inward(3, 8)
    integer :: hit(8), i, j, k
    k = 0
    do j = 0, 2
      do i = 0, 2
        k = k + 1
        x(:, k) = [0.5_rk * i, 0.5_rk * j, 0.0_rk]
      end do
    end do
    k = 0
    do j = 0, 1
      do i = 0, 1
        k = k + 1
        seg(:, k) = int([1 + i + 3 * j, 2 + i + 3 * j, 5 + i + 3 * j, 4 + i + 3 * j], ik)
        sid(k) = k
      end do
    end do
    call surface_from_segments(seg, sid, x, plate)
    ! Probes 10..17: below the interior (depth 0.03), below a free edge
    ! exactly (depth 0.03), beside the free edge below the plane, above.
    x(:, 10) = [0.3_rk, 0.4_rk, -0.03_rk]
    x(:, 11) = [0.0_rk, 0.4_rk, -0.03_rk]
    x(:, 12) = [-0.2_rk, 0.4_rk, -0.03_rk]
    x(:, 13) = [0.3_rk, 0.4_rk, 0.02_rk]
    x(:, 14) = [1.0_rk, 1.0_rk, -0.01_rk]
    x(:, 15) = [1.1_rk, 1.1_rk, -0.01_rk]
    x(:, 16) = [0.5_rk, 0.5_rk, -0.04_rk]
    x(:, 17) = [0.7_rk, 0.9_rk, 0.0_rk]
    pseg(:, 1) = int([10, 11, 12, 13], ik)
    pseg(:, 2) = int([14, 15, 16, 17], ik)
    psid = [1_i8, 2_i8]
    call surface_from_segments(pseg, psid, x, probes)
    call audit_gaps(x, probes, plate, .false., 0.5_rk, [(.true., i = 1, 8)], gap, hit, inward)
    call check_close('plate: below the interior, depth', gap(1), -0.03_rk, 1e-14_rk)
    call check_close('plate: below the free edge, depth', gap(2), -0.03_rk, 1e-14_rk)
    call check_true('plate: beside the free edge is outside', gap(3) > 0.0_rk)
    call check_close('plate: above, gap', gap(4), 0.02_rk, 1e-14_rk)
    call check_close('plate: below the free corner, depth', gap(5), -0.01_rk, 1e-14_rk)
    call check_true('plate: beyond the free corner is outside', gap(6) > 0.0_rk)
    call check_close('plate: below an interior node, depth', gap(7), -0.04_rk, 1e-14_rk)
    call check_true('plate: on the surface, gap 0', abs(gap(8)) < 1e-15_rk)
    call check_true('plate: inward direction of a penetrator is +z', &
        all(abs(inward(:, 1) - [0.0_rk, 0.0_rk, 1.0_rk]) < 1e-14_rk))
  end subroutine open_plate

  !> Self-contact: one surface of two sheets facing each other, the upper
  !> one (normal -z) 0.05 below the lower one (normal +z): every node of
  !> each is 0.05 inside the other's body. A single curved sheet (a half
  !> cylinder) has no node inside itself.
  subroutine self_sheets()
    integer, parameter :: n = 4
    real(rk) :: x(3, 2 * (n + 1)**2), gap(2 * (n + 1)**2), inward(3, 2 * (n + 1)**2)
    real(rk) :: xc(3, (n + 1) * 9), gc((n + 1) * 9), ic(3, (n + 1) * 9), th
    integer(ik) :: seg(4, 2 * n * n), segc(4, n * 8)
    integer(i8) :: sid(2 * n * n), sidc(n * 8)
    integer :: hit(2 * (n + 1)**2), hitc((n + 1) * 9), i, j, k, s, off
    type(contact_surface_t) :: sheets, tube
    do k = 0, 1
      do j = 0, n
        do i = 0, n
          x(:, 1 + i + (n + 1) * j + k * (n + 1)**2) = [real(i, rk), real(j, rk), &
              -0.05_rk * k * n] / real(n, rk)
        end do
      end do
    end do
    s = 0
    do k = 0, 1
      off = k * (n + 1)**2
      do j = 0, n - 1
        do i = 0, n - 1
          s = s + 1
          sid(s) = s
          seg(:, s) = int(off + [1 + i + (n + 1) * j, 2 + i + (n + 1) * j, &
              2 + i + (n + 1) * (j + 1), 1 + i + (n + 1) * (j + 1)], ik)
          if (k == 1) seg(:, s) = seg([1, 4, 3, 2], s)
        end do
      end do
    end do
    call surface_from_segments(seg, sid, x, sheets)
    call audit_gaps(x, sheets, sheets, .true., 0.5_rk, [(.true., i = 1, sheets%nnode)], gap, &
        hit, inward)
    call check_true('self: every node of two facing sheets 0.05 inside', &
        all(abs(gap(:sheets%nnode) + 0.05_rk) < 1e-14_rk))
    ! Half cylinder of radius 0.5 about the x axis, 8 segments around.
    do j = 0, 8
      th = PI * j / 8.0_rk
      do i = 0, n
        xc(:, 1 + i + (n + 1) * j) = [real(i, rk) / n, 0.5_rk * cos(th), 0.5_rk * sin(th)]
      end do
    end do
    s = 0
    do j = 0, 7
      do i = 0, n - 1
        s = s + 1
        sidc(s) = s
        segc(:, s) = int([1 + i + (n + 1) * j, 1 + i + (n + 1) * (j + 1), &
            2 + i + (n + 1) * (j + 1), 2 + i + (n + 1) * j], ik)
      end do
    end do
    call surface_from_segments(segc, sidc, xc, tube)
    call audit_gaps(xc, tube, tube, .true., 2.0_rk, [(.true., i = 1, tube%nnode)], gc, hitc, ic)
    call check_true('self: a half cylinder has no node inside itself', &
        all(gc(:tube%nnode) >= 0.0_rk))
  end subroutine self_sheets

  !> Self-contact at a fold closed to a V (the folding tube's apex): one
  !> strip whose profile runs out along one flank and back along the other,
  !> 35 degrees apart, nodes bunched at the apex (0.012 from it) as a tight
  !> fold's are, normals into the V: nothing is inside anything. With the
  !> second flank turned 7.5 degrees past the first (crossing it), its nodes
  !> beyond the crossing are inside. The tube's measured apex profile: its
  !> apex node lies beyond the rim of the rings excluded around it and
  !> 3e-3 behind the plane of the flank's third segment, beside it, not
  !> behind it; the audit reported it 2.6e-2 inside before the rim rule
  !> (this check fails without it).
  subroutine self_vfold()
    integer, parameter :: nx = 4, np = 11
    real(rk), parameter :: along(0:5) = [0.0_rk, 0.012_rk, 0.04_rk, 0.09_rk, 0.15_rk, 0.21_rk]
    real(rk) :: x(3, (nx + 1) * np), gap((nx + 1) * np), inward(3, (nx + 1) * np)
    real(rk) :: ta, tb, dir(3)
    integer(ik) :: seg(4, nx * (np - 1))
    integer(i8) :: sid(nx * (np - 1))
    integer :: hit((nx + 1) * np), i, j, s, pass, node
    logical :: ok_open, ok_cross, ok_apex
    !> The folding tube's outer surface through the apex of its upper fold
    !> at t = 96 us (DAM), radial and axial offsets from the apex node of
    !> the 11 nodes of one generatrix (problems/tube_fold).
    real(rk), parameter :: apex_profile(2, np) = reshape([0.13093_rk, -0.07457_rk, &
        0.07601_rk, -0.04922_rk, 0.04458_rk, -0.02807_rk, 0.02265_rk, -0.01243_rk, &
        0.00867_rk, -0.00262_rk, 0.0_rk, 0.0_rk, 0.00924_rk, -0.00263_rk, &
        0.03015_rk, -0.00778_rk, 0.05283_rk, -0.00818_rk, 0.08739_rk, -0.00390_rk, &
        0.12920_rk, -0.00464_rk], [2, np])
    type(contact_surface_t) :: v
    ok_open = .true.
    ok_cross = .true.
    ok_apex = .true.
    do pass = 1, 3
      ta = -17.5_rk * PI / 180.0_rk
      tb = 17.5_rk * PI / 180.0_rk
      if (pass == 2) tb = -25.0_rk * PI / 180.0_rk
      do j = 1, np
        ! Profile node j: flank a's far end (j = 1) to the apex (j = 6) to
        ! flank b's far end (j = 11).
        if (pass == 3) then
          dir = [0.0_rk, apex_profile(1, j), apex_profile(2, j)]
        else if (j <= 6) then
          dir = [0.0_rk, cos(ta), sin(ta)] * along(6 - j)
        else
          dir = [0.0_rk, cos(tb), sin(tb)] * along(j - 6)
        end if
        do i = 0, nx
          x(:, 1 + i + (nx + 1) * (j - 1)) = dir + [0.1_rk * i, 0.0_rk, 0.0_rk]
        end do
      end do
      s = 0
      do j = 1, np - 1
        do i = 0, nx - 1
          s = s + 1
          sid(s) = s
          seg(:, s) = int([1 + i + (nx + 1) * (j - 1), 1 + i + (nx + 1) * j, &
              2 + i + (nx + 1) * j, 2 + i + (nx + 1) * (j - 1)], ik)
        end do
      end do
      call surface_from_segments(seg, sid, x, v)
      call audit_gaps(x, v, v, .true., 0.5_rk, [(.true., i = 1, v%nnode)], gap, hit, inward)
      do node = 1, v%nnode
        j = (int(v%nodes(node)) - 1) / (nx + 1) + 1
        if (pass == 1 .and. gap(node) < 0.0_rk) ok_open = .false.
        if (pass == 3 .and. gap(node) < 0.0_rk) ok_apex = .false.
        ! Flank b's nodes 0.15 and 0.21 from the apex are behind flank a
        ! (sin 7.5 deg x 0.15 = 0.02 deep), well away from its rim.
        if (pass == 2 .and. j >= 10 .and. .not. gap(node) < 0.0_rk) ok_cross = .false.
      end do
    end do
    call check_true('self: a fold closed to a V has no node inside itself', ok_open)
    call check_true('self: a flank turned past the other is inside it beyond the crossing', &
        ok_cross)
    call check_true('self: the folding tube''s closed fold has no node inside itself', ok_apex)
  end subroutine self_vfold

  !> Sagitta on the sphere of radius 0.5: against the true bulge of the
  !> sphere over each segment's centre, R - |C - centre|. The estimate is
  !> exact for a uniform mesh of a sphere; the cubed sphere's segments differ
  !> in shape (edge ratio up to sqrt 2 and skewed diagonals), which bounds
  !> the ratio within [1/2, 2].
  subroutine sphere_sagitta()
    real(rk), allocatable :: x(:, :), sz(:), sag(:), tn(:, :, :), tc(:, :)
    type(contact_surface_t) :: surf
    real(rk) :: ratio_lo, ratio_hi, bulge
    integer :: s
    call cube_surface(8, .true., x, surf)
    allocate(sz(surf%nseg), sag(surf%nseg), tn(3, 4, surf%nseg), tc(3, surf%nseg))
    call segment_metrics(x, surf, sz, sag, tc, tn)
    ratio_lo = huge(1.0_rk)
    ratio_hi = 0.0_rk
    do s = 1, surf%nseg
      bulge = 0.5_rk - norm2(tc(:, s) - 0.5_rk)
      ratio_lo = min(ratio_lo, sag(s) / bulge)
      ratio_hi = max(ratio_hi, sag(s) / bulge)
    end do
    write(*, '(a,2f8.4)') '  sagitta / true bulge, min and max: ', ratio_lo, ratio_hi
    call check_true('sagitta within [1/2, 2] of the sphere''s bulge', &
        ratio_lo >= 0.5_rk .and. ratio_hi <= 2.0_rk)
  end subroutine sphere_sagitta

  !> The audit of some nodes against the part of the target near them (the
  !> segments whose corners all lie within the reach and two segment spans
  !> of the nodes' box) on the whole target's grid box, as contact_monitor
  !> audits on several ranks, against the audit on the whole target: the
  !> same gaps, inward directions and closest segments, bit for bit. The
  !> probes sit above the cube's lattice nodes along the faces' normals, so
  !> the closest point is a lattice node shared by several segments, and
  !> which of them is reported (the first visited of exactly equal
  !> distances) depends on the order of the candidates: a part that visited
  !> them in another order than the whole surface would report another.
  subroutine near_part()
    real(rk), allocatable :: x(:, :), xq(:, :), gap(:), inward(:, :), gap_p(:), inward_p(:, :)
    integer, allocatable :: hit(:), hit_p(:), list(:)
    logical, allocatable :: sel(:)
    type(contact_surface_t) :: target, probes, part
    integer(ik), allocatable :: seg(:, :)
    integer(i8), allocatable :: sid(:)
    real(rk) :: box(3, 2), lo(3), hi(3), reach, span, h, n(3)
    integer :: nn, i, k, m, s, nsel, ties, bad
    call cube_surface(8, .false., x, target)
    nn = size(x, 2)
    ! One probe segment per target segment: its corners lifted off the face
    ! by 0.05 (outside) or -0.05 (inside, every second segment).
    allocate(xq(3, nn + 4 * target%nseg), seg(4, target%nseg), sid(target%nseg))
    xq(:, :nn) = x
    do s = 1, target%nseg
      n = cross(x(:, target%segments(2, s)) - x(:, target%segments(1, s)), &
          x(:, target%segments(4, s)) - x(:, target%segments(1, s)))
      n = n / norm2(n)
      if (mod(s, 2) == 0) n = -n
      do k = 1, 4
        xq(:, nn + 4 * (s - 1) + k) = x(:, target%segments(k, s)) + 0.05_rk * n
      end do
      seg(:, s) = int(nn + [4 * s - 3, 4 * s - 2, 4 * s - 1, 4 * s], ik)
      sid(s) = int(s, i8)
    end do
    call surface_from_segments(seg, sid, xq, probes)
    reach = 0.15_rk
    allocate(gap(probes%nnode), hit(probes%nnode), inward(3, probes%nnode))
    allocate(gap_p(probes%nnode), hit_p(probes%nnode), inward_p(3, probes%nnode))
    sel = [(xq(1, probes%nodes(i)) < 0.2_rk, i = 1, probes%nnode)]
    nsel = count(sel)
    call audit_gaps(xq, probes, target, .false., reach, sel, gap, hit, inward)
    ! The part: the box of the selected probes widened by the reach and two
    ! spans (the longest distance between two corners of a segment).
    span = 0.0_rk
    do s = 1, target%nseg
      do k = 1, 4
        do m = 1, k - 1
          span = max(span, norm2(x(:, target%segments(k, s)) - x(:, target%segments(m, s))))
        end do
      end do
    end do
    h = reach + 2.0_rk * span
    lo = huge(1.0_rk)
    hi = -huge(1.0_rk)
    do i = 1, probes%nnode
      if (.not. sel(i)) cycle
      lo = min(lo, xq(:, probes%nodes(i)) - h)
      hi = max(hi, xq(:, probes%nodes(i)) + h)
    end do
    list = pack([(s, s = 1, target%nseg)], [(all(x(:, target%segments(1, s)) >= lo .and. &
        x(:, target%segments(1, s)) <= hi) .and. all(x(:, target%segments(2, s)) >= lo .and. &
        x(:, target%segments(2, s)) <= hi) .and. all(x(:, target%segments(3, s)) >= lo .and. &
        x(:, target%segments(3, s)) <= hi) .and. all(x(:, target%segments(4, s)) >= lo .and. &
        x(:, target%segments(4, s)) <= hi), s = 1, target%nseg)])
    call surface_from_segments(target%segments(:, list), target%segment_id(list), x, part)
    box(:, 1) = minval(x, dim=2)
    box(:, 2) = maxval(x, dim=2)
    call audit_gaps(xq, probes, part, .false., reach, sel, gap_p, hit_p, inward_p, &
        grid_box=box)
    bad = 0
    ties = 0
    do i = 1, probes%nnode
      if (.not. sel(i)) cycle
      if (hit(i) > 0) then
        ! A tie: the closest point is a corner of the closest segment (the
        ! audit's own distance to it: q = that corner), a lattice node that
        ! several segments share.
        if (any([(sqrt(sum((xq(:, probes%nodes(i)) - x(:, target%segments(k, hit(i))))**2)) &
            == abs(gap(i)), k = 1, 4)])) ties = ties + 1
      end if
      if (hit_p(i) > 0) hit_p(i) = list(hit_p(i))
      if (gap_p(i) /= gap(i) .or. hit_p(i) /= hit(i) .or. any(inward_p(:, i) /= inward(:, i))) &
          bad = bad + 1
    end do
    call check_true('audit near part: some probes audited, on part of the target, with ties', &
        nsel > 20 .and. size(list) < target%nseg .and. ties > 10)
    call check_true('audit near part: gaps, directions and closest segments those of the '// &
        'whole target, bit for bit', bad == 0)
  end subroutine near_part

end program test_contact_audit
