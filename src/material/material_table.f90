!> Material table: one entry per named material, with its equation of state.
!> A new EOS is a new kernel module plus one case in material_eos.
module material_table
  use core_kinds, only: rk
  use eos_ideal_gas, only: ideal_gas_pressure, ideal_gas_sound_speed, ideal_gas_energy
  use eos_mie_gruneisen, only: mie_gruneisen_t, mg_pressure, mg_sound_speed, &
      mg_energy_from_pressure
  use material_flow_stress, only: steinberg_guinan_t, johnson_cook_t, sg_shear_modulus, &
      sg_yield, jc_yield, temperature_from_energy, SG_REFERENCE_TEMPERATURE
  implicit none
  private
  public :: material_eos, material_energy_from_pressure, material_library, material_flow
  public :: material_library_source

  !> The built-in data sets, in the order `impact3d --materials` lists them.
  character(len=*), parameter, public :: LIBRARY_NAMES(9) = [character(len=12) :: 'al6061', &
      'cu_ofhc', 'cu_taylor', 'ss304', 'be_verney', 'wha', 'ti6al4v', 'steel_1006', 'steel_4340']
  !> The same as one line, for messages.
  character(len=*), parameter, public :: LIBRARY_LIST = 'al6061, cu_ofhc, cu_taylor, ss304, '// &
      'be_verney, wha, ti6al4v, steel_1006, steel_4340'

  integer, parameter, public :: EOS_IDEAL_GAS = 1, EOS_MIE_GRUNEISEN = 2
  integer, parameter, public :: STRENGTH_NONE = 0, STRENGTH_ELASTIC_PLASTIC = 1
  integer, parameter, public :: STRENGTH_STEINBERG_GUINAN = 2, STRENGTH_JOHNSON_COOK = 3
  integer, parameter, public :: MATERIAL_NAME_LEN = 32

  !> One material.
  type, public :: material_t
    character(len=MATERIAL_NAME_LEN) :: name = '' !< deck name
    character(len=MATERIAL_NAME_LEN) :: library = '' !< built-in data set, '' for none
    integer :: eos = EOS_IDEAL_GAS !< EOS_* code
    real(rk) :: gamma = 1.4_rk !< ideal gas: ratio of specific heats
    type(mie_gruneisen_t) :: mg = mie_gruneisen_t(rho0=0.0_rk, c0=0.0_rk, s1=0.0_rk, &
        gamma0=0.0_rk) !< Mie-Gruneisen data
    integer :: strength = STRENGTH_NONE !< STRENGTH_* model
    real(rk) :: shear_modulus = 0.0_rk !< G
    real(rk) :: yield_stress = huge(1.0_rk) !< Y, or Y0 with hardening (huge = elastic)
    real(rk) :: hardening_modulus = 0.0_rk !< H of elastic_plastic: Y = Y0 + H eps_p
    type(steinberg_guinan_t) :: sg !< Steinberg-Guinan data
    !> Steinberg-Guinan temperature from the energy above the cold compression
    !> energy (sg_temperature); false: from e itself, the default
    logical :: sg_cold_energy = .false.
    type(johnson_cook_t) :: jc !< Johnson-Cook data
  end type material_t

contains

  !> Pressure and sound speed of the zones in list(:) made of material mat.
  subroutine material_eos(mat, list, density, energy, pressure, sound_speed)
    type(material_t), intent(in) :: mat
    integer, intent(in) :: list(:) !< zones of this material
    real(rk), intent(in) :: density(:), energy(:)
    real(rk), intent(inout) :: pressure(:), sound_speed(:)
    integer :: i, z
    select case (mat%eos)
    case (EOS_IDEAL_GAS)
      do i = 1, size(list)
        z = list(i)
        pressure(z) = ideal_gas_pressure(mat%gamma, density(z), energy(z))
        sound_speed(z) = ideal_gas_sound_speed(mat%gamma, density(z), pressure(z))
      end do
    case (EOS_MIE_GRUNEISEN)
      do i = 1, size(list)
        z = list(i)
        pressure(z) = mg_pressure(mat%mg, density(z), energy(z))
        sound_speed(z) = mg_sound_speed(mat%mg, density(z), energy(z), pressure(z))
      end do
    end select
    ! With strength the signal speed is the longitudinal one, sqrt(c^2 + 4G/(3 rho)).
    if (mat%strength /= STRENGTH_NONE) then
      do i = 1, size(list)
        z = list(i)
        if (density(z) > 0.0_rk) sound_speed(z) = sqrt(sound_speed(z)**2 + &
            4.0_rk * shear_modulus(mat, pressure(z), energy(z), density(z)) &
            / (3.0_rk * density(z)))
      end do
    end if
  end subroutine material_eos

  !> Shear modulus of a zone: constant, or Steinberg-Guinan's G(p, T, rho).
  elemental function shear_modulus(mat, p, e, rho) result(g)
    type(material_t), intent(in) :: mat
    real(rk), intent(in) :: p, e, rho
    real(rk) :: g
    if (mat%strength == STRENGTH_STEINBERG_GUINAN) then
      g = sg_shear_modulus(mat%sg, p, sg_temperature(mat, e, rho), rho / mat%sg%rho0)
    else
      g = mat%shear_modulus
    end if
  end function shear_modulus

  !> Shear modulus and yield stress of a zone of material mat at pressure p,
  !> specific internal energy e (temperature T = T0 + e/cv, constant specific
  !> heat), density rho, plastic strain eps_p and equivalent strain rate rate,
  !> and the linear hardening modulus h the radial return must use (that of
  !> elastic_plastic; 0 for the other models, whose hardening is explicit in y).
  elemental subroutine material_flow(mat, p, e, rho, eps_p, rate, g, y, h)
    type(material_t), intent(in) :: mat
    real(rk), intent(in) :: p, e, rho, eps_p, rate
    real(rk), intent(out) :: g, y, h
    real(rk) :: temperature
    h = 0.0_rk
    select case (mat%strength)
    case (STRENGTH_STEINBERG_GUINAN)
      temperature = sg_temperature(mat, e, rho)
      g = sg_shear_modulus(mat%sg, p, temperature, rho / mat%sg%rho0)
      y = sg_yield(mat%sg, eps_p, p, temperature, rho / mat%sg%rho0)
    case (STRENGTH_JOHNSON_COOK)
      temperature = temperature_from_energy(max(e, 0.0_rk), mat%jc%cv, mat%jc%tr)
      g = mat%shear_modulus
      y = jc_yield(mat%jc, eps_p, rate, temperature)
    case (STRENGTH_ELASTIC_PLASTIC)
      g = mat%shear_modulus
      y = mat%yield_stress
      h = mat%hardening_modulus
      if (h > 0.0_rk) y = y + h * max(eps_p, 0.0_rk)
    case default
      g = mat%shear_modulus
      y = mat%yield_stress
    end select
  end subroutine material_flow

  !> Steinberg-Guinan temperature 300 K + e_th/cv. By default e_th = max(e, 0), the
  !> energy above the ambient state. With sg_cold_energy (Mie-Gruneisen materials)
  !> e_th = max(e - e_c(rho), 0) with the cold compression (or expansion) energy
  !> approximated by the energy on the linear Us-up Hugoniot,
  !>   e_c = c0^2 chi^2 / (2 (1 - s1 chi)^2), chi = 1 - rho0/rho,
  !> which is the energy of the isentrope through the ambient state to second
  !> order in chi (shock heating is third order); rho0 is the EOS's.
  elemental function sg_temperature(mat, e, rho) result(temperature)
    type(material_t), intent(in) :: mat
    real(rk), intent(in) :: e, rho
    real(rk) :: temperature
    real(rk) :: chi, e_cold
    if (mat%sg_cold_energy) then
      chi = 1.0_rk - mat%mg%rho0 / rho
      e_cold = 0.5_rk * (mat%mg%c0 * chi / (1.0_rk - mat%mg%s1 * chi))**2
      temperature = temperature_from_energy(max(e - e_cold, 0.0_rk), mat%sg%cv, &
          SG_REFERENCE_TEMPERATURE)
    else
      temperature = temperature_from_energy(max(e, 0.0_rk), mat%sg%cv, SG_REFERENCE_TEMPERATURE)
    end if
  end function sg_temperature

  !> Specific internal energy that gives pressure p at density rho.
  elemental function material_energy_from_pressure(mat, rho, p) result(e)
    type(material_t), intent(in) :: mat
    real(rk), intent(in) :: rho, p
    real(rk) :: e
    select case (mat%eos)
    case (EOS_IDEAL_GAS)
      e = ideal_gas_energy(mat%gamma, rho, p)
    case (EOS_MIE_GRUNEISEN)
      e = mg_energy_from_pressure(mat%mg, rho, p)
    case default
      e = 0.0_rk
    end select
  end function material_energy_from_pressure

  !> Built-in Mie-Gruneisen data (cm, g, us, Mbar) from Steinberg, UCRL-MA-106439,
  !> as tabulated in docs/problems.md: 'al6061' (Al 6061-T6), 'cu_ofhc'
  !> (OFHC copper), 'cu_taylor' (cu_ofhc's EOS and G0 with the yield stress Y0 fitted
  !> to the Taylor slow shot of Eakins & Thadhani, this project; see
  !> material_flow_stress, sg_set), 'ss304' (304 stainless steel: recalled values,
  !> still to be checked against a primary source), 'be_verney' (beryllium of the
  !> Verney problem), and the sets with values from several sources named at each
  !> ('wha', 'ti6al4v', 'steel_1006', 'steel_4340'; material_library_source).
  !> found is false for any other name.
  subroutine material_library(name, mg, shear, yield, found)
    character(len=*), intent(in) :: name
    type(mie_gruneisen_t), intent(inout) :: mg
    real(rk), intent(out) :: shear !< G0
    real(rk), intent(out) :: yield !< Y0
    logical, intent(out) :: found
    found = .true.
    select case (name)
    case ('al6061')
      mg = mie_gruneisen_t(rho0=2.703_rk, c0=0.524_rk, s1=1.40_rk, gamma0=1.97_rk, b=0.48_rk)
      shear = 0.276_rk
      yield = 0.0029_rk
    case ('cu_ofhc')
      mg = mie_gruneisen_t(rho0=8.93_rk, c0=0.394_rk, s1=1.489_rk, gamma0=2.02_rk, b=0.47_rk)
      shear = 0.477_rk
      yield = 0.0012_rk
    case ('cu_taylor')
      mg = mie_gruneisen_t(rho0=8.93_rk, c0=0.394_rk, s1=1.489_rk, gamma0=2.02_rk, b=0.47_rk)
      shear = 0.477_rk
      yield = 0.00377_rk
    case ('ss304')
      mg = mie_gruneisen_t(rho0=7.90_rk, c0=0.457_rk, s1=1.49_rk, gamma0=1.93_rk, b=0.5_rk)
      shear = 0.770_rk
      yield = 0.0034_rk
    case ('be_verney')
      mg = mie_gruneisen_t(rho0=1.845_rk, c0=0.800_rk, s1=1.124_rk, gamma0=1.11_rk, b=0.16_rk)
      shear = 1.51_rk
      yield = 0.0033_rk
    case ('wha')
      ! rho0: Johnson & Cook (1983), tungsten alloy (.07 Ni .03 Fe); c0, s1,
      ! gamma0: Steinberg's pure tungsten (recalled, not the alloy's); no
      ! shear modulus (give shear_modulus); Y0 = the Johnson-Cook A.
      mg = mie_gruneisen_t(rho0=17.0_rk, c0=0.403_rk, s1=1.237_rk, gamma0=1.67_rk, b=0.0_rk)
      shear = 0.0_rk
      yield = 0.01506_rk
    case ('ti6al4v')
      ! rho0, c0, s1: Marsh (1980), LASL Shock Hugoniot Data; gamma0, G0, Y0:
      ! Steinberg, UCRL-MA-106439 (recalled, unverified); b = 0 (not recalled).
      mg = mie_gruneisen_t(rho0=4.419_rk, c0=0.513_rk, s1=1.028_rk, gamma0=1.23_rk, b=0.0_rk)
      shear = 0.419_rk
      yield = 0.0133_rk
    case ('steel_1006')
      ! rho0: Johnson & Cook (1983), 1006 steel; c0, s1, gamma0: the values in
      ! common use for mild steel (primary source unconfirmed); G = 0.80 Mbar
      ! (E = 207 GPa, nu = 0.29, handbook); Y0 = the Johnson-Cook A.
      mg = mie_gruneisen_t(rho0=7.89_rk, c0=0.4569_rk, s1=1.49_rk, gamma0=2.17_rk, b=0.0_rk)
      shear = 0.80_rk
      yield = 0.0035_rk
    case ('steel_4340')
      ! VAR 4340 at Rc 38, the rods of Piekutowski et al. (1999): rho0 their
      ! 7830 kg/m^3; c0 = sqrt(K/rho0) and G from handbook E = 205 GPa, nu =
      ! 0.29; gamma0 = 3 alpha K/(rho0 cp) with alpha = 12.3e-6 /K, cp = 477
      ! J/(kg K); s1 the steels' recalled Hugoniot slope (unverified); b = 0;
      ! Y0 = the rods' yield, 1140 MPa (= the Johnson-Cook A of jc_set).
      mg = mie_gruneisen_t(rho0=7.83_rk, c0=0.4558_rk, s1=1.49_rk, gamma0=1.61_rk, b=0.0_rk)
      shear = 0.795_rk
      yield = 0.0114_rk
    case default
      found = .false.
      shear = 0.0_rk
      yield = 0.0_rk
    end select
  end subroutine material_library

  !> Where a built-in data set's values come from, value by value (also in
  !> docs/problems.md, "Material data"); '' for an unknown name.
  function material_library_source(name) result(text)
    character(len=*), intent(in) :: name
    character(len=:), allocatable :: text
    select case (name)
    case ('al6061')
      text = 'Steinberg, UCRL-MA-106439 (1991, Change 1 1996), EOS and Steinberg-Guinan rows; '// &
          'checked against a published transcription of the report. Johnson-Cook A = 324, '// &
          'B = 114 MPa, n = 0.42, C = 0.002, m = 1.34, Tm = 925 K: the 6061-T6 set of the '// &
          'secondary literature (recalled; no primary source reached); cp 0.90 J/(g K) (CRC, Al)'
    case ('cu_ofhc')
      text = 'Steinberg, UCRL-MA-106439 (1991, Change 1 1996), EOS and Steinberg-Guinan rows; '// &
          'checked against a published transcription of the report'
    case ('cu_taylor')
      text = 'cu_ofhc (Steinberg, UCRL-MA-106439) with Y0 = 0.00377 Mbar and beta = 1.6 '// &
          'fitted to the Taylor slow shot of Eakins & Thadhani (this project)'
    case ('ss304')
      text = 'Steinberg, UCRL-MA-106439 and Steinberg, Cochran & Guinan, J. Appl. Phys. 51 '// &
          '(1980) 1498: recalled values, not checked against a copy of either; c0 and s1 '// &
          'agree with the recalled Marsh (1980) 304 SS fit'
    case ('be_verney')
      text = 'Verney problem: rho0, G0, Y0 as used by Verney; the rest recalled from '// &
          'Steinberg, UCRL-MA-106439, unverified'
    case ('wha')
      text = 'rho0, Johnson-Cook A, B, n, C, m, Tm, cp: Johnson & Cook (1983), tungsten '// &
          'alloy .07Ni .03Fe (recalled, unverified); c0, s1, gamma0: Steinberg''s pure '// &
          'tungsten (recalled, not alloy data); no shear modulus'
    case ('ti6al4v')
      text = 'rho0, c0, s1: Marsh (1980), LASL Shock Hugoniot Data (recalled, unverified); '// &
          'gamma0, G0, Y0: Steinberg, UCRL-MA-106439 (recalled, unverified); b = 0'
    case ('steel_1006')
      text = 'rho0, Johnson-Cook A, B, n, C, m, Tm, cp: Johnson & Cook (1983), 1006 steel '// &
          '(recalled, unverified); c0, s1, gamma0: values in common use for mild steel '// &
          '(primary source unconfirmed); G: E = 207 GPa, nu = 0.29 (handbook)'
    case ('steel_4340')
      text = 'VAR 4340, Rc 38 (Piekutowski et al. 1999 rods): rho0 7830 kg/m^3 and Y0 = '// &
          'Johnson-Cook A = 1140 MPa from that paper; c0 = sqrt(K/rho0), G = 79.5 GPa and '// &
          'gamma0 = 3 alpha K/(rho0 cp) = 1.61 derived from handbook E = 205 GPa, nu = 0.29, '// &
          'alpha = 12.3e-6/K, cp = 477 J/(kg K); s1 = 1.49: the steels'' Hugoniot slope '// &
          '(recalled Marsh 1980 fits, unverified); b = 0; Johnson-Cook B = 510 MPa, n = 0.26, '// &
          'C = 0.014, m = 1.03, Tm = 1793 K, cp: Johnson & Cook (1983/1985) 4340 at Rc 30 '// &
          '(recalled, unverified), A raised to the Rc 38 yield'
    case default
      text = ''
    end select
  end function material_library_source

end module material_table
