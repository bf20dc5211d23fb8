!> Steinberg-Guinan temperature through the material table (material_flow):
!> (a) by default T = 300 K + max(e, 0)/cv; (b) with sg_cold_energy the cold
!> compression energy e_c = c0^2 chi^2/(2 (1 - s1 chi)^2), chi = 1 - rho0/rho, is
!> subtracted first: e = e_c gives T = 300 K (G = G0 [1 + A p eta^(-1/3)]) and
!> e = e_c + 200 cv gives T = 500 K; at rho = rho0 both agree bit for bit;
!> (c) the energy below the cold curve counts as T = 300 K, not colder.
program test_material_table
  use core_kinds, only: rk
  use material_table, only: material_t, material_flow, STRENGTH_STEINBERG_GUINAN, &
      EOS_MIE_GRUNEISEN
  use material_flow_stress, only: sg_set, sg_shear_modulus, sg_yield
  use eos_mie_gruneisen, only: mie_gruneisen_t
  use check, only: check_close, check_true, check_summary
  implicit none
  real(rk), parameter :: tol = 100 * epsilon(1.0_rk)
  real(rk), parameter :: p = 0.02_rk, eps_p = 0.1_rk
  type(material_t) :: hot, cold
  real(rk) :: rho, eta, chi, e_cold, g, y, h, g_ref, y_ref, g_cold, y_cold

  hot = material_t(name='cu', eos=EOS_MIE_GRUNEISEN, mg=mie_gruneisen_t(rho0=8.93_rk, &
      c0=0.394_rk, s1=1.489_rk, gamma0=2.02_rk, b=0.47_rk), &
      strength=STRENGTH_STEINBERG_GUINAN, sg=sg_set('cu_ofhc'))
  cold = hot
  cold%sg_cold_energy = .true.
  rho = 1.1_rk * hot%mg%rho0
  eta = rho / hot%sg%rho0
  chi = 1.0_rk - hot%mg%rho0 / rho
  e_cold = 0.5_rk * (hot%mg%c0 * chi / (1.0_rk - hot%mg%s1 * chi))**2

  ! (a) Default: T = 300 + e/cv.
  call material_flow(hot, p, e_cold, rho, eps_p, 0.0_rk, g, y, h)
  call check_close('default: G at T = 300 + e/cv', g, &
      sg_shear_modulus(hot%sg, p, 300.0_rk + e_cold / hot%sg%cv, eta), tol)
  call check_true('default: no hardening modulus for the return', h == 0.0_rk)

  ! (b) Cold energy subtracted.
  call material_flow(cold, p, e_cold, rho, eps_p, 0.0_rk, g_cold, y_cold, h)
  g_ref = sg_shear_modulus(cold%sg, p, 300.0_rk, eta)
  y_ref = sg_yield(cold%sg, eps_p, p, 300.0_rk, eta)
  call check_close('cold: e = e_c gives G at 300 K', g_cold, g_ref, tol)
  call check_close('cold: e = e_c gives Y at 300 K', y_cold, y_ref, tol)
  call check_close('cold: G at 300 K = G0 (1 + A p eta^(-1/3))', g_cold, &
      cold%sg%g0 * (1.0_rk + cold%sg%a * p / eta**(1.0_rk / 3.0_rk)), tol)
  call check_true('cold: hotter default is softer', g < g_cold)
  call material_flow(cold, p, e_cold + 200.0_rk * cold%sg%cv, rho, eps_p, 0.0_rk, g, y, h)
  call check_close('cold: e = e_c + 200 cv gives G at 500 K', g, &
      sg_shear_modulus(cold%sg, p, 500.0_rk, eta), 1.0e3_rk * epsilon(1.0_rk))
  ! At rho0 the cold energy is zero: both ways agree exactly.
  call material_flow(hot, p, 1.0e-4_rk, hot%mg%rho0, eps_p, 0.0_rk, g, y, h)
  call material_flow(cold, p, 1.0e-4_rk, hot%mg%rho0, eps_p, 0.0_rk, g_cold, y_cold, h)
  call check_true('rho = rho0: same G and Y bit for bit', g == g_cold .and. y == y_cold)

  ! (c) Below the cold curve: T = 300 K.
  call material_flow(cold, p, 0.5_rk * e_cold, rho, eps_p, 0.0_rk, g, y, h)
  call check_close('cold: e < e_c counts as 300 K', g, g_ref, tol)

  call check_summary()
end program test_material_table
