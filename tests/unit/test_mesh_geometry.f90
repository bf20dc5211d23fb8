!> Geometry kernels: exact trilinear volume (against 2x2x2 Gauss quadrature
!> of det J, exact for trilinear hexes), B-matrix against finite differences,
!> Euler identity V = sum(B.x)/3, face area vectors, characteristic length.
program test_mesh_geometry
  use core_kinds, only: rk
  use mesh_geometry, only: hex_volume, hex_volume_gradient, hex_characteristic_length, &
      quad_vector_area, quad_node_area_vectors, SIGN_XI, SIGN_ETA, SIGN_ZETA
  use check, only: check_close, check_true, check_summary
  implicit none
  real(rk), parameter :: eps = epsilon(1.0_rk)
  real(rk) :: x(3, 8), b(3, 8), v, vp, vm, h, fd, a(3, 4), p(3, 4), total(3), ref(3, 4)
  real(rk) :: lin(3, 3), r
  integer :: trial, k, i, seed_size
  integer, allocatable :: seed(:)
  character(len=64) :: name

  call random_seed(size=seed_size)
  allocate(seed(seed_size))
  seed = 12345
  call random_seed(put=seed)

  ! Unit cube and a box.
  x = unit_cube()
  call check_close('unit cube volume', hex_volume(x), 1.0_rk, 4 * eps)
  x(1, :) = 2.0_rk * x(1, :)
  x(2, :) = 3.0_rk * x(2, :)
  x(3, :) = 0.5_rk * x(3, :)
  call check_close('box volume', hex_volume(x), 3.0_rk, 4 * eps)
  call check_close('box length = smallest edge', hex_characteristic_length(x, 3.0_rk), &
      0.5_rk, 4 * eps)

  ! A linear map of the cube: volume = det.
  lin = reshape([1.0_rk, 0.2_rk, 0.1_rk, -0.3_rk, 1.1_rk, 0.05_rk, 0.4_rk, 0.0_rk, 0.9_rk], [3, 3])
  x = matmul(lin, unit_cube())
  call check_close('parallelepiped volume = det', hex_volume(x), det3(lin), 8 * eps)

  ! Random trilinear hexes with non-planar faces.
  do trial = 1, 20
    x = unit_cube()
    call random_number(b)
    x = x + 0.3_rk * (b - 0.5_rk)
    write(name, '(a,i0)') 'distorted hex volume vs Gauss 2x2x2, case ', trial
    call check_close(trim(name), hex_volume(x), gauss_volume(x), 16 * eps)
    call hex_volume_gradient(x, v, b)
    write(name, '(a,i0)') 'V from gradient routine, case ', trial
    call check_close(trim(name), v, hex_volume(x), 16 * eps)
    write(name, '(a,i0)') 'Euler identity V = sum(B.x)/3, case ', trial
    call check_close(trim(name), sum(b * x) / 3.0_rk, v, 64 * eps)
    ! Central differences are exact up to round-off for a cubic: check B . dx.
    h = 1.0e-4_rk
    do k = 1, 8, 3
      do i = 1, 3
        x(i, k) = x(i, k) + h
        vp = hex_volume(x)
        x(i, k) = x(i, k) - 2.0_rk * h
        vm = hex_volume(x)
        x(i, k) = x(i, k) + h
        fd = (vp - vm) / (2.0_rk * h)
        write(name, '(a,i0,a,i0,a,i0)') 'B vs finite difference, case ', trial, ' node ', k, &
            ' dir ', i
        call check_close(trim(name), b(i, k), fd, 1.0e-9_rk, atol=1.0e-10_rk)
      end do
    end do
    ! Translation invariance: sum of B is zero.
    call check_true('sum of B is zero', maxval(abs(sum(b, dim=2))) < 64 * eps)
  end do

  ! Bilinear quadrilateral: nodal area vectors sum to the vector area, and
  ! match a fine midpoint-rule integration of N_k n dA.
  do trial = 1, 5
    call random_number(p)
    p = reshape([0.0_rk, 0.0_rk, 0.0_rk, 1.0_rk, 0.0_rk, 0.0_rk, 1.0_rk, 1.0_rk, 0.0_rk, &
        0.0_rk, 1.0_rk, 0.0_rk], [3, 4]) + 0.3_rk * (p - 0.5_rk)
    call quad_node_area_vectors(p, a)
    total = sum(a, dim=2)
    r = maxval(abs(total - quad_vector_area(p)))
    call check_true('quad node areas sum to the vector area', r < 16 * eps)
    ref = midpoint_node_areas(p, 400)
    call check_true('quad node areas vs quadrature', maxval(abs(a - ref)) < 1.0e-5_rk)
  end do
  call check_summary()

contains

  function unit_cube() result(c)
    real(rk) :: c(3, 8)
    c(1, :) = 0.5_rk * (SIGN_XI + 1.0_rk)
    c(2, :) = 0.5_rk * (SIGN_ETA + 1.0_rk)
    c(3, :) = 0.5_rk * (SIGN_ZETA + 1.0_rk)
  end function unit_cube

  real(rk) function det3(m)
    real(rk), intent(in) :: m(3, 3)
    det3 = m(1, 1) * (m(2, 2) * m(3, 3) - m(2, 3) * m(3, 2)) &
        - m(1, 2) * (m(2, 1) * m(3, 3) - m(2, 3) * m(3, 1)) &
        + m(1, 3) * (m(2, 1) * m(3, 2) - m(2, 2) * m(3, 1))
  end function det3

  !> det J integrated by 2-point Gauss in each direction (exact: det J of a
  !> trilinear map is at most quadratic in each variable).
  real(rk) function gauss_volume(xx)
    real(rk), intent(in) :: xx(3, 8)
    real(rk) :: g(2), jac(3, 3), xi, eta, zeta
    integer :: i1, i2, i3, kk
    g = [-1.0_rk, 1.0_rk] / sqrt(3.0_rk)
    gauss_volume = 0.0_rk
    do i1 = 1, 2
      do i2 = 1, 2
        do i3 = 1, 2
          xi = g(i1)
          eta = g(i2)
          zeta = g(i3)
          jac = 0.0_rk
          do kk = 1, 8
            jac(:, 1) = jac(:, 1) + xx(:, kk) * SIGN_XI(kk) * (1 + SIGN_ETA(kk) * eta) * &
                (1 + SIGN_ZETA(kk) * zeta) / 8
            jac(:, 2) = jac(:, 2) + xx(:, kk) * SIGN_ETA(kk) * (1 + SIGN_XI(kk) * xi) * &
                (1 + SIGN_ZETA(kk) * zeta) / 8
            jac(:, 3) = jac(:, 3) + xx(:, kk) * SIGN_ZETA(kk) * (1 + SIGN_XI(kk) * xi) * &
                (1 + SIGN_ETA(kk) * eta) / 8
          end do
          gauss_volume = gauss_volume + det3(jac)
        end do
      end do
    end do
  end function gauss_volume

  function midpoint_node_areas(pp, n) result(aa)
    real(rk), intent(in) :: pp(3, 4)
    integer, intent(in) :: n
    real(rk) :: aa(3, 4), s, t, xs(3), xt(3), nrm(3), shp(4)
    integer :: i1, i2
    aa = 0.0_rk
    do i1 = 1, n
      do i2 = 1, n
        s = (i1 - 0.5_rk) / n
        t = (i2 - 0.5_rk) / n
        xs = (1 - t) * (pp(:, 2) - pp(:, 1)) + t * (pp(:, 3) - pp(:, 4))
        xt = (1 - s) * (pp(:, 4) - pp(:, 1)) + s * (pp(:, 3) - pp(:, 2))
        nrm = [xs(2) * xt(3) - xs(3) * xt(2), xs(3) * xt(1) - xs(1) * xt(3), &
            xs(1) * xt(2) - xs(2) * xt(1)]
        shp = [(1 - s) * (1 - t), s * (1 - t), s * t, (1 - s) * t]
        kk_loop: block
          integer :: kk
          do kk = 1, 4
            aa(:, kk) = aa(:, kk) + shp(kk) * nrm / real(n * n, rk)
          end do
        end block kk_loop
      end do
    end do
  end function midpoint_node_areas

end program test_mesh_geometry
