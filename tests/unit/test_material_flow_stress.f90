!> Steinberg-Guinan and Johnson-Cook kernels: (a) values at a chosen state for
!> every named set, against the formula re-evaluated here in another arithmetic
!> order (logs and exponentials instead of powers, G0 distributed) and against
!> literals computed separately in 30-digit arithmetic (Python mpmath);
!> (b) the Ymax cap and eps_i; (c) zero strength at and above melt, Tm(rho0) = Tm0;
!> (d) monotonic hardening, G falling with T and rising with p, no negative G;
!> (e) Johnson-Cook T* clipping, rate factor 1 below eps_dot0, eps_p = 0;
!> (f) temperature from energy and the unit conversions of the sets;
!> (g) 'cu_taylor' is 'cu_ofhc' but for the fitted Y0 and beta.
program test_material_flow_stress
  use core_kinds, only: rk
  use material_flow_stress, only: steinberg_guinan_t, johnson_cook_t, sg_shear_modulus, &
      sg_yield, sg_melt_temperature, sg_set, jc_yield, jc_set, temperature_from_energy, &
      SG_REFERENCE_TEMPERATURE
  use check, only: check_close, check_true, check_summary
  implicit none
  real(rk), parameter :: tol = 100 * epsilon(1.0_rk)
  character(len=*), parameter :: set_names(3) = [character(len=7) :: 'al6061', 'cu_ofhc', &
      'ss304']
  ! Literals from 30-digit arithmetic at eps_p = 0.05, p = 0.05 Mbar, T = 600 K,
  ! eta = 1.05: Tm, G, Y for al6061, cu_ofhc, ss304.
  real(rk), parameter :: tm_literal(3) = [1426.2433788130085_rk, 2102.8377821248583_rk, &
      2771.9591704113275_rk]
  real(rk), parameter :: g_literal(3) = [0.31351972037703438_rk, 0.48945797250275767_rk, &
      0.7505013674536072_rk]
  real(rk), parameter :: y_literal(3) = [0.004015943365888236_rk, 0.001957038583604057_rk, &
      0.004951632144508238_rk]
  real(rk), parameter :: eps_p = 0.05_rk, p = 0.05_rk, temperature = 600.0_rk, eta = 1.05_rk
  type(steinberg_guinan_t) :: sg, sg_shifted
  type(johnson_cook_t) :: jc
  real(rk) :: expected, factor, tm, y_previous, y, g_cold, g_hot
  real(rk) :: strains(8), temperatures(5), pressures(5), values(8)
  logical :: increasing
  integer :: iset, i
  character(len=80) :: tag

  ! (a) Steinberg-Guinan values for each set.
  do iset = 1, size(set_names)
    sg = sg_set(trim(set_names(iset)))
    tag = 'SG '//trim(set_names(iset))//': '
    call check_true(trim(tag)//'set found', sg%g0 > 0.0_rk)

    expected = exp(log(sg%tm0) + 2.0_rk * sg%a_melt * (eta - 1.0_rk) / eta &
        + (2.0_rk * sg%gamma0 - 2.0_rk * sg%a_melt - 2.0_rk / 3.0_rk) * log(eta))
    tm = sg_melt_temperature(sg, eta)
    call check_close(trim(tag)//'Tm formula', tm, expected, tol)
    call check_close(trim(tag)//'Tm literal', tm, tm_literal(iset), tol)

    expected = sg%g0 + sg%g0 * sg%a * p * exp(-log(eta) / 3.0_rk) &
        - sg%g0 * sg%b * temperature + 300.0_rk * sg%g0 * sg%b
    call check_close(trim(tag)//'G formula', sg_shear_modulus(sg, p, temperature, eta), &
        expected, tol)
    call check_close(trim(tag)//'G literal', sg_shear_modulus(sg, p, temperature, eta), &
        g_literal(iset), tol)

    ! Y = Y0 f(eps) G/G0 with f below the cap at this strain for all three sets.
    expected = sg%y0 * exp(sg%n * log(1.0_rk + sg%beta * eps_p)) * (expected / sg%g0)
    call check_true(trim(tag)//'below cap at test strain', &
        sg%y0 * exp(sg%n * log(1.0_rk + sg%beta * eps_p)) < sg%ymax)
    call check_close(trim(tag)//'Y formula', sg_yield(sg, eps_p, p, temperature, eta), &
        expected, tol)
    call check_close(trim(tag)//'Y literal', sg_yield(sg, eps_p, p, temperature, eta), &
        y_literal(iset), tol)

    ! Reference state: G0 and Y0 exactly.
    call check_close(trim(tag)//'G(0, 300 K, rho0) = G0', &
        sg_shear_modulus(sg, 0.0_rk, SG_REFERENCE_TEMPERATURE, 1.0_rk), sg%g0, tol)
    call check_close(trim(tag)//'Y(0, 0, 300 K, rho0) = Y0', &
        sg_yield(sg, 0.0_rk, 0.0_rk, SG_REFERENCE_TEMPERATURE, 1.0_rk), sg%y0, tol)

    ! (b) Ymax cap: at eps_p = 100 every set's f(eps) exceeds Ymax.
    call check_true(trim(tag)//'uncapped f(100) > Ymax', &
        sg%y0 * (1.0_rk + sg%beta * 100.0_rk)**sg%n > sg%ymax)
    call check_close(trim(tag)//'cap at reference state', &
        sg_yield(sg, 100.0_rk, 0.0_rk, SG_REFERENCE_TEMPERATURE, 1.0_rk), sg%ymax, tol)
    factor = sg_shear_modulus(sg, p, temperature, eta) / sg%g0
    call check_close(trim(tag)//'cap times G/G0', sg_yield(sg, 100.0_rk, p, temperature, eta), &
        sg%ymax * factor, tol)

    ! (c) Melt: Tm(rho0) = Tm0; zero G and Y at and above Tm, positive just below.
    call check_close(trim(tag)//'Tm(rho0) = Tm0', sg_melt_temperature(sg, 1.0_rk), sg%tm0, &
        tol)
    call check_true(trim(tag)//'Tm rises with compression', tm > sg%tm0)
    call check_true(trim(tag)//'G = 0 at Tm', sg_shear_modulus(sg, p, tm, eta) == 0.0_rk)
    call check_true(trim(tag)//'Y = 0 at Tm', sg_yield(sg, eps_p, p, tm, eta) == 0.0_rk)
    call check_true(trim(tag)//'G = 0 above Tm', &
        sg_shear_modulus(sg, p, tm + 50.0_rk, eta) == 0.0_rk)
    call check_true(trim(tag)//'Y = 0 above Tm', &
        sg_yield(sg, eps_p, p, tm + 50.0_rk, eta) == 0.0_rk)
    ! Just below melt at rho0, p = 0 the linear softening 1 - B (Tm0 - 300) is still
    ! positive for all three sets (smallest: 304 SS, 0.054).
    call check_close(trim(tag)//'G just below Tm0', &
        sg_shear_modulus(sg, 0.0_rk, sg%tm0 - 1.0_rk, 1.0_rk), &
        sg%g0 * (1.0_rk - sg%b * (sg%tm0 - 301.0_rk)), tol)
    call check_true(trim(tag)//'G > 0 just below Tm0', &
        sg_shear_modulus(sg, 0.0_rk, sg%tm0 - 1.0_rk, 1.0_rk) > 0.0_rk)

    ! (d) Monotonic hardening up to the cap (strictly rising below it).
    strains = [0.0_rk, 0.001_rk, 0.01_rk, 0.03_rk, 0.1_rk, 0.3_rk, 1.0_rk, 3.0_rk]
    values = sg_yield(sg, strains, p, temperature, eta)
    increasing = .true.
    do i = 2, size(strains)
      if (sg%y0 * (1.0_rk + sg%beta * strains(i))**sg%n < sg%ymax) then
        increasing = increasing .and. values(i) > values(i - 1)
      else
        increasing = increasing .and. values(i) >= values(i - 1)
      end if
    end do
    call check_true(trim(tag)//'Y rises with eps_p', increasing)

    ! G falls with T at fixed p and rises with p at fixed T (elemental over arrays).
    temperatures = [200.0_rk, 300.0_rk, 600.0_rk, 900.0_rk, 1100.0_rk]
    values(1:5) = sg_shear_modulus(sg, p, temperatures, eta)
    call check_true(trim(tag)//'G falls with T', all(values(2:5) < values(1:4)))
    pressures = [-0.01_rk, 0.0_rk, 0.05_rk, 0.2_rk, 1.0_rk]
    values(1:5) = sg_shear_modulus(sg, pressures, temperature, 1.0_rk)
    call check_true(trim(tag)//'G rises with p', all(values(2:5) > values(1:4)))
    call check_true(trim(tag)//'G never negative in deep tension', &
        sg_shear_modulus(sg, -10.0_rk, temperature, 1.0_rk) == 0.0_rk)
  end do

  ! (b) eps_i shifts the hardening curve: eps_i = 0.1, eps_p = 0.05 equals eps_p = 0.15.
  sg = sg_set('cu_ofhc')
  sg_shifted = sg
  sg_shifted%eps_i = 0.1_rk
  call check_close('SG eps_i shifts the strain', sg_yield(sg_shifted, 0.05_rk, p, temperature, &
      eta), sg_yield(sg, 0.15_rk, p, temperature, eta), tol)
  ! A dilated state: eta < 1 lowers Tm for these sets (gamma0 - a - 1/3 > 0).
  call check_true('SG Cu Tm falls in tension', sg_melt_temperature(sg, 0.95_rk) < sg%tm0)

  ! 304 SS at eta = 1.05, p = 0.05 Mbar: 1 + A p eta^(-1/3) - B (T - 300) crosses zero
  ! near 2742 K, below Tm(1.05) = 2772 K; G is clipped to zero there, not negative.
  sg = sg_set('ss304')
  call check_true('SG ss304 G clipped to 0 below melt', &
      sg_shear_modulus(sg, p, 2760.0_rk, eta) == 0.0_rk .and. &
      2760.0_rk < sg_melt_temperature(sg, eta))
  call check_true('SG ss304 G > 0 before the crossing', &
      sg_shear_modulus(sg, p, 2700.0_rk, eta) > 0.0_rk)

  ! Unknown names give the unset default.
  sg = sg_set('unobtainium')
  call check_true('SG unknown set is unset', sg%g0 == 0.0_rk .and. sg%y0 == 0.0_rk)

  ! (e) Johnson-Cook, OFHC Cu.
  jc = jc_set('cu_ofhc')
  call check_close('JC A = 90 MPa', jc%a * 1.0e5_rk, 90.0_rk, tol)
  call check_close('JC B = 292 MPa', jc%b * 1.0e5_rk, 292.0_rk, tol)
  ! eps_p = 0.2, rate 1e-3 /us = 1000 /s, T = 500 K.
  expected = exp(log(1000.0_rk)) ! the rate ratio, 1e-3 / 1e-6
  expected = (jc%a + jc%b * exp(jc%n * log(0.2_rk))) * (1.0_rk + jc%c * log(expected)) &
      * (1.0_rk - exp(jc%m * log((500.0_rk - 298.0_rk) / (1356.0_rk - 298.0_rk))))
  call check_close('JC formula', jc_yield(jc, 0.2_rk, 1.0e-3_rk, 500.0_rk), expected, tol)
  call check_close('JC literal', jc_yield(jc, 0.2_rk, 1.0e-3_rk, 500.0_rk), &
      0.0026189673983504822_rk, tol)
  ! Rate factor is 1 at and below eps_dot0, including zero and negative rates.
  y = jc_yield(jc, 0.2_rk, jc%eps_dot0, 500.0_rk)
  call check_close('JC rate factor 1 below eps_dot0', &
      jc_yield(jc, 0.2_rk, 0.01_rk * jc%eps_dot0, 500.0_rk), y, tol)
  call check_close('JC rate factor 1 at zero rate', jc_yield(jc, 0.2_rk, 0.0_rk, 500.0_rk), &
      y, tol)
  call check_close('JC rate factor 1 at negative rate', &
      jc_yield(jc, 0.2_rk, -1.0_rk, 500.0_rk), y, tol)
  call check_true('JC rate hardening', jc_yield(jc, 0.2_rk, 1.0e-3_rk, 500.0_rk) > y)
  ! T* clipped: below Tr it is 0 (no extra strength), at and above Tm it is 1 (zero).
  call check_close('JC T* = 0 at Tr', jc_yield(jc, 0.0_rk, 0.0_rk, jc%tr), jc%a, tol)
  call check_close('JC T* clipped below Tr', jc_yield(jc, 0.0_rk, 0.0_rk, 77.0_rk), jc%a, tol)
  call check_true('JC zero at Tm', jc_yield(jc, 0.2_rk, 1.0e-3_rk, jc%tm) == 0.0_rk)
  call check_true('JC zero above Tm', jc_yield(jc, 0.2_rk, 1.0e-3_rk, 2000.0_rk) == 0.0_rk)
  ! eps_p = 0 with n < 1 gives the value A (the derivative would be infinite).
  call check_close('JC eps_p = 0 gives A', jc_yield(jc, 0.0_rk, 0.0_rk, 298.0_rk), &
      90.0e-5_rk, tol)
  values = jc_yield(jc, strains, 1.0e-3_rk, 500.0_rk)
  call check_true('JC Y rises with eps_p', all(values(2:8) > values(1:7)))
  values(1:5) = jc_yield(jc, 0.2_rk, 1.0e-3_rk, [300.0_rk, 500.0_rk, 800.0_rk, 1100.0_rk, &
      1300.0_rk])
  call check_true('JC Y falls with T', all(values(2:5) < values(1:4)))
  jc = jc_set('unobtainium')
  call check_true('JC unknown set is unset', jc%a == 0.0_rk .and. jc%b == 0.0_rk)

  ! (f) Temperature from energy; cv in Mbar cm^3/(g K) (1 J = 1e-5 Mbar cm^3).
  sg = sg_set('al6061')
  ! 900 J/g into Al at 0.9 J/(g K) heats it by 1000 K.
  call check_close('T from e (Al, 900 J/g)', temperature_from_energy(900.0e-5_rk, sg%cv, &
      300.0_rk), 1300.0_rk, tol)
  call check_close('T from e = 0', temperature_from_energy(0.0_rk, sg%cv, 300.0_rk), 300.0_rk, &
      tol)
  call check_close('cv Al 0.9 J/(g K)', sg%cv * 1.0e5_rk, 0.9_rk, tol)
  sg = sg_set('ss304')
  call check_close('cv SS 0.5 J/(g K)', sg%cv * 1.0e5_rk, 0.5_rk, tol)
  ! Heating Cu to just below melt through the energy removes most of its strength.
  sg = sg_set('cu_ofhc')
  call check_close('cv Cu 0.385 J/(g K)', sg%cv * 1.0e5_rk, 0.385_rk, tol)
  g_cold = sg_shear_modulus(sg, 0.0_rk, temperature_from_energy(0.0_rk, sg%cv, 300.0_rk), &
      1.0_rk)
  g_hot = sg_shear_modulus(sg, 0.0_rk, temperature_from_energy(sg%cv * 1400.0_rk, sg%cv, &
      300.0_rk), 1.0_rk)
  call check_close('SG Cu G at 1700 K', g_hot, g_cold * (1.0_rk - sg%b * 1400.0_rk), tol)
  y_previous = sg_yield(sg, 0.0_rk, 0.0_rk, 1789.0_rk, 1.0_rk)
  call check_true('SG Cu Y > 0 at 1789 K', y_previous > 0.0_rk)

  ! (g) The Taylor-fitted copper: Y0 = 0.00377 Mbar, beta = 1.6, the rest cu_ofhc's.
  sg = sg_set('cu_taylor')
  sg_shifted = sg_set('cu_ofhc')
  call check_close('cu_taylor Y0', sg%y0, 0.00377_rk, tol)
  call check_close('cu_taylor beta', sg%beta, 1.6_rk, tol)
  sg_shifted%y0 = sg%y0
  sg_shifted%beta = sg%beta
  call check_true('cu_taylor: other parameters those of cu_ofhc', &
      all([sg%g0, sg%ymax, sg%n, sg%eps_i, sg%a, sg%b, sg%tm0, sg%gamma0, sg%a_melt, sg%rho0, &
      sg%cv] == [sg_shifted%g0, sg_shifted%ymax, sg_shifted%n, sg_shifted%eps_i, sg_shifted%a, &
      sg_shifted%b, sg_shifted%tm0, sg_shifted%gamma0, sg_shifted%a_melt, sg_shifted%rho0, &
      sg_shifted%cv]))

  call check_summary()
end program test_material_flow_stress
