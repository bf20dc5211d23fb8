!> Edge viscosity kernel (zone_edge_forces): in a uniform compression of a
!> box along x the four x-edges carry q_edge = rho [C2 g |du| + sqrt(C2^2 g^2
!> du^2 + C1^2 c^2)] |du| through a quarter of the cross-section each, so the
!> x = 0 face is pushed out by q_edge A_x and nothing acts along y and z;
!> uniform expansion and rigid translation give no force; on distorted hexes
!> with random velocities the forces sum to zero (no momentum) and their work
!> on the velocities is never positive (dissipation only); the limiter factor
!> scales the forces linearly and 0 switches them off.
program test_hydro_edge_viscosity
  use core_kinds, only: rk
  use mesh_geometry, only: SIGN_XI, SIGN_ETA, SIGN_ZETA
  use hydro_kernels, only: zone_edge_forces
  use check, only: check_close, check_true, check_summary
  implicit none
  real(rk), parameter :: eps = epsilon(1.0_rk)
  real(rk), parameter :: c1 = 0.5_rk, c2 = 2.0_rk / 3.0_rk, rho = 1.3_rk, cs = 0.7_rk
  real(rk), parameter :: g = (1.4_rk + 1.0_rk) / 4.0_rk
  integer :: zone_node(8, 1), k, trial, seed_size
  integer, allocatable :: seed(:)
  real(rk) :: x(3, 8), v(3, 8), f(3, 8, 1), edge_q(2, 1), vol(1), dens(1), sound(1)
  real(rk) :: a, du, qe, fx, work, scale, f1(3, 8, 1), r(3, 8)
  character(len=64) :: name

  zone_node(:, 1) = [(k, k = 1, 8)]
  vol = 1.0_rk
  dens = rho
  sound = cs
  edge_q(:, 1) = [1.0_rk, g]

  ! Box 2 x 3 x 0.5 compressed along x: v_x = -a x.
  x = box(2.0_rk, 3.0_rk, 0.5_rk)
  a = 0.4_rk
  v = 0.0_rk
  v(1, :) = -a * x(1, :)
  f = 0.0_rk
  call zone_edge_forces(1, zone_node, x, v, vol, dens, sound, edge_q, c1, c2, .true., f)
  du = 2.0_rk * a
  qe = rho * (c2 * g * du + sqrt((c2 * g * du)**2 + (c1 * cs)**2)) * du
  fx = sum(f(1, :, 1), mask=SIGN_XI < 0.0_rk)
  call check_close('x = 0 face pushed out by q_edge * (3 x 0.5)', fx, -qe * 1.5_rk, 8 * eps)
  call check_close('x = 2 face: the opposite', sum(f(1, :, 1), mask=SIGN_XI > 0.0_rk), &
      qe * 1.5_rk, 8 * eps)
  call check_true('no force along y and z', all(abs(f(2:3, :, 1)) <= 8 * eps * qe))
  do k = 1, 8
    write(name, '(a,i0,a)') 'node ', k, ' carries a quarter of its face'
    call check_close(trim(name), abs(f(1, k, 1)), 0.25_rk * qe * 1.5_rk, 8 * eps)
  end do

  ! Uniform expansion and rigid translation: no force.
  v = 0.3_rk * x
  f = 0.0_rk
  call zone_edge_forces(1, zone_node, x, v, vol, dens, sound, edge_q, c1, c2, .true., f)
  call check_true('uniform expansion: no force', all(f == 0.0_rk))
  v = 0.0_rk
  v(1, :) = 5.0_rk
  v(3, :) = -2.0_rk
  call zone_edge_forces(1, zone_node, x, v, vol, dens, sound, edge_q, c1, c2, .true., f)
  call check_true('rigid translation: no force', all(f == 0.0_rk))

  ! Distorted hexes, random velocities: no momentum, work <= 0, limiter scaling.
  call random_seed(size=seed_size)
  allocate(seed(seed_size))
  seed = 4242
  call random_seed(put=seed)
  do trial = 1, 20
    call random_number(r)
    x = box(1.0_rk, 1.0_rk, 1.0_rk) + 0.3_rk * (r - 0.5_rk)
    call random_number(v)
    v = v - 0.5_rk
    edge_q(1, 1) = 1.0_rk
    f = 0.0_rk
    call zone_edge_forces(1, zone_node, x, v, vol, dens, sound, edge_q, c1, c2, .true., f)
    scale = maxval(abs(f)) + tiny(1.0_rk)
    write(name, '(a,i0)') 'random hex: forces sum to zero, case ', trial
    call check_true(trim(name), all(abs(sum(f(:, :, 1), dim=2)) <= 32 * eps * scale))
    work = sum(f(:, :, 1) * v)
    write(name, '(a,i0)') 'random hex: work of the forces <= 0, case ', trial
    call check_true(trim(name), work <= 0.0_rk)
    write(name, '(a,i0)') 'random hex: some edge compressed, case ', trial
    call check_true(trim(name), scale > tiny(1.0_rk) .and. work < 0.0_rk)
    edge_q(1, 1) = 0.25_rk
    f1 = 0.0_rk
    call zone_edge_forces(1, zone_node, x, v, vol, dens, sound, edge_q, c1, c2, .true., f1)
    write(name, '(a,i0)') 'random hex: limiter factor 1/4 scales the forces, case ', trial
    call check_true(trim(name), all(abs(f1 - 0.25_rk * f) <= 8 * eps * scale))
    edge_q(1, 1) = 0.0_rk
    f1 = 0.0_rk
    call zone_edge_forces(1, zone_node, x, v, vol, dens, sound, edge_q, c1, c2, .true., f1)
    write(name, '(a,i0)') 'random hex: limiter factor 0 switches the forces off, case ', trial
    call check_true(trim(name), all(f1 == 0.0_rk))
  end do

  call check_summary()

contains

  function box(lx, ly, lz) result(c)
    real(rk), intent(in) :: lx, ly, lz
    real(rk) :: c(3, 8)
    c(1, :) = 0.5_rk * lx * (SIGN_XI + 1.0_rk)
    c(2, :) = 0.5_rk * ly * (SIGN_ETA + 1.0_rk)
    c(3, :) = 0.5_rk * lz * (SIGN_ZETA + 1.0_rk)
  end function box

end program test_hydro_edge_viscosity
