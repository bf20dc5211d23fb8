!> Failure models (material_failure): (a) Johnson-Cook's failure strain
!> against literals computed separately in 30-digit arithmetic (Python
!> mpmath) for VAR 4340 steel's D1..D5 (Johnson & Cook 1985: 0.05, 3.44,
!> -2.12, 0.002, 0.61) at chosen triaxiality, rate and temperature, the rate
!> factor 1 below the reference rate; (b) the floor where a negative D1 makes
!> the formula negative (Lesuer's 6061-T6 set -0.77, 1.45, -0.47, 0, 1.6 at
!> sigma* = 2), and its positive value at sigma* = 0.5; (c) the maximum
!> plastic strain model and the factory (an unknown name refused); (d)
!> failure_damage_rate takes sigma* = -p/sbar and epsdot* = rate / reference;
!> (e) the homologous temperature of a Johnson-Cook material from its energy,
!> clipped to [0, 1], and 0 for the other strength models.
program test_material_failure
  use core_kinds, only: rk
  use material_failure, only: failure_model_t, failure_t, failure_model_new, &
      failure_damage_rate, failure_homologous, FAILURE_STRAIN_FLOOR
  use material_table, only: material_t, STRENGTH_JOHNSON_COOK, STRENGTH_ELASTIC_PLASTIC
  use check, only: check_close, check_true, check_summary
  implicit none
  ! Relative tolerance: the formula is a few operations and one exp and one
  ! log, each correctly rounded to within an ulp or two; 100 ulp is ample
  ! and still far below any physical difference.
  real(rk), parameter :: tol = 100 * epsilon(1.0_rk)
  real(rk), parameter :: d4340(5) = [0.05_rk, 3.44_rk, -2.12_rk, 0.002_rk, 0.61_rk]
  real(rk), parameter :: d6061(5) = [-0.77_rk, 1.45_rk, -0.47_rk, 0.0_rk, 1.6_rk]
  class(failure_model_t), allocatable :: model
  type(failure_t) :: fail
  type(material_t) :: mat
  logical :: ok

  ! (a) 4340.
  call failure_model_new('johnson_cook', d4340, model, ok)
  call check_true('factory: johnson_cook', ok .and. allocated(model))
  call check_close('JC 4340 sigma*=1/3, epsdot*=1000, T*=0.1', &
      model%failure_strain(1.0_rk / 3.0_rk, 1000.0_rk, 0.1_rk), &
      1.87907059872537568670041131052_rk, tol)
  call check_close('JC 4340 sigma*=-1, epsdot*=0.5 (rate factor 1), T*=0', &
      model%failure_strain(-1.0_rk, 0.5_rk, 0.0_rk), 28.7091129576456602650022341061_rk, tol)
  call check_close('JC 4340 sigma*=0, reference rate, room temperature: D1 + D2', &
      model%failure_strain(0.0_rk, 1.0_rk, 0.0_rk), 3.49_rk, tol)
  ! (b) 6061-T6: negative formula floored by failure_damage_rate.
  call failure_model_new('johnson_cook', d6061, model, ok)
  call check_close('JC 6061 sigma*=2, epsdot*=10, T*=0.2 (negative)', &
      model%failure_strain(2.0_rk, 10.0_rk, 0.2_rk), -0.268738323123790611417595764018_rk, tol)
  call check_close('JC 6061 sigma*=0.5, epsdot*=10, T*=0.2', &
      model%failure_strain(0.5_rk, 10.0_rk, 0.2_rk), 0.496752606189399842320262016542_rk, tol)
  call move_alloc(model, fail%model)
  fail%rate_reference = 1.0e-6_rk
  ! sigma* = -p/sbar = 2 with p = -0.004, sbar = 0.002; epsdot* = 1e-5/1e-6 = 10.
  call check_close('damage rate at the floor', failure_damage_rate(fail, -0.004_rk, &
      0.002_rk, 1.0e-5_rk, 0.2_rk), 1.0_rk / FAILURE_STRAIN_FLOOR, tol)
  ! (d) sigma* = 0.5 from p = -0.001, sbar = 0.002.
  call check_close('damage rate 1/eps_f, sigma* = -p/sbar, epsdot* over the reference', &
      failure_damage_rate(fail, -0.001_rk, 0.002_rk, 1.0e-5_rk, 0.2_rk), &
      1.0_rk / 0.496752606189399842320262016542_rk, tol)
  call check_true('failure_t fails with a model', fail%fails())
  ! (c) maximum plastic strain, the factory's refusal, spall alone.
  call failure_model_new('plastic_strain', [0.3_rk], model, ok)
  call check_true('factory: plastic_strain', ok)
  call check_close('plastic_strain: constant', model%failure_strain(5.0_rk, 1.0e6_rk, 1.0_rk), &
      0.3_rk, tol)
  call failure_model_new('gurson', [0.3_rk], model, ok)
  call check_true('factory: unknown name refused', .not. ok .and. .not. allocated(model))
  fail = failure_t()
  call check_true('failure_t: no model, no spall: never fails', .not. fail%fails())
  fail%spall_strength = 0.01_rk
  call check_true('failure_t: spall alone fails', fail%fails())
  ! (e) T* = (T - Tr)/(Tm - Tr), T = Tr + e/cv.
  mat%strength = STRENGTH_JOHNSON_COOK
  mat%jc%tr = 300.0_rk
  mat%jc%tm = 1800.0_rk
  mat%jc%cv = 0.5e-5_rk
  ! e = 1.5e-3 -> T = 600 K -> T* = 0.2.
  call check_close('T* of Johnson-Cook', failure_homologous(mat, 1.5e-3_rk), 0.2_rk, tol)
  call check_close('T* clipped at 1', failure_homologous(mat, 1.0_rk), 1.0_rk, tol)
  call check_close('T* clipped at 0 (negative energy)', failure_homologous(mat, -1.0e-3_rk), &
      0.0_rk, tol, 0.0_rk)
  mat%strength = STRENGTH_ELASTIC_PLASTIC
  call check_close('T* 0 without a temperature model', failure_homologous(mat, 1.5e-3_rk), &
      0.0_rk, tol, 0.0_rk)
  call check_summary()
end program test_material_failure
