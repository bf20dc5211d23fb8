!> Steinberg-Guinan temperature through the material table (material_flow):
!> (a) by default T = 300 K + max(e, 0)/cv; (b) with sg_cold_energy the cold
!> compression energy e_c = c0^2 chi^2/(2 (1 - s1 chi)^2), chi = 1 - rho0/rho, is
!> subtracted first: e = e_c gives T = 300 K (G = G0 [1 + A p eta^(-1/3)]) and
!> e = e_c + 200 cv gives T = 500 K; at rho = rho0 both agree bit for bit;
!> (c) the energy below the cold curve counts as T = 300 K, not colder;
!> (d) the library: every Johnson-Cook set (JC_SET_NAMES) is a library material
!> with A > 0 and the library's rho0 within 1%; steel_4340's values are those their
!> sources derive (docs/problems.md, "Material data": c0 = sqrt(K/rho0), G from E
!> = 205 GPa and nu = 0.29, gamma0 = 3 alpha K/(rho0 cp), Y0 = A = 1140 MPa), to
!> the rounding of the tabulated digits (half a unit of the last digit given).
program test_material_table
  use core_kinds, only: rk
  use material_table, only: material_t, material_flow, STRENGTH_STEINBERG_GUINAN, &
      EOS_MIE_GRUNEISEN, material_library, material_library_source, LIBRARY_NAMES
  use material_flow_stress, only: sg_set, sg_shear_modulus, sg_yield, jc_set, johnson_cook_t, &
      JC_SET_NAMES
  use eos_mie_gruneisen, only: mie_gruneisen_t
  use check, only: check_close, check_true, check_summary
  implicit none
  real(rk), parameter :: tol = 100 * epsilon(1.0_rk)
  real(rk), parameter :: p = 0.02_rk, eps_p = 0.1_rk
  type(material_t) :: hot, cold
  real(rk) :: rho, eta, chi, e_cold, g, y, h, g_ref, y_ref, g_cold, y_cold
  ! Handbook constants of 4340 steel (docs/problems.md), in Mbar, g/cm^3, 1/K,
  ! Mbar cm^3/(g K).
  real(rk), parameter :: e_4340 = 2.05_rk, nu_4340 = 0.29_rk, alpha_4340 = 12.3e-6_rk
  real(rk), parameter :: cp_4340 = 0.477e-5_rk
  type(mie_gruneisen_t) :: mg
  type(johnson_cook_t) :: jc
  real(rk) :: shear, yield, bulk
  logical :: found
  integer :: k

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

  ! (d) The library.
  do k = 1, size(LIBRARY_NAMES)
    call material_library(trim(LIBRARY_NAMES(k)), mg, shear, yield, found)
    call check_true('library '//trim(LIBRARY_NAMES(k))//' found, with a source', found .and. &
        len_trim(material_library_source(trim(LIBRARY_NAMES(k)))) > 0)
    jc = jc_set(trim(LIBRARY_NAMES(k)))
    if (index(', '//JC_SET_NAMES//',', ', '//trim(LIBRARY_NAMES(k))//',') > 0) then
      call check_true('JC set '//trim(LIBRARY_NAMES(k))//': A > 0, Tm > Tr, cv > 0', &
          jc%a > 0.0_rk .and. jc%tm > jc%tr .and. jc%cv > 0.0_rk)
      ! The same material as the library entry: its density within 1% (cu_ofhc:
      ! Johnson & Cook's 8.96 against Steinberg's 8.93 g/cm^3).
      call check_close('JC set '//trim(LIBRARY_NAMES(k))//': rho0 of the library', jc%rho0, &
          mg%rho0, 0.01_rk)
    else
      call check_true('no JC set for '//trim(LIBRARY_NAMES(k)), jc%a == 0.0_rk)
    end if
  end do
  call material_library('steel_4340', mg, shear, yield, found)
  jc = jc_set('steel_4340')
  bulk = e_4340 / (3.0_rk * (1.0_rk - 2.0_rk * nu_4340))
  call check_close('steel_4340 c0 = sqrt(K/rho0)', mg%c0, sqrt(bulk / mg%rho0), &
      0.00005_rk / 0.4558_rk)
  call check_close('steel_4340 G = E/(2(1 + nu))', shear, e_4340 / (2.0_rk * (1.0_rk + nu_4340)), &
      0.0005_rk / 0.795_rk)
  call check_close('steel_4340 gamma0 = 3 alpha K/(rho0 cp)', mg%gamma0, &
      3.0_rk * alpha_4340 * bulk / (mg%rho0 * cp_4340), 0.005_rk / 1.61_rk)
  call check_close('steel_4340 cp of the JC set', jc%cv, cp_4340, tol)
  call check_close('steel_4340 Y0 = JC A = 1140 MPa', yield, 1140.0e-5_rk, tol)
  call check_close('steel_4340 JC A = 1140 MPa', jc%a, 1140.0e-5_rk, tol)
  call check_close('steel_4340 rho0 = 7830 kg/m^3', mg%rho0, 7.83_rk, tol)

  call check_summary()
end program test_material_table
