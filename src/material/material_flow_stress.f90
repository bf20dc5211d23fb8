!> Flow-stress and shear-modulus kernels: the Steinberg-Guinan model and the
!> Johnson-Cook model, with named parameter sets. Pure/elemental, no MPI, no I/O.
!> Units cm, g, us, Mbar (1 Mbar = 1e5 MPa, 1 J = 1e-5 Mbar cm^3), temperature K.
!>
!> Steinberg-Guinan, from D. J. Steinberg, S. G. Cochran and M. W. Guinan,
!> J. Appl. Phys. 51, 1498 (1980), and D. J. Steinberg, UCRL-MA-106439
!> "Equation of state and strength properties of selected materials" (LLNL):
!>   G = G0 [1 + A p eta^(-1/3) - B (T - 300)]
!>   Y = min(Y0 [1 + beta (eps_p + eps_i)]^n, Ymax) [1 + A p eta^(-1/3) - B (T - 300)]
!>   Tm = Tm0 exp(2 a (1 - 1/eta)) eta^(2 (gamma0 - a - 1/3)), eta = rho/rho0
!> with A = G'_p/G0, B = -G'_T/G0, and G = Y = 0 at or above melt (T >= Tm). The
!> yield's pressure and temperature factor is that of G because Steinberg takes
!> Y'_p/Y0 = G'_p/G0, so Y = Y0 f(eps) G/G0. The melt law is Lindemann's with
!> gamma = gamma0 - a (1 - rho0/rho): 'a' is Steinberg's first-order volume
!> correction to the Grueneisen gamma, tabulated in his strength table next to
!> Tm0 and gamma0. It is not the 'b' of his Mie-Grueneisen EOS (the column b of
!> the table in docs/problems.md): his EOS has gamma(rho) = (gamma0 + b mu) rho0/rho, mu = eta - 1,
!> whose first-order volume coefficient is gamma0 - b, and his tabulated a is that
!> value rounded (Cu 2.02 - 0.47 = 1.55 ~ 1.5, Al 1.97 - 0.48 = 1.49 ~ 1.5).
!>
!> Pressure: Steinberg's G and Y use the signed pressure p (no max(p, 0); some
!> codes add one, e.g. IMPETUS Afea's *MAT_STEINBERG_GUINAN). We follow Steinberg,
!> so tension lowers G a little, and clip the factor at zero so that no pressure
!> can make G or Y negative (only reached at p < -eta^(1/3)/A, e.g. -0.15 Mbar in Al,
!> far beyond spall).
!>
!> Temperature: Steinberg takes T from the energy above the cold curve with a
!> Dulong-Petit heat capacity. Here T = 300 K + e/cv with a constant specific heat
!> cv (Mbar cm^3/(g K)) and e the specific internal energy measured from the
!> ambient state; by default the cold-compression energy is not subtracted, which
!> slightly overestimates T under strong compression (material_table subtracts an
!> approximation of it when a material asks, with sg_cold_energy).
!>
!> Johnson-Cook, from G. R. Johnson and W. H. Cook, Proc. 7th Int. Symp. on
!> Ballistics, The Hague, 1983, pp. 541-547:
!>   Y = (A + B eps_p^n) (1 + C ln(max(eps_dot/eps_dot0, 1))) (1 - T*^m),
!>   T* = (T - Tr)/(Tm - Tr) clipped to [0, 1].
!> eps_p^n at eps_p = 0 with n < 1 is 0, but its derivative is infinite: these
!> kernels return values only.
module material_flow_stress
  use core_kinds, only: rk
  implicit none
  private
  public :: sg_shear_modulus, sg_yield, sg_melt_temperature, sg_set
  public :: jc_yield, jc_set, temperature_from_energy

  !> Steinberg's reference temperature (K) of G0 and Y0.
  real(rk), parameter, public :: SG_REFERENCE_TEMPERATURE = 300.0_rk
  !> Names accepted by sg_set.
  character(len=*), parameter, public :: SG_SET_NAMES = 'al6061, cu_ofhc, cu_taylor, ss304'
  !> Names accepted by jc_set.
  character(len=*), parameter, public :: JC_SET_NAMES = 'al6061, cu_ofhc, wha, steel_1006, '// &
      'steel_4340'

  !> Steinberg-Guinan parameters (cm-g-us-Mbar, K). The defaults mean unset.
  type, public :: steinberg_guinan_t
    real(rk) :: g0 = 0.0_rk !< shear modulus at 300 K, p = 0 (Mbar)
    real(rk) :: y0 = 0.0_rk !< yield stress at 300 K, p = 0, eps_p = 0 (Mbar)
    real(rk) :: ymax = 0.0_rk !< cap on the work-hardened yield Y0 f(eps) (Mbar)
    real(rk) :: beta = 0.0_rk !< work-hardening coefficient
    real(rk) :: n = 0.0_rk !< work-hardening exponent
    real(rk) :: eps_i = 0.0_rk !< initial equivalent plastic strain
    real(rk) :: a = 0.0_rk !< A = G'_p/G0 (1/Mbar)
    real(rk) :: b = 0.0_rk !< B = -G'_T/G0 (1/K)
    real(rk) :: tm0 = 0.0_rk !< melt temperature at rho = rho0 (K)
    real(rk) :: gamma0 = 0.0_rk !< Grueneisen gamma at rho0 (melt law)
    real(rk) :: a_melt = 0.0_rk !< Steinberg's melt-law a, volume coefficient of gamma
    real(rk) :: rho0 = 0.0_rk !< reference density (g/cm^3)
    real(rk) :: cv = 0.0_rk !< constant specific heat (Mbar cm^3/(g K))
  end type steinberg_guinan_t

  !> Johnson-Cook parameters (cm-g-us-Mbar, K). Tm > Tr and eps_dot0 > 0 are required.
  type, public :: johnson_cook_t
    real(rk) :: a = 0.0_rk !< yield stress at eps_p = 0 (Mbar)
    real(rk) :: b = 0.0_rk !< hardening modulus (Mbar)
    real(rk) :: n = 0.0_rk !< hardening exponent
    real(rk) :: c = 0.0_rk !< strain-rate coefficient
    real(rk) :: m = 0.0_rk !< thermal-softening exponent
    real(rk) :: tm = 0.0_rk !< melt temperature (K)
    real(rk) :: tr = 298.0_rk !< reference (room) temperature (K)
    real(rk) :: eps_dot0 = 1.0e-6_rk !< reference plastic strain rate (1/us; 1e-6 = 1/s)
    real(rk) :: cv = 0.0_rk !< constant specific heat (Mbar cm^3/(g K))
    real(rk) :: rho0 = 0.0_rk !< reference density (g/cm^3)
  end type johnson_cook_t

contains

  !> Temperature T0 + e/cv from specific internal energy e with a constant specific heat.
  elemental function temperature_from_energy(e, cv, t0) result(temperature)
    real(rk), intent(in) :: e !< specific internal energy above the state at T0 (Mbar cm^3/g)
    real(rk), intent(in) :: cv !< specific heat, > 0 (Mbar cm^3/(g K))
    real(rk), intent(in) :: t0 !< temperature at e = 0 (K)
    real(rk) :: temperature

    temperature = t0 + e / cv
  end function temperature_from_energy

  !> Steinberg-Guinan melt temperature Tm0 exp(2a(1 - 1/eta)) eta^(2(gamma0 - a - 1/3)).
  elemental function sg_melt_temperature(m, eta) result(tm)
    type(steinberg_guinan_t), intent(in) :: m
    real(rk), intent(in) :: eta !< compression rho/rho0, > 0
    real(rk) :: tm

    tm = m%tm0 * exp(2.0_rk * m%a_melt * (1.0_rk - 1.0_rk / eta)) &
        * eta**(2.0_rk * (m%gamma0 - m%a_melt - 1.0_rk / 3.0_rk))
  end function sg_melt_temperature

  !> Steinberg-Guinan shear modulus G0 [1 + A p eta^(-1/3) - B (T - 300)]; zero at or
  !> above melt and never negative.
  elemental function sg_shear_modulus(m, p, temperature, eta) result(g)
    type(steinberg_guinan_t), intent(in) :: m
    real(rk), intent(in) :: p !< pressure, signed (Mbar)
    real(rk), intent(in) :: temperature !< K
    real(rk), intent(in) :: eta !< compression rho/rho0, > 0
    real(rk) :: g

    g = m%g0 * sg_softening(m, p, temperature, eta)
  end function sg_shear_modulus

  !> Steinberg-Guinan yield stress min(Y0 [1 + beta (eps_p + eps_i)]^n, Ymax) G/G0;
  !> zero at or above melt.
  elemental function sg_yield(m, eps_p, p, temperature, eta) result(y)
    type(steinberg_guinan_t), intent(in) :: m
    real(rk), intent(in) :: eps_p !< equivalent plastic strain (negative taken as 0)
    real(rk), intent(in) :: p !< pressure, signed (Mbar)
    real(rk), intent(in) :: temperature !< K
    real(rk), intent(in) :: eta !< compression rho/rho0, > 0
    real(rk) :: y
    real(rk) :: hardened

    hardened = m%y0 * (1.0_rk + m%beta * (max(eps_p, 0.0_rk) + m%eps_i))**m%n
    y = min(hardened, m%ymax) * sg_softening(m, p, temperature, eta)
  end function sg_yield

  !> The factor G/G0 = max(1 + A p eta^(-1/3) - B (T - 300), 0), or 0 at or above melt.
  elemental function sg_softening(m, p, temperature, eta) result(factor)
    type(steinberg_guinan_t), intent(in) :: m
    real(rk), intent(in) :: p, temperature, eta
    real(rk) :: factor

    if (temperature >= sg_melt_temperature(m, eta)) then
      factor = 0.0_rk
    else
      factor = max(1.0_rk + m%a * p / eta**(1.0_rk / 3.0_rk) &
          - m%b * (temperature - SG_REFERENCE_TEMPERATURE), 0.0_rk)
    end if
  end function sg_softening

  !> Named Steinberg-Guinan set: 'al6061' (Al 6061-T6), 'cu_ofhc' (OFHC copper),
  !> 'cu_taylor' (the copper of the Taylor rods of Eakins & Thadhani), 'ss304' (304
  !> stainless steel). Any other name gives the unset default (g0 = 0); valid names
  !> are SG_SET_NAMES.
  !>
  !> G0, Y0, Ymax, beta, n, A, B, Tm0, rho0 and gamma0 are the table of docs/problems.md
  !> (Steinberg, UCRL-MA-106439). The Al and Cu strength rows, and a_melt = 1.5 for
  !> both, agree with the transcription of UCRL-MA-106439 (Change 1, 1996) in the
  !> Uintah MPM material files (SCG_Aluminum6061-T6.xml, SCG_CopperOFHC.xml). The
  !> 304 SS row is recalled, not checked against a primary source; its a_melt =
  !> gamma0 - b = 1.93 - 0.5 = 1.43 is derived from the EOS (see the module header),
  !> not a tabulated value. cv: constant room-temperature specific heats, Al 0.90,
  !> Cu 0.385 (CRC Handbook values for the pure metals, 0.897 and 0.385 J/(g K)) and
  !> 304 SS 0.50 J/(g K) (typical data-sheet value), times 1e-5 Mbar cm^3/J.
  !>
  !> 'cu_taylor': fitted to the Taylor slow shot of Eakins & Thadhani (J. Appl. Phys.
  !> 100, 073503 (2006): rod 1.91 cm x 7.51 cm at 0.0083 cm/us, final length 7.03 cm
  !> and foot diameter 2.36 cm, as tabulated by Jia et al., J. Comput. Phys. 267
  !> (2014)), this project: Y0 = 0.00377 Mbar and beta = 1.6 fitted (Newton on the
  !> final length and foot diameter, rigid wall, coarse mesh of problems/taylor;
  !> docs/verification-solids.md), every other parameter cu_ofhc's. Their rods behave
  !> like cold-worked copper: a high initial yield and little further hardening.
  pure function sg_set(name) result(m)
    character(len=*), intent(in) :: name !< set name, one of SG_SET_NAMES
    type(steinberg_guinan_t) :: m

    select case (name)
    case ('al6061')
      m = steinberg_guinan_t(g0=0.276_rk, y0=0.0029_rk, ymax=0.0068_rk, beta=125.0_rk, &
          n=0.10_rk, eps_i=0.0_rk, a=6.52_rk, b=6.16e-4_rk, tm0=1220.0_rk, gamma0=1.97_rk, &
          a_melt=1.5_rk, rho0=2.703_rk, cv=0.90e-5_rk)
    case ('cu_ofhc')
      m = steinberg_guinan_t(g0=0.477_rk, y0=0.0012_rk, ymax=0.0064_rk, beta=36.0_rk, &
          n=0.45_rk, eps_i=0.0_rk, a=2.83_rk, b=3.77e-4_rk, tm0=1790.0_rk, gamma0=2.02_rk, &
          a_melt=1.5_rk, rho0=8.93_rk, cv=0.385e-5_rk)
    case ('cu_taylor')
      m = steinberg_guinan_t(g0=0.477_rk, y0=0.00377_rk, ymax=0.0064_rk, beta=1.6_rk, &
          n=0.45_rk, eps_i=0.0_rk, a=2.83_rk, b=3.77e-4_rk, tm0=1790.0_rk, gamma0=2.02_rk, &
          a_melt=1.5_rk, rho0=8.93_rk, cv=0.385e-5_rk)
    case ('ss304')
      m = steinberg_guinan_t(g0=0.770_rk, y0=0.0034_rk, ymax=0.0250_rk, beta=43.0_rk, &
          n=0.35_rk, eps_i=0.0_rk, a=2.26_rk, b=4.55e-4_rk, tm0=2380.0_rk, gamma0=1.93_rk, &
          a_melt=1.43_rk, rho0=7.90_rk, cv=0.50e-5_rk)
    case default
      m = steinberg_guinan_t()
    end select
  end function sg_set

  !> Johnson-Cook yield (A + B eps_p^n)(1 + C ln(max(eps_dot/eps_dot0, 1)))(1 - T*^m),
  !> T* = (T - Tr)/(Tm - Tr) clipped to [0, 1]; zero at or above Tm.
  elemental function jc_yield(m, eps_p, eps_dot_p, temperature) result(y)
    type(johnson_cook_t), intent(in) :: m
    real(rk), intent(in) :: eps_p !< equivalent plastic strain (negative taken as 0)
    real(rk), intent(in) :: eps_dot_p !< equivalent plastic strain rate (1/us)
    real(rk), intent(in) :: temperature !< K
    real(rk) :: y
    real(rk) :: homologous

    homologous = min(max((temperature - m%tr) / (m%tm - m%tr), 0.0_rk), 1.0_rk)
    y = (m%a + m%b * max(eps_p, 0.0_rk)**m%n) &
        * (1.0_rk + m%c * log(max(eps_dot_p / m%eps_dot0, 1.0_rk))) &
        * (1.0_rk - homologous**m%m)
  end function jc_yield

  !> Named Johnson-Cook set: 'cu_ofhc' (OFHC copper, Johnson & Cook 1983: A = 90 MPa,
  !> B = 292 MPa, n = 0.31, C = 0.025, m = 1.09, Tm = 1356 K, with their reference
  !> rate 1/s, density 8.96 g/cm^3 and specific heat 383 J/(kg K)), 'wha', 'steel_1006',
  !> 'al6061' (6061-T6) and 'steel_4340' (VAR 4340 at Rc 38), sources at each case and
  !> in docs/problems.md. Any other name gives the unset default (a = b = 0); valid
  !> names are JC_SET_NAMES.
  pure function jc_set(name) result(m)
    character(len=*), intent(in) :: name !< set name, one of JC_SET_NAMES
    type(johnson_cook_t) :: m

    select case (name)
    case ('cu_ofhc')
      m = johnson_cook_t(a=90.0e-5_rk, b=292.0e-5_rk, n=0.31_rk, c=0.025_rk, m=1.09_rk, &
          tm=1356.0_rk, tr=298.0_rk, eps_dot0=1.0e-6_rk, cv=0.383e-5_rk, rho0=8.96_rk)
    case ('wha')
      ! Johnson & Cook (1983), tungsten alloy (.07 Ni .03 Fe): recalled values.
      m = johnson_cook_t(a=1506.0e-5_rk, b=177.0e-5_rk, n=0.12_rk, c=0.016_rk, m=1.00_rk, &
          tm=1723.0_rk, tr=298.0_rk, eps_dot0=1.0e-6_rk, cv=0.134e-5_rk, rho0=17.0_rk)
    case ('steel_1006')
      ! Johnson & Cook (1983), 1006 steel: recalled values.
      m = johnson_cook_t(a=350.0e-5_rk, b=275.0e-5_rk, n=0.36_rk, c=0.022_rk, m=1.00_rk, &
          tm=1811.0_rk, tr=298.0_rk, eps_dot0=1.0e-6_rk, cv=0.452e-5_rk, rho0=7.89_rk)
    case ('al6061')
      ! 6061-T6: the set of the secondary literature (A = 324 MPa, B = 114 MPa,
      ! n = 0.42, C = 0.002, m = 1.34, Tm = 925 K; recalled, no primary source
      ! reached), cv and rho0 those of sg_set('al6061').
      m = johnson_cook_t(a=324.0e-5_rk, b=114.0e-5_rk, n=0.42_rk, c=0.002_rk, m=1.34_rk, &
          tm=925.0_rk, tr=298.0_rk, eps_dot0=1.0e-6_rk, cv=0.90e-5_rk, rho0=2.703_rk)
    case ('steel_4340')
      ! VAR 4340 at Rc 38 (the rods of Piekutowski et al. 1999): A = their yield,
      ! 1140 MPa; B, n, C, m, Tm and cp of Johnson & Cook's 4340 at Rc 30 (B = 510
      ! MPa, n = 0.26, C = 0.014, m = 1.03, Tm = 1793 K, 477 J/(kg K); recalled).
      m = johnson_cook_t(a=1140.0e-5_rk, b=510.0e-5_rk, n=0.26_rk, c=0.014_rk, m=1.03_rk, &
          tm=1793.0_rk, tr=298.0_rk, eps_dot0=1.0e-6_rk, cv=0.477e-5_rk, rho0=7.83_rk)
    case default
      m = johnson_cook_t()
    end select
  end function jc_set

end module material_flow_stress
