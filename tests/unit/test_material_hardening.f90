!> Linear isotropic hardening (elastic_plastic with hardening_modulus H): the
!> radial return driven as the hydro drives it (material_flow gives G, Y = Y0 +
!> H eps_p and H; deviatoric_update returns with dplastic = (sbar - Y)/(3G + H))
!> against the analytic elastic-plastic response of a radial (proportional)
!> path, where the return is exact:
!>   eps_p = (3 G eps_eq - Y0)/(3 G + H),  sbar = Y0 + H eps_p  (eps_eq >= Y0/(3G)),
!> with eps_eq the equivalent total deviatoric strain sqrt(2/3 e':e').
!> (a) uniaxial strain (grad v = diag(edot, 0, 0), eps_eq = 2/3 |eps|), many
!> small steps and one large step; (b) pure shear without spin (grad v
!> symmetric, eps_eq = gamma/sqrt(3)); (c) the surface stays at Y0 + H eps_p
!> during plastic loading, unloading is elastic and leaves eps_p unchanged;
!> (d) H = 0 is the perfectly plastic return bit for bit.
program test_material_hardening
  use core_kinds, only: rk
  use material_table, only: material_t, material_flow, STRENGTH_ELASTIC_PLASTIC
  use material_strength, only: deviatoric_update
  use check, only: check_close, check_true, check_summary
  implicit none
  ! Round-off: one step 100 eps; 1000 accumulated steps 1e-12.
  real(rk), parameter :: tol1 = 100 * epsilon(1.0_rk), tol_n = 1.0e-12_rk
  real(rk), parameter :: g = 0.276_rk, y0 = 0.0029_rk, h = 0.05_rk
  integer, parameter :: nstep = 1000
  type(material_t) :: mat, perfect
  real(rk) :: grad(3, 3), s(6), eps_p, eps_eq, expected_p, sbar, step, edot, gdot
  real(rk) :: s_perfect(6), eps_perfect, worst
  integer :: i
  logical :: on_surface, identical

  mat = material_t(name='hardening', strength=STRENGTH_ELASTIC_PLASTIC, shear_modulus=g, &
      yield_stress=y0, hardening_modulus=h)
  perfect = material_t(name='perfect', strength=STRENGTH_ELASTIC_PLASTIC, shear_modulus=g, &
      yield_stress=y0)

  ! (a) Uniaxial strain in compression to eps = -0.01 (eps_eq = 6.67e-3, about
  ! twice the yield strain Y0/(3G) = 3.5e-3).
  edot = -1.0e-3_rk
  step = 1.0e-2_rk
  grad = 0.0_rk
  grad(1, 1) = edot
  s = 0.0_rk
  eps_p = 0.0_rk
  on_surface = .true.
  worst = 0.0_rk
  do i = 1, nstep
    call advance(mat, grad, step, s, eps_p)
    sbar = mises(s)
    if (eps_p > 0.0_rk) then
      on_surface = on_surface .and. abs(sbar - (y0 + h * eps_p)) <= tol1 * (y0 + h * eps_p)
      worst = max(worst, abs(sbar - (y0 + h * eps_p)) / (y0 + h * eps_p))
    end if
  end do
  eps_eq = 2.0_rk / 3.0_rk * abs(edot) * step * nstep
  expected_p = (3.0_rk * g * eps_eq - y0) / (3.0_rk * g + h)
  call check_true('uniaxial: plastic at the end', eps_p > 0.0_rk)
  call check_close('uniaxial: eps_p = (3G eps_eq - Y0)/(3G + H)', eps_p, expected_p, tol_n)
  call check_close('uniaxial: sbar = Y0 + H eps_p (analytic eps_p)', sbar, &
      y0 + h * expected_p, tol_n)
  call check_close('uniaxial: s_xx = -2/3 sbar', s(1), -2.0_rk / 3.0_rk * sbar, tol_n)
  call check_close('uniaxial: s_yy = s_zz = sbar/3', s(2), sbar / 3.0_rk, tol_n)
  call check_close('uniaxial: s_zz = s_yy', s(3), s(2), tol1)
  call check_true('uniaxial: sbar = Y0 + H eps_p after every plastic step', on_surface)
  write(*, '(a,es10.3)') '  worst relative distance from the surface: ', worst

  ! The same strain in one step: the return is exact for linear hardening.
  s = 0.0_rk
  eps_p = 0.0_rk
  call advance(mat, grad, step * nstep, s, eps_p)
  call check_close('uniaxial, one step: eps_p', eps_p, expected_p, tol1)
  call check_close('uniaxial, one step: sbar = Y0 + H eps_p', mises(s), y0 + h * expected_p, &
      tol1)

  ! (c) Unloading: reverse the strain rate for 100 steps (the stress change
  ! 2G * 100 |edot| step = 5.5e-4 Mbar, well inside the 2 sbar elastic range).
  s = 0.0_rk
  eps_p = 0.0_rk
  do i = 1, nstep
    call advance(mat, grad, step, s, eps_p)
  end do
  expected_p = eps_p
  sbar = mises(s)
  do i = 1, 100
    call advance(mat, -grad, step, s, eps_p)
  end do
  call check_true('unloading: eps_p unchanged', eps_p == expected_p)
  call check_close('unloading: sbar falls by 2G |d eps|', mises(s), &
      sbar - 2.0_rk * g * abs(edot) * step * 100, tol_n)

  ! (b) Pure shear without spin: grad v symmetric, engineering shear rate gdot,
  ! to gamma = 0.02 (eps_eq = 0.0115, yield at gamma = Y0/(sqrt(3) G) = 6.1e-3).
  gdot = 2.0e-3_rk
  grad = 0.0_rk
  grad(1, 2) = 0.5_rk * gdot
  grad(2, 1) = 0.5_rk * gdot
  s = 0.0_rk
  eps_p = 0.0_rk
  do i = 1, nstep
    call advance(mat, grad, step, s, eps_p)
  end do
  eps_eq = gdot * step * nstep / sqrt(3.0_rk)
  expected_p = (3.0_rk * g * eps_eq - y0) / (3.0_rk * g + h)
  call check_close('shear: eps_p = (3G eps_eq - Y0)/(3G + H)', eps_p, expected_p, tol_n)
  call check_close('shear: tau = (Y0 + H eps_p)/sqrt(3)', s(4), &
      (y0 + h * expected_p) / sqrt(3.0_rk), tol_n)
  call check_true('shear: normal deviators stay zero', all(s([1, 2, 3, 5, 6]) == 0.0_rk))

  ! (d) H = 0: the return with the hardening argument is the perfectly plastic one.
  grad = 0.0_rk
  grad(1, 1) = edot
  s = 0.0_rk
  eps_p = 0.0_rk
  s_perfect = 0.0_rk
  eps_perfect = 0.0_rk
  identical = .true.
  do i = 1, nstep
    call advance(perfect, grad, step, s, eps_p)
    call perfectly_plastic(perfect, grad, step, s_perfect, eps_perfect)
    identical = identical .and. all(s == s_perfect) .and. eps_p == eps_perfect
  end do
  call check_true('H = 0: bitwise the return without hardening', identical)
  call check_close('H = 0: sbar = Y0', mises(s), y0, tol1)

  call check_summary()

contains

  !> One step as hydro_strength_update takes it.
  subroutine advance(m, grad, step, s, eps_p)
    type(material_t), intent(in) :: m
    real(rk), intent(in) :: grad(3, 3), step
    real(rk), intent(inout) :: s(6), eps_p
    real(rk) :: shear, yield, hardening, s_new(6), dp
    call material_flow(m, 0.0_rk, 0.0_rk, 1.0_rk, eps_p, 0.0_rk, shear, yield, hardening)
    call deviatoric_update(s, grad, step, shear, yield, s_new, dp, hardening)
    s = s_new
    eps_p = eps_p + dp
  end subroutine advance

  !> One step without the hardening argument.
  subroutine perfectly_plastic(m, grad, step, s, eps_p)
    type(material_t), intent(in) :: m
    real(rk), intent(in) :: grad(3, 3), step
    real(rk), intent(inout) :: s(6), eps_p
    real(rk) :: s_new(6), dp
    call deviatoric_update(s, grad, step, m%shear_modulus, m%yield_stress, s_new, dp)
    s = s_new
    eps_p = eps_p + dp
  end subroutine perfectly_plastic

  !> von Mises equivalent stress sqrt(3/2 s:s).
  pure real(rk) function mises(s)
    real(rk), intent(in) :: s(6)
    mises = sqrt(1.5_rk * (s(1)**2 + s(2)**2 + s(3)**2 + 2.0_rk * (s(4)**2 + s(5)**2 &
        + s(6)**2)))
  end function mises

end program test_material_hardening
