!> RBF put-back-on weights (thin plate spline + linear polynomial in the tangent plane):
!> constant and linear reproduction in rotated, translated and scaled planes, unit weights
!> at a node, weights summing to 1, nodes perturbed off the plane, degenerate node sets
!> (collinear, coincident, k < 3, zero normal) with their fallback, the k = 3 case
!> against barycentric coordinates, node-order and scale invariance, and the measured
!> order of convergence on a 3 x 3 patch.
program test_contact_rbf
  use, intrinsic :: iso_fortran_env, only: output_unit
  use core_kinds, only: rk
  use contact_rbf, only: rbf_weights
  use check, only: check_true, check_close, check_summary
  implicit none
  real(rk), parameter :: eps = epsilon(1.0_rk)
  !> Node counts of the patterns.
  integer, parameter :: COUNTS(4) = [4, 5, 8, 9]
  !> Plane scales: spacing of the node pattern.
  real(rk), parameter :: SCALES(3) = [1.0e-3_rk, 1.0_rk, 1.0e3_rk]

  call set_seed()
  call test_constant()
  call test_linear()
  call test_sum()
  call test_off_plane()
  call test_degenerate()
  call test_triangle()
  call test_invariance()
  call test_convergence()
  call check_summary()

contains

  subroutine set_seed()
    integer :: seed_size
    integer, allocatable :: seed(:)
    call random_seed(size=seed_size)
    allocate(seed(seed_size))
    seed = 161803
    call random_seed(put=seed)
  end subroutine set_seed

  !> Orthonormal frame (e1, e2, n) as the columns of a rotation by Euler angles z-x-z.
  function frame(alpha, beta, gamma) result(r)
    real(rk), intent(in) :: alpha, beta, gamma
    real(rk) :: r(3, 3), inner(3, 3)
    real(rk) :: first(3, 3), second(3, 3), third(3, 3)
    first = rot(3, alpha)
    second = rot(1, beta)
    third = rot(3, gamma)
    inner = matmul(second, third)
    r = matmul(first, inner)
  end function frame

  function rot(axis, angle) result(r)
    integer, intent(in) :: axis
    real(rk), intent(in) :: angle
    real(rk) :: r(3, 3)
    integer :: i, j
    i = mod(axis, 3) + 1
    j = mod(axis + 1, 3) + 1
    r = 0.0_rk
    r(axis, axis) = 1.0_rk
    r(i, i) = cos(angle)
    r(j, j) = cos(angle)
    r(j, i) = sin(angle)
    r(i, j) = -sin(angle)
  end function rot

  !> Irregular node patterns of unit spacing in plane coordinates (2, k): a quadrilateral
  !> (4), plus an inner node (5), a jittered 3 x 3 grid without (8) or with (9) its centre.
  function pattern(k) result(uv)
    integer, intent(in) :: k
    real(rk) :: uv(2, k)
    real(rk) :: grid(2, 9)
    integer :: i, j, m
    select case (k)
    case (4, 5)
      uv(:, 1:4) = reshape([0.0_rk, 0.0_rk, 1.0_rk, 0.1_rk, 1.1_rk, 0.9_rk, -0.1_rk, 1.0_rk], &
          [2, 4])
      if (k == 5) uv(:, 5) = [0.45_rk, 0.55_rk]
    case default
      m = 0
      do j = -1, 1
        do i = -1, 1
          m = m + 1
          grid(:, m) = [real(i, rk) + 0.12_rk * sin(1.7_rk * m), &
              real(j, rk) + 0.11_rk * cos(2.3_rk * m)]
        end do
      end do
      if (k == 9) then
        uv = grid
      else
        uv = grid(:, [1, 2, 3, 4, 6, 7, 8, 9])
      end if
    end select
  end function pattern

  !> 3D positions origin + scale (u e1 + v e2).
  function place(origin, scale, r, uv) result(x)
    real(rk), intent(in) :: origin(3), scale, r(3, 3), uv(:, :)
    real(rk) :: x(3, size(uv, 2))
    integer :: j
    do j = 1, size(uv, 2)
      x(:, j) = origin + scale * (uv(1, j) * r(:, 1) + uv(2, j) * r(:, 2))
    end do
  end function place

  !> One 3D position origin + scale (u e1 + v e2).
  function at(origin, scale, r, uv) result(x)
    real(rk), intent(in) :: origin(3), scale, r(3, 3), uv(2)
    real(rk) :: x(3)
    x = origin + scale * (uv(1) * r(:, 1) + uv(2) * r(:, 2))
  end function at

  !> A point of the pattern's bounding box enlarged by `margin` (plane coordinates).
  function random_point(uv, margin) result(p)
    real(rk), intent(in) :: uv(:, :), margin
    real(rk) :: p(2), r(2)
    call random_number(r)
    p = minval(uv, dim=2) - margin &
        + r * (maxval(uv, dim=2) - minval(uv, dim=2) + 2.0_rk * margin)
  end function random_point

  !> Constant fields are reproduced for 4, 5, 8, 9 nodes in planes of spacing 1e-3, 1, 1e3.
  subroutine test_constant()
    real(rk), parameter :: c = -3.7_rk
    real(rk) :: r(3, 3), origin(3), p(3), worst
    integer :: ik, is, trial, k
    logical :: ok, all_ok
    character(len=100) :: name

    r = frame(0.7_rk, 1.1_rk, -0.4_rk)
    do is = 1, size(SCALES)
      origin = SCALES(is) * [3.1_rk, -2.4_rk, 5.7_rk]
      do ik = 1, size(COUNTS)
        k = COUNTS(ik)
        worst = 0.0_rk
        all_ok = .true.
        block
          real(rk) :: uv(2, k), x(3, k), w(k)
          uv = pattern(k)
          x = place(origin, SCALES(is), r, uv)
          do trial = 1, 20
            p = at(origin, SCALES(is), r, random_point(uv, 0.0_rk))
            call rbf_weights(x, p, r(:, 3), w, ok)
            all_ok = all_ok .and. ok
            worst = max(worst, abs(sum(w * c) - c) / abs(c))
          end do
        end block
        write(name, '(a,i0,a,es7.0)') 'constant field: k = ', k, ', spacing ', SCALES(is)
        call check_true(trim(name)//': ok', all_ok)
        call check_close(trim(name)//': max rel error', worst, 0.0_rk, 0.0_rk, atol=1.0e-13_rk)
      end do
    end do
  end subroutine test_constant

  !> Linear fields a + b . x are reproduced at random points inside the patch and at the
  !> nodes, where the weights are the unit vector.
  subroutine test_linear()
    real(rk), parameter :: a = 0.83_rk, b(3) = [1.3_rk, -0.6_rk, 2.2_rk]
    real(rk) :: r(3, 3), origin(3), p(3), worst, worst_node, worst_unit, fref
    integer :: ik, is, trial, k, j
    logical :: ok, all_ok
    character(len=100) :: name

    r = frame(-1.9_rk, 0.45_rk, 2.6_rk)
    do is = 1, size(SCALES), 2
      origin = SCALES(is) * [-7.0_rk, 0.3_rk, 2.9_rk]
      do ik = 1, size(COUNTS)
        k = COUNTS(ik)
        worst = 0.0_rk
        worst_node = 0.0_rk
        worst_unit = 0.0_rk
        all_ok = .true.
        block
          real(rk) :: uv(2, k), x(3, k), w(k), f(k)
          uv = pattern(k)
          x = place(origin, SCALES(is), r, uv)
          f = a + matmul(b / SCALES(is), x)
          fref = maxval(abs(f))
          do trial = 1, 20
            p = at(origin, SCALES(is), r, random_point(uv, 0.0_rk))
            call rbf_weights(x, p, r(:, 3), w, ok)
            all_ok = all_ok .and. ok
            worst = max(worst, abs(sum(w * f) - (a + dot_product(b / SCALES(is), p))) / fref)
          end do
          do j = 1, k
            call rbf_weights(x, x(:, j), r(:, 3), w, ok)
            all_ok = all_ok .and. ok
            worst_node = max(worst_node, abs(sum(w * f) - f(j)) / fref)
            w(j) = w(j) - 1.0_rk
            worst_unit = max(worst_unit, maxval(abs(w)))
          end do
        end block
        write(name, '(a,i0,a,es7.0)') 'linear field: k = ', k, ', spacing ', SCALES(is)
        call check_true(trim(name)//': ok', all_ok)
        call check_close(trim(name)//': inside, max rel error', worst, 0.0_rk, 0.0_rk, &
            atol=1.0e-12_rk)
        call check_close(trim(name)//': at nodes, max rel error', worst_node, 0.0_rk, &
            0.0_rk, atol=1.0e-12_rk)
        call check_close(trim(name)//': at nodes, max |w - e_j|', worst_unit, 0.0_rk, &
            0.0_rk, atol=1.0e-13_rk)
      end do
    end do
  end subroutine test_linear

  !> Weights sum to 1 at random points inside and around (up to one spacing outside) the
  !> patch, in random planes.
  subroutine test_sum()
    real(rk) :: r(3, 3), angles(3), origin(3), p(3), worst, scale
    integer :: ik, trial, k
    logical :: ok, all_ok

    worst = 0.0_rk
    all_ok = .true.
    do ik = 1, size(COUNTS)
      k = COUNTS(ik)
      block
        real(rk) :: uv(2, k), x(3, k), w(k)
        uv = pattern(k)
        do trial = 1, 200
          call random_number(angles)
          call random_number(origin)
          r = frame(6.3_rk * angles(1), 3.2_rk * angles(2), 6.3_rk * angles(3))
          scale = 10.0_rk**(6 * origin(1) - 3)
          origin = scale * 10 * (origin - 0.5_rk)
          x = place(origin, scale, r, uv)
          p = at(origin, scale, r, random_point(uv, 1.0_rk))
          call rbf_weights(x, p, r(:, 3), w, ok)
          all_ok = all_ok .and. ok
          worst = max(worst, abs(sum(w) - 1.0_rk))
        end do
      end block
    end do
    call check_true('sum: 800 random planes and points (inside and outside): ok', all_ok)
    call check_close('sum: max |sum w - 1|', worst, 0.0_rk, 0.0_rk, atol=1.0e-13_rk)
  end subroutine test_sum

  !> Nodes and point moved off the plane by up to 1e-3 of the spacing: in-plane linear
  !> fields are still reproduced and the weights are those of the planar nodes.
  subroutine test_off_plane()
    real(rk), parameter :: a = -1.4_rk
    real(rk) :: r(3, 3), origin(3), p(3), p0(3), b(3), worst, worst_w, fref, scale, hp
    integer :: ik, trial, k
    logical :: ok, ok0, all_ok

    r = frame(2.2_rk, -0.8_rk, 0.3_rk)
    scale = 0.05_rk
    origin = [1.0_rk, 2.0_rk, -0.5_rk]
    b = (0.7_rk * r(:, 1) - 1.9_rk * r(:, 2)) / scale
    worst = 0.0_rk
    worst_w = 0.0_rk
    all_ok = .true.
    do ik = 1, size(COUNTS)
      k = COUNTS(ik)
      block
        real(rk) :: uv(2, k), x(3, k), x0(3, k), w(k), w0(k), f(k), h(k)
        uv = pattern(k)
        x0 = place(origin, scale, r, uv)
        call random_number(h)
        h = 1.0e-3_rk * scale * (2 * h - 1)
        x = x0 + spread(r(:, 3), 2, k) * spread(h, 1, 3)
        f = a + matmul(b, x)
        fref = maxval(abs(f))
        do trial = 1, 20
          p0 = at(origin, scale, r, random_point(uv, 0.0_rk))
          call random_number(hp)
          p = p0 + 1.0e-3_rk * scale * (2 * hp - 1) * r(:, 3)
          call rbf_weights(x, p, r(:, 3), w, ok)
          call rbf_weights(x0, p0, r(:, 3), w0, ok0)
          all_ok = all_ok .and. ok .and. ok0
          worst = max(worst, abs(sum(w * f) - (a + dot_product(b, p))) / fref)
          worst_w = max(worst_w, maxval(abs(w - w0)))
        end do
      end block
    end do
    call check_true('off-plane nodes (1e-3 spacing): ok', all_ok)
    call check_close('off-plane nodes: in-plane linear field, max rel error', worst, 0.0_rk, &
        0.0_rk, atol=1.0e-12_rk)
    call check_close('off-plane nodes: max |w - w(planar nodes)|', worst_w, 0.0_rk, 0.0_rk, &
        atol=1.0e-13_rk)
  end subroutine test_off_plane

  !> Collinear (in space, or only after projection), coincident, too few nodes and a zero
  !> normal give ok = .false. and nonnegative fallback weights summing to 1; a thin but
  !> not collinear patch is accepted.
  subroutine test_degenerate()
    real(rk) :: r(3, 3), origin(3), x(3, 5), x3(3, 9), p(3), w(5), w9(9), w2(2)
    real(rk) :: uv(2, 5), uv9(2, 9)
    logical :: ok
    integer :: j

    r = frame(0.3_rk, 1.3_rk, 2.1_rk)
    origin = [0.5_rk, -1.5_rk, 2.0_rk]
    do j = 1, 5
      uv(:, j) = [0.3_rk * j - 0.2_rk * j**2 / 5, 0.5_rk * (0.3_rk * j - 0.2_rk * j**2 / 5)]
    end do
    x = place(origin, 2.0_rk, r, uv)
    p = origin + 0.7_rk * r(:, 1) - 0.4_rk * r(:, 2)
    call rbf_weights(x, p, r(:, 3), w, ok)
    call check_true('collinear nodes: ok = .false.', .not. ok)
    call check_close('collinear nodes: sum w', sum(w), 1.0_rk, 4 * eps)
    call check_true('collinear nodes: w >= 0', all(w >= 0))
    call check_true('collinear nodes: nearest node has the largest weight', &
        maxloc(w, dim=1) == minloc(sum((x - spread(p, 2, 5))**2, dim=1), dim=1))

    call rbf_weights(x, x(:, 3), r(:, 3), w, ok)
    call check_true('collinear nodes, point at node 3: ok = .false., w = e_3', &
        (.not. ok) .and. maxval(abs(w - [0.0_rk, 0.0_rk, 1.0_rk, 0.0_rk, 0.0_rk])) <= eps)

    ! Spread in the plane (e1, n): collinear only after projection along n.
    do j = 1, 5
      x(:, j) = origin + 0.1_rk * j * r(:, 1) + 0.3_rk * sin(real(j, rk)) * r(:, 3)
    end do
    call rbf_weights(x, p, r(:, 3), w, ok)
    call check_true('nodes collinear after projection: ok = .false.', .not. ok)
    call check_close('nodes collinear after projection: sum w', sum(w), 1.0_rk, 4 * eps)

    ! Two nodes of a 3 x 3 patch projecting onto the same point.
    uv9 = pattern(9)
    x3 = place(origin, 1.0_rk, r, uv9)
    x3(:, 7) = x3(:, 2) + 0.01_rk * r(:, 3)
    p = at(origin, 1.0_rk, r, [0.2_rk, 0.1_rk])
    call rbf_weights(x3, p, r(:, 3), w9, ok)
    call check_true('coincident nodes: ok = .false.', .not. ok)
    call check_close('coincident nodes: sum w', sum(w9), 1.0_rk, 4 * eps)
    call check_true('coincident nodes: w >= 0', all(w9 >= 0))

    ! A patch 1e-3 as wide as long is not collinear: linear reproduction holds.
    uv = pattern(5)
    uv(2, :) = 1.0e-3_rk * uv(2, :)
    x = place(origin, 1.0_rk, r, uv)
    p = at(origin, 1.0_rk, r, [0.4_rk, 0.3e-3_rk])
    call rbf_weights(x, p, r(:, 3), w, ok)
    call check_true('thin patch (width/length 1e-3): ok', ok)
    call check_close('thin patch: sum w', sum(w), 1.0_rk, 0.0_rk, atol=1.0e-13_rk)
    call check_close('thin patch: linear reproduction (coordinate along e1)', &
        dot_product(w, matmul(r(:, 1), x - spread(origin, 2, 5))), 0.4_rk, 1.0e-12_rk)

    call rbf_weights(x(:, 1:2), p, r(:, 3), w2, ok)
    call check_true('k = 2: ok = .false., sum w = 1', (.not. ok) .and. &
        abs(sum(w2) - 1.0_rk) <= 4 * eps)

    uv = pattern(5)
    x = place(origin, 1.0_rk, r, uv)
    call rbf_weights(x, p, [0.0_rk, 0.0_rk, 0.0_rk], w, ok)
    call check_true('zero normal: ok = .false., sum w = 1, w >= 0', (.not. ok) .and. &
        abs(sum(w) - 1.0_rk) <= 4 * eps .and. all(w >= 0))

    x = spread(origin, 2, 5)
    call rbf_weights(x, p, r(:, 3), w, ok)
    call check_true('all nodes at one point: ok = .false., w = 1/k', (.not. ok) .and. &
        all(abs(w - 0.2_rk) <= eps))
  end subroutine test_degenerate

  !> Three nodes: the spline part vanishes and the weights are barycentric coordinates.
  subroutine test_triangle()
    real(rk) :: r(3, 3), x(3, 3), p(3), w(3), bary(3), uv(2, 3), pu(2), det
    logical :: ok

    r = frame(1.0_rk, 2.0_rk, 3.0_rk)
    uv = reshape([0.0_rk, 0.0_rk, 2.0_rk, 0.3_rk, 0.4_rk, 1.7_rk], [2, 3])
    pu = [0.9_rk, 0.6_rk]
    x = place([0.1_rk, 0.2_rk, 0.3_rk], 1.0_rk, r, uv)
    p = at([0.1_rk, 0.2_rk, 0.3_rk], 1.0_rk, r, pu)
    det = (uv(1, 2) - uv(1, 1)) * (uv(2, 3) - uv(2, 1)) &
        - (uv(1, 3) - uv(1, 1)) * (uv(2, 2) - uv(2, 1))
    bary(2) = ((pu(1) - uv(1, 1)) * (uv(2, 3) - uv(2, 1)) &
        - (uv(1, 3) - uv(1, 1)) * (pu(2) - uv(2, 1))) / det
    bary(3) = ((uv(1, 2) - uv(1, 1)) * (pu(2) - uv(2, 1)) &
        - (pu(1) - uv(1, 1)) * (uv(2, 2) - uv(2, 1))) / det
    bary(1) = 1.0_rk - bary(2) - bary(3)
    call rbf_weights(x, p, r(:, 3), w, ok)
    call check_true('k = 3: ok', ok)
    call check_close('k = 3: weights = barycentric coordinates (max diff)', &
        maxval(abs(w - bary)), 0.0_rk, 0.0_rk, atol=1.0e-14_rk)
  end subroutine test_triangle

  !> Reversing the node order reverses the weights, and scaling the whole configuration
  !> by 1e6 leaves them unchanged, both to round-off.
  subroutine test_invariance()
    real(rk) :: r(3, 3), origin(3), x(3, 9), p(3), w(9), wr(9), ws(9), uv(2, 9)
    logical :: ok1, ok2, ok3

    r = frame(-0.3_rk, 0.9_rk, 1.4_rk)
    origin = [2.0_rk, 1.0_rk, -3.0_rk]
    uv = pattern(9)
    x = place(origin, 0.1_rk, r, uv)
    p = at(origin, 0.1_rk, r, [0.37_rk, -0.52_rk])
    call rbf_weights(x, p, r(:, 3), w, ok1)
    call rbf_weights(x(:, 9:1:-1), p, r(:, 3), wr, ok2)
    call rbf_weights(1.0e6_rk * x, 1.0e6_rk * p, r(:, 3), ws, ok3)
    call check_true('invariance: ok', ok1 .and. ok2 .and. ok3)
    call check_close('reversed node order: max |w - reversed w|', &
        maxval(abs(w - wr(9:1:-1))), 0.0_rk, 0.0_rk, atol=1.0e-14_rk)
    call check_close('scaled by 1e6: max |w - w(scaled)|', maxval(abs(w - ws)), 0.0_rk, &
        0.0_rk, atol=1.0e-13_rk)
  end subroutine test_invariance

  !> Smooth fields on a jittered 3 x 3 patch of spacing h = 1/2^m around a fixed point:
  !> the max error over 16 points of the patch (fixed in patch coordinates) falls by 4
  !> per halving. A quadratic field (exactly second order: linear parts are reproduced and
  !> the weights do not depend on h) and exp(u/2) sin(v + 1/3) (second order as h -> 0).
  subroutine test_convergence()
    integer, parameter :: levels = 6
    real(rk) :: r(3, 3), centre(3), x(3, 9), uv(2, 9), w(9), f(9), p(3), ppl(2)
    real(rk) :: err(levels, 2), h, order, low(2)
    integer :: m, j, ip, jp, which
    logical :: ok, all_ok
    character(len=120) :: line

    r = frame(0.6_rk, -1.2_rk, 0.25_rk)
    centre = [0.4_rk, -0.3_rk, 1.1_rk]
    uv = pattern(9)
    all_ok = .true.
    err = 0.0_rk
    do m = 1, levels
      h = 0.5_rk**(m - 1)
      x = place(centre, h, r, uv)
      do which = 1, 2
        do j = 1, 9
          f(j) = field(which, plane_coords(r, centre, x(:, j)))
        end do
        do jp = 1, 4
          do ip = 1, 4
            ppl = [-0.8_rk + 0.53_rk * (ip - 1), -0.75_rk + 0.51_rk * (jp - 1)]
            p = at(centre, h, r, ppl)
            call rbf_weights(x, p, r(:, 3), w, ok)
            all_ok = all_ok .and. ok
            err(m, which) = max(err(m, which), &
                abs(sum(w * f) - field(which, plane_coords(r, centre, p))))
          end do
        end do
      end do
    end do
    call check_true('convergence: ok', all_ok)
    low = huge(1.0_rk)
    do which = 1, 2
      do m = 2, levels
        order = log(err(m - 1, which) / err(m, which)) / log(2.0_rk)
        low(which) = min(low(which), order)
        write(line, '(a,i0,a,es10.3,a,es10.3,a,f7.4)') 'info convergence field ', which, &
            ': h = ', 0.5_rk**(m - 1), ' max error ', err(m, which), ' order ', order
        write(output_unit, '(a)') trim(line)
      end do
    end do
    call check_true('convergence: quadratic field, measured order >= 1.5 at every halving', &
        low(1) >= 1.5_rk)
    call check_close('convergence: quadratic field, order = 2', low(1), 2.0_rk, 1.0e-6_rk)
    call check_true('convergence: exp(u/2) sin(v+1/3), order >= 1.5 at every halving', &
        low(2) >= 1.5_rk)

  end subroutine test_convergence

  !> In-plane coordinates of y about centre in the frame r.
  function plane_coords(r, centre, y) result(q)
    real(rk), intent(in) :: r(3, 3), centre(3), y(3)
    real(rk) :: q(2)
    q = [dot_product(r(:, 1), y - centre), dot_product(r(:, 2), y - centre)]
  end function plane_coords

  !> The convergence test fields: 1 quadratic, 2 exp(u/2) sin(v + 1/3).
  function field(which, q) result(v)
    integer, intent(in) :: which
    real(rk), intent(in) :: q(2)
    real(rk) :: v
    if (which == 1) then
      v = 1.0_rk + 0.3_rk * q(1) - 0.7_rk * q(2) + 0.5_rk * q(1)**2 &
          + 0.8_rk * q(1) * q(2) - 0.4_rk * q(2)**2
    else
      v = exp(0.5_rk * q(1)) * sin(q(2) + 1.0_rk / 3.0_rk)
    end if
  end function field

end program test_contact_rbf
