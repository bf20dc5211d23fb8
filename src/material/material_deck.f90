!> The material package's deck groups, each key declared once in its table
!> (core_keys) next to the group's reader: &material (material_table's
!> material_t) and &block (block_spec_t: where each material is). io_deck has
!> checked the key names and value types and hands each reader the group's
!> text; the reader does the namelist read and the checks of the values.
module material_deck
  use core_kinds, only: rk
  use core_status, only: status_t
  use core_text, only: to_lower
  use core_names, only: name_hint
  use core_text, only: to_text
  use core_unit_checks, only: DENSITY_FACTOR, brief_text, density_ratio_text, density_mistake
  use core_keys, only: UNSET, key_t, KEY_LEN
  use core_units, only: UNITS_SI, UNITS_NONE, SI_DENSITY, SI_VELOCITY, SI_PRESSURE, &
      SI_SPECIFIC_ENERGY, SI_TIME
  use mesh_global, only: NAME_LEN
  use material_table, only: material_t, EOS_IDEAL_GAS, EOS_MIE_GRUNEISEN, material_library, &
      STRENGTH_NONE, STRENGTH_ELASTIC_PLASTIC, STRENGTH_STEINBERG_GUINAN, STRENGTH_JOHNSON_COOK, &
      LIBRARY_NAMES
  use material_flow_stress, only: sg_set, jc_set, SG_SET_NAMES, JC_SET_NAMES
  use material_failure, only: failure_t, erosion_spec_t, failure_model_new, FAILURE_NAMES
  implicit none
  private
  public :: read_material, check_material_names, read_block, read_erosion

  !> A block: zones whose centroid lies in box, made of one material.
  type, public :: block_spec_t
    character(len=NAME_LEN) :: name = ''
    integer :: material = 0 !< index into config%materials
    real(rk) :: box(6) = [-huge(1.0_rk), huge(1.0_rk), -huge(1.0_rk), huge(1.0_rk), &
        -huge(1.0_rk), huge(1.0_rk)]
  end type block_spec_t

  !> &material: equation of state and strength model.
  type(key_t), parameter, public :: MATERIAL_KEYS(38) = [ &
      key_t("name", "c", "required", "", &
      "name used by &block"), &
      key_t("eos", "c", "required", "", &
      "equation of state: 'ideal_gas' or 'mie_gruneisen'"), &
      key_t("gamma", "r", "required for ideal_gas", "", &
      "ratio of specific heats, > 1"), &
      key_t("library", "c", "''", "", &
      "built-in data set; impact3d --materials lists them with their values and sources"), &
      key_t("rho0", "r", "from library", "density", &
      "reference density"), &
      key_t("c0", "r", "from library", "velocity", &
      "bulk sound speed (Us = c0 + s1 up)"), &
      key_t("s1", "r", "from library", "", &
      "Hugoniot slope, >= 1"), &
      key_t("gamma0", "r", "from library", "", &
      "Gruneisen coefficient at rho0"), &
      key_t("b", "r", "from library, else 0", "", &
      "first-order volume correction: rho Gamma = rho0 (gamma0 + b mu), in [0, gamma0)"), &
      key_t("p_min", "r", "none", "pressure", &
      "pressure cut-off (spall), <= 0"), &
      key_t("strength", "c", "'none'", "", &
      "'none', 'elastic_plastic', 'steinberg_guinan' or 'johnson_cook'"), &
      key_t("shear_modulus", "r", "from library", "pressure", &
      "shear modulus G (G0 at 300 K and p = 0 for Steinberg-Guinan), > 0"), &
      key_t("yield_stress", "r", "from library", "pressure", &
      "yield stress Y0 of elastic_plastic and steinberg_guinan, > 0"), &
      key_t("hardening_modulus", "r", "0", "pressure", &
      "elastic_plastic: linear isotropic hardening modulus H, >= 0"), &
      key_t("cv", "r", "from library", "specific_energy/K", &
      "steinberg_guinan, johnson_cook: constant specific heat, > 0"), &
      key_t("jc_a", "r", "from library", "pressure", &
      "johnson_cook: A, yield stress at eps_p = 0 (Mbar), > 0"), &
      key_t("jc_b", "r", "from library", "pressure", &
      "johnson_cook: B, hardening modulus (Mbar), >= 0"), &
      key_t("jc_n", "r", "from library", "", &
      "johnson_cook: n, hardening exponent, >= 0"), &
      key_t("jc_c", "r", "from library", "", &
      "johnson_cook: C, strain-rate coefficient, >= 0"), &
      key_t("jc_m", "r", "from library", "", &
      "johnson_cook: m, thermal-softening exponent, > 0"), &
      key_t("eps_dot0", "r", "from library, else 1e-6", "1/time", &
      "johnson_cook: reference plastic strain rate, > 0"), &
      key_t("t_room", "r", "from library, else 298", "K", &
      "johnson_cook: room (reference) temperature Tr (K), > 0"), &
      key_t("t_melt", "r", "from library", "K", &
      "johnson_cook: melt temperature Tm (K), > t_room"), &
      key_t("sg_beta", "r", "from library", "", &
      "steinberg_guinan: beta, work-hardening coefficient, >= 0"), &
      key_t("sg_n", "r", "from library", "", &
      "steinberg_guinan: n, work-hardening exponent, >= 0"), &
      key_t("sg_ymax", "r", "from library", "pressure", &
      "steinberg_guinan: Ymax, cap on the work-hardened yield, >= yield_stress"), &
      key_t("sg_eps_i", "r", "from library, else 0", "", &
      "steinberg_guinan: initial equivalent plastic strain eps_i, >= 0"), &
      key_t("sg_a", "r", "from library", "1/pressure", &
      "steinberg_guinan: A = G'_p/G0, pressure coefficient of G and Y (1/Mbar), >= 0"), &
      key_t("sg_b", "r", "from library", "1/K", &
      "steinberg_guinan: B = -G'_T/G0, temperature coefficient of G and Y (1/K), >= 0"), &
      key_t("sg_tmelt0", "r", "from library", "K", &
      "steinberg_guinan: melt temperature Tm0 at rho0 (K), > 300"), &
      key_t("sg_gamma0", "r", "gamma0", "", &
      "steinberg_guinan: Gruneisen gamma0 of the melt law, > 0"), &
      key_t("sg_a_melt", "r", "from library", "", &
      "steinberg_guinan: Steinberg's a of the melt law, >= 0"), &
      key_t("sg_cold_energy", "l", ".false.", "", &
      "steinberg_guinan: temperature from the energy above the cold compression energy"), &
      key_t("failure", "c", "none", "", &
      "damage model: 'johnson_cook' or 'plastic_strain' (needs a strength model)"), &
      key_t("jc_damage", "r", "required for failure = 'johnson_cook'", "", &
      "Johnson-Cook damage D1..D5: eps_f = [D1 + D2 exp(D3 s*)][1 + D4 ln e*][1 + D5 T*]"), &
      key_t("failure_strain", "r", "required for failure = 'plastic_strain'", "", &
      "equivalent plastic strain at failure, > 0"), &
      key_t("spall_strength", "r", "none", "pressure", &
      "a zone whose pressure falls below -spall_strength fails, > 0"), &
      key_t("erode", "l", ".false.", "", &
      "a failed zone is eroded (else it stays, with no shear stress and no tension)")]

  !> &erosion: distortion erosion (optional, at most one group).
  type(key_t), parameter, public :: EROSION_KEYS(3) = [ &
      key_t("volume_ratio", "r", "0 (off)", "", &
      "erode a zone whose V/V0 falls below this, in [0, 1)"), &
      key_t("dt_fraction", "r", "0 (off)", "", &
      "erode a zone whose own stable step is below this fraction of the first step, [0, 1)"), &
      key_t("blocks", "c", "all", "", &
      "comma-separated block names the distortion erosion applies to")]

  !> &block: the zones of one material.
  type(key_t), parameter, public :: BLOCK_KEYS(3) = [ &
      key_t("name", "c", "required", "", &
      "block name"), &
      key_t("material", "c", "required", "", &
      "a &material name"), &
      key_t("box", "r", "everything", "length", &
      "xmin, xmax, ymin, ymax, zmin, zmax: zones whose centroid is inside")]

contains

  !> The index-th &material into mat: library data (converted to the deck's
  !> units), then the keys given, then the checks of the EOS and strength model.
  subroutine read_material(sect, index, mat, status, read_ok, units, fail)
    use material_flow_stress, only: steinberg_guinan_t, johnson_cook_t, SG_REFERENCE_TEMPERATURE
    character(len=*), intent(in) :: sect(:) !< the group's text (io_deck: unknown keys blanked)
    integer, intent(in) :: index
    type(material_t), intent(inout) :: mat
    type(status_t), intent(inout) :: status
    logical, intent(inout) :: read_ok !< set false when the group cannot be read
    character(len=*), intent(in) :: units !< &control units: library data are converted to it
    type(failure_t), intent(inout), optional :: fail !< the failure keys (absent: not read)
    character(len=*), parameter :: SG_LIBS = ' (or a library with Steinberg-Guinan data: '// &
        SG_SET_NAMES//')'
    character(len=*), parameter :: JC_LIBS = ' (or a library with Johnson-Cook data: '// &
        JC_SET_NAMES//')'
    character(len=*), parameter :: ANY_LIB = ' (or give library)'
    character(len=NAME_LEN) :: name, library
    character(len=32) :: eos, strength
    real(rk) :: gamma, rho0, c0, s1, gamma0, b, p_min, shear_modulus, yield_stress
    real(rk) :: hardening_modulus, cv
    real(rk) :: jc_a, jc_b, jc_n, jc_c, jc_m, eps_dot0, t_room, t_melt
    real(rk) :: sg_beta, sg_n, sg_ymax, sg_eps_i, sg_a, sg_b, sg_tmelt0, sg_gamma0, sg_a_melt
    real(rk) :: lib_shear, lib_yield
    character(len=32) :: failure
    real(rk) :: jc_damage(5), failure_strain, spall_strength
    logical :: erode
    integer :: ios
    logical :: found, sg_cold_energy, rho0_refused
    character(len=256) :: msg
    character(len=16) :: where
    namelist /material/ name, eos, gamma, library, rho0, c0, s1, gamma0, b, p_min, strength, &
        shear_modulus, yield_stress, hardening_modulus, cv, jc_a, jc_b, jc_n, jc_c, jc_m, &
        eps_dot0, t_room, t_melt, sg_beta, sg_n, sg_ymax, sg_eps_i, sg_a, sg_b, sg_tmelt0, &
        sg_gamma0, sg_a_melt, sg_cold_energy, failure, jc_damage, failure_strain, &
        spall_strength, erode

    write(where, '(a,i0,a)') '&material(', index, ')'
    name = ''
    eos = ''
    library = ''
    gamma = UNSET
    rho0 = UNSET
    c0 = UNSET
    s1 = UNSET
    gamma0 = UNSET
    b = UNSET
    p_min = UNSET
    strength = 'none'
    shear_modulus = UNSET
    yield_stress = UNSET
    hardening_modulus = UNSET
    cv = UNSET
    jc_a = UNSET
    jc_b = UNSET
    jc_n = UNSET
    jc_c = UNSET
    jc_m = UNSET
    eps_dot0 = UNSET
    t_room = UNSET
    t_melt = UNSET
    sg_beta = UNSET
    sg_n = UNSET
    sg_ymax = UNSET
    sg_eps_i = UNSET
    sg_a = UNSET
    sg_b = UNSET
    sg_tmelt0 = UNSET
    sg_gamma0 = UNSET
    sg_a_melt = UNSET
    sg_cold_energy = .false.
    failure = 'none'
    jc_damage = UNSET
    failure_strain = UNSET
    spall_strength = UNSET
    erode = .false.
    lib_shear = UNSET
    lib_yield = UNSET
    read(sect, nml=material, iostat=ios, iomsg=msg)
    if (ios /= 0) then
      call status%add(trim(where)//': cannot read the group: '//trim(msg))
      read_ok = .false.
      return
    end if
    if (len_trim(name) == 0) call status%add(trim(where)//': name: required')
    mat%name = name
    mat%library = to_lower(library)
    select case (to_lower(eos))
    case ('ideal_gas')
      mat%eos = EOS_IDEAL_GAS
      if (gamma == UNSET) then
        call status%add(trim(where)//': gamma: required for eos = ''ideal_gas''')
      else if (.not. (gamma > 1.0_rk)) then
        call status%add(trim(where)//': gamma: must be > 1')
      end if
      mat%gamma = gamma
      if (any([rho0, c0, s1, gamma0, b, p_min] /= UNSET) .or. len_trim(library) > 0) &
          call status%add(trim(where)//': eos: ''ideal_gas'' takes only gamma '// &
          '(library, rho0, c0, s1, gamma0, b, p_min are Mie-Gruneisen data)')
    case ('mie_gruneisen')
      mat%eos = EOS_MIE_GRUNEISEN
      if (len_trim(library) > 0) then
        call material_library(to_lower(library), mat%mg, lib_shear, lib_yield, found)
        if (.not. found) call status%add(trim(where)//': library: '''//trim(library)// &
            ''' is not a built-in material'//name_hint(library, LIBRARY_NAMES))
        if (found .and. units == UNITS_NONE) call status%add(trim(where)//': library: '''// &
            trim(library)//''' has data in cm-g-us-mbar; with &control units = ''none'' give '// &
            'every property yourself (or choose units = ''cm-g-us-mbar'' or ''si'')')
        ! Library data are cm-g-us-mbar: to SI (kg, m, s, Pa) when asked.
        if (found .and. units == UNITS_SI) then
          mat%mg%rho0 = mat%mg%rho0 * SI_DENSITY
          mat%mg%c0 = mat%mg%c0 * SI_VELOCITY
          lib_shear = lib_shear * SI_PRESSURE
          lib_yield = lib_yield * SI_PRESSURE
        end if
      end if
      ! A rho0 far from the library's is the usual sign of mixed units.
      ! (The library's value is kept then, so that the regions are checked
      ! against it and not against the mistake.)
      rho0_refused = .false.
      if (rho0 /= UNSET .and. len_trim(library) > 0 .and. mat%mg%rho0 > 0.0_rk .and. &
          rho0 > 0.0_rk) then
        rho0_refused = rho0 >= DENSITY_FACTOR * mat%mg%rho0 .or. &
            rho0 * DENSITY_FACTOR <= mat%mg%rho0
        if (rho0_refused) call status%add(trim(where)//': rho0: '//brief_text(rho0)//' is '// &
            density_ratio_text(rho0 / mat%mg%rho0)//' the rho0 '//brief_text(mat%mg%rho0)// &
            ' of library '''//trim(library)//''' (in '//trim(units)//'), more than '// &
            to_text(nint(DENSITY_FACTOR))//' times from it: expected about '// &
            brief_text(mat%mg%rho0)//'; '//density_mistake(units, rho0 / mat%mg%rho0))
      end if
      if (rho0 /= UNSET .and. .not. rho0_refused) mat%mg%rho0 = rho0
      if (c0 /= UNSET) mat%mg%c0 = c0
      if (s1 /= UNSET) mat%mg%s1 = s1
      if (gamma0 /= UNSET) mat%mg%gamma0 = gamma0
      if (b /= UNSET) mat%mg%b = b
      if (p_min /= UNSET) mat%mg%p_min = p_min
      if (.not. (mat%mg%rho0 > 0.0_rk)) call status%add(trim(where)//': rho0: required '// &
          '(> 0) for eos = ''mie_gruneisen'' (or give library)')
      if (.not. (mat%mg%c0 > 0.0_rk)) call status%add(trim(where)//': c0: required '// &
          '(> 0) for eos = ''mie_gruneisen'' (or give library)')
      if (.not. (mat%mg%s1 >= 1.0_rk)) call status%add(trim(where)//': s1: required, '// &
          '>= 1, for eos = ''mie_gruneisen'' (or give library)')
      if (.not. (mat%mg%gamma0 > 0.0_rk)) call status%add(trim(where)//': gamma0: '// &
          'required (> 0) for eos = ''mie_gruneisen'' (or give library)')
      if (mat%mg%b < 0.0_rk .or. mat%mg%b >= mat%mg%gamma0) call status%add(trim(where)// &
          ': b: must be in [0, gamma0)')
      if (p_min /= UNSET .and. p_min > 0.0_rk) call status%add(trim(where)// &
          ': p_min: must be <= 0 (a tension cut-off)')
      if (gamma /= UNSET) call status%add(trim(where)//': gamma: only for eos = ''ideal_gas''')
    case ('')
      call status%add(trim(where)//': eos: required (valid: ideal_gas, mie_gruneisen)')
      return
    case default
      call status%add(trim(where)//': eos: '''//trim(eos)//''' is not an equation of '// &
          'state (valid: ideal_gas, mie_gruneisen)')
    end select
    ! Strength: a library set gives the model's defaults and every key overrides
    ! them; without a library each required key of the model must be given. A key
    ! of another model is an error.
    select case (to_lower(strength))
    case ('none')
      mat%strength = STRENGTH_NONE
      call only_for([character(len=KEY_LEN) :: 'shear_modulus', 'yield_stress'], &
          [shear_modulus, yield_stress], '''elastic_plastic'', ''steinberg_guinan'' or '// &
          '''johnson_cook''')
      call reject_ep()
      call reject_sg()
      call reject_jc()
      call reject_cv()
    case ('elastic_plastic')
      mat%strength = STRENGTH_ELASTIC_PLASTIC
      mat%shear_modulus = lib_shear
      mat%yield_stress = lib_yield
      if (shear_modulus /= UNSET) mat%shear_modulus = shear_modulus
      if (yield_stress /= UNSET) mat%yield_stress = yield_stress
      if (hardening_modulus /= UNSET) mat%hardening_modulus = hardening_modulus
      if (.not. (mat%shear_modulus > 0.0_rk)) call status%add(trim(where)// &
          ': shear_modulus: required (> 0) for strength = ''elastic_plastic'' (or give library)')
      if (.not. (mat%yield_stress > 0.0_rk)) call status%add(trim(where)// &
          ': yield_stress: required (> 0) for strength = ''elastic_plastic'' (or give library)')
      call check_key('hardening_modulus', mat%hardening_modulus, &
          mat%hardening_modulus >= 0.0_rk, '>= 0 (Mbar)', 'elastic_plastic', ANY_LIB)
      call reject_sg()
      call reject_jc()
      call reject_cv()
    case ('steinberg_guinan')
      mat%strength = STRENGTH_STEINBERG_GUINAN
      mat%sg = sg_set(to_lower(library))
      if (mat%sg%g0 > 0.0_rk .and. units == UNITS_SI) then
        mat%sg%g0 = mat%sg%g0 * SI_PRESSURE
        mat%sg%y0 = mat%sg%y0 * SI_PRESSURE
        mat%sg%ymax = mat%sg%ymax * SI_PRESSURE
        mat%sg%a = mat%sg%a / SI_PRESSURE
        mat%sg%cv = mat%sg%cv * SI_SPECIFIC_ENERGY
      end if
      if (.not. (mat%sg%g0 > 0.0_rk)) mat%sg = steinberg_guinan_t(g0=UNSET, y0=UNSET, &
          ymax=UNSET, beta=UNSET, n=UNSET, eps_i=0.0_rk, a=UNSET, b=UNSET, tm0=UNSET, &
          gamma0=UNSET, a_melt=UNSET, rho0=UNSET, cv=UNSET)
      ! The reference density, and by default the melt law's gamma0, are the EOS's.
      mat%sg%rho0 = mat%mg%rho0
      mat%sg%gamma0 = mat%mg%gamma0
      if (shear_modulus /= UNSET) mat%sg%g0 = shear_modulus
      if (yield_stress /= UNSET) mat%sg%y0 = yield_stress
      if (sg_ymax /= UNSET) mat%sg%ymax = sg_ymax
      if (sg_beta /= UNSET) mat%sg%beta = sg_beta
      if (sg_n /= UNSET) mat%sg%n = sg_n
      if (sg_eps_i /= UNSET) mat%sg%eps_i = sg_eps_i
      if (sg_a /= UNSET) mat%sg%a = sg_a
      if (sg_b /= UNSET) mat%sg%b = sg_b
      if (sg_tmelt0 /= UNSET) mat%sg%tm0 = sg_tmelt0
      if (sg_gamma0 /= UNSET) mat%sg%gamma0 = sg_gamma0
      if (sg_a_melt /= UNSET) mat%sg%a_melt = sg_a_melt
      if (cv /= UNSET) mat%sg%cv = cv
      mat%sg_cold_energy = sg_cold_energy
      mat%shear_modulus = mat%sg%g0
      if (mat%eos /= EOS_MIE_GRUNEISEN) then
        call status%add(trim(where)//': strength: ''steinberg_guinan'' needs eos = '// &
            '''mie_gruneisen'' (its rho0 and gamma0 enter G, Y and the melt law)')
      else
        call check_key('shear_modulus', mat%sg%g0, mat%sg%g0 > 0.0_rk, '> 0 (G0, Mbar)', &
            'steinberg_guinan', SG_LIBS)
        call check_key('yield_stress', mat%sg%y0, mat%sg%y0 > 0.0_rk, '> 0 (Y0, Mbar)', &
            'steinberg_guinan', SG_LIBS)
        call check_key('sg_ymax', mat%sg%ymax, mat%sg%ymax >= mat%sg%y0, &
            '>= yield_stress (Ymax >= Y0, Mbar)', 'steinberg_guinan', SG_LIBS)
        call check_key('sg_beta', mat%sg%beta, mat%sg%beta >= 0.0_rk, '>= 0', &
            'steinberg_guinan', SG_LIBS)
        call check_key('sg_n', mat%sg%n, mat%sg%n >= 0.0_rk, '>= 0', 'steinberg_guinan', &
            SG_LIBS)
        call check_key('sg_eps_i', mat%sg%eps_i, mat%sg%eps_i >= 0.0_rk, '>= 0', &
            'steinberg_guinan', SG_LIBS)
        call check_key('sg_a', mat%sg%a, mat%sg%a >= 0.0_rk, '>= 0 (1/Mbar)', &
            'steinberg_guinan', SG_LIBS)
        call check_key('sg_b', mat%sg%b, mat%sg%b >= 0.0_rk, '>= 0 (1/K)', &
            'steinberg_guinan', SG_LIBS)
        call check_key('sg_tmelt0', mat%sg%tm0, mat%sg%tm0 > SG_REFERENCE_TEMPERATURE, &
            '> 300 K (the reference temperature of G0 and Y0)', 'steinberg_guinan', SG_LIBS)
        call check_key('sg_gamma0', mat%sg%gamma0, mat%sg%gamma0 > 0.0_rk, '> 0', &
            'steinberg_guinan', SG_LIBS)
        call check_key('sg_a_melt', mat%sg%a_melt, mat%sg%a_melt >= 0.0_rk, '>= 0', &
            'steinberg_guinan', SG_LIBS)
        call check_key('cv', mat%sg%cv, mat%sg%cv > 0.0_rk, '> 0 (Mbar cm^3/(g K))', &
            'steinberg_guinan', SG_LIBS)
      end if
      call reject_ep()
      call reject_jc()
    case ('johnson_cook')
      mat%strength = STRENGTH_JOHNSON_COOK
      mat%jc = jc_set(to_lower(library))
      if (.not. (mat%jc%a > 0.0_rk)) mat%jc = johnson_cook_t(a=UNSET, b=UNSET, n=UNSET, &
          c=UNSET, m=UNSET, tm=UNSET, cv=UNSET)
      if (units == UNITS_SI) then
        ! The default reference rate 1e-6 /us is 1 /s.
        mat%jc%eps_dot0 = mat%jc%eps_dot0 / SI_TIME
        if (mat%jc%a > 0.0_rk) then
          mat%jc%a = mat%jc%a * SI_PRESSURE
          mat%jc%b = mat%jc%b * SI_PRESSURE
          mat%jc%cv = mat%jc%cv * SI_SPECIFIC_ENERGY
        end if
      end if
      mat%shear_modulus = lib_shear
      if (shear_modulus /= UNSET) mat%shear_modulus = shear_modulus
      if (jc_a /= UNSET) mat%jc%a = jc_a
      if (jc_b /= UNSET) mat%jc%b = jc_b
      if (jc_n /= UNSET) mat%jc%n = jc_n
      if (jc_c /= UNSET) mat%jc%c = jc_c
      if (jc_m /= UNSET) mat%jc%m = jc_m
      if (eps_dot0 /= UNSET) mat%jc%eps_dot0 = eps_dot0
      if (t_room /= UNSET) mat%jc%tr = t_room
      if (t_melt /= UNSET) mat%jc%tm = t_melt
      if (cv /= UNSET) mat%jc%cv = cv
      call check_key('shear_modulus', mat%shear_modulus, mat%shear_modulus > 0.0_rk, &
          '> 0 (Mbar)', 'johnson_cook', ANY_LIB)
      call check_key('jc_a', mat%jc%a, mat%jc%a > 0.0_rk, '> 0 (Mbar)', 'johnson_cook', &
          JC_LIBS)
      call check_key('jc_b', mat%jc%b, mat%jc%b >= 0.0_rk, '>= 0 (Mbar)', 'johnson_cook', &
          JC_LIBS)
      call check_key('jc_n', mat%jc%n, mat%jc%n >= 0.0_rk, '>= 0', 'johnson_cook', JC_LIBS)
      call check_key('jc_c', mat%jc%c, mat%jc%c >= 0.0_rk, '>= 0', 'johnson_cook', JC_LIBS)
      call check_key('jc_m', mat%jc%m, mat%jc%m > 0.0_rk, '> 0', 'johnson_cook', JC_LIBS)
      call check_key('eps_dot0', mat%jc%eps_dot0, mat%jc%eps_dot0 > 0.0_rk, '> 0 (1/us)', &
          'johnson_cook', JC_LIBS)
      call check_key('t_room', mat%jc%tr, mat%jc%tr > 0.0_rk, '> 0 (K)', 'johnson_cook', &
          JC_LIBS)
      if (mat%jc%tr > 0.0_rk) call check_key('t_melt', mat%jc%tm, mat%jc%tm > mat%jc%tr, &
          '> t_room (K)', 'johnson_cook', JC_LIBS)
      call check_key('cv', mat%jc%cv, mat%jc%cv > 0.0_rk, '> 0 (Mbar cm^3/(g K))', &
          'johnson_cook', JC_LIBS)
      call only_for([character(len=KEY_LEN) :: 'yield_stress'], [yield_stress], &
          '''elastic_plastic'' or ''steinberg_guinan'' (the initial yield of '// &
          '''johnson_cook'' is jc_a)')
      call reject_ep()
      call reject_sg()
    case default
      call status%add(trim(where)//': strength: '''//trim(strength)//''' is not a strength '// &
          'model (valid: none, elastic_plastic, steinberg_guinan, johnson_cook)')
    end select
    if (present(fail)) call read_failure()

  contains

    !> The failure keys into fail (after the strength model is known).
    subroutine read_failure()
      logical :: ok
      select case (to_lower(failure))
      case ('none')
        if (any(jc_damage /= UNSET)) call status%add(trim(where)//': jc_damage: only '// &
            'for failure = ''johnson_cook''')
        if (failure_strain /= UNSET) call status%add(trim(where)//': failure_strain: '// &
            'only for failure = ''plastic_strain''')
      case ('johnson_cook')
        if (any(jc_damage == UNSET)) then
          call status%add(trim(where)//': jc_damage: five values D1, D2, D3, D4, D5 '// &
              'required for failure = ''johnson_cook''')
        else if (.not. (jc_damage(1) + jc_damage(2) > 0.0_rk)) then
          call status%add(trim(where)//': jc_damage: D1 + D2 (the failure strain at '// &
              'zero triaxiality, reference rate and room temperature) must be > 0')
        else
          call failure_model_new('johnson_cook', jc_damage, fail%model, ok)
        end if
        if (failure_strain /= UNSET) call status%add(trim(where)//': failure_strain: '// &
            'only for failure = ''plastic_strain''')
      case ('plastic_strain')
        if (failure_strain == UNSET) then
          call status%add(trim(where)//': failure_strain: required for failure = '// &
              '''plastic_strain''')
        else if (.not. (failure_strain > 0.0_rk)) then
          call status%add(trim(where)//': failure_strain: must be > 0')
        else
          call failure_model_new('plastic_strain', [failure_strain], fail%model, ok)
        end if
        if (any(jc_damage /= UNSET)) call status%add(trim(where)//': jc_damage: only '// &
            'for failure = ''johnson_cook''')
      case default
        call status%add(trim(where)//': failure: '''//trim(failure)//''' is not a '// &
            'failure model (valid: none, '//FAILURE_NAMES//')')
      end select
      if (to_lower(failure) /= 'none' .and. mat%strength == STRENGTH_NONE) call status%add( &
          trim(where)//': failure: needs a strength model (the damage grows with the '// &
          'plastic strain; strength = ''none'' here)')
      if (spall_strength /= UNSET) then
        if (.not. (spall_strength > 0.0_rk)) call status%add(trim(where)// &
            ': spall_strength: must be > 0 (a magnitude: the zone fails below '// &
            '-spall_strength)')
        fail%spall_strength = spall_strength
      end if
      if (erode .and. to_lower(failure) == 'none' .and. spall_strength == UNSET) &
          call status%add(trim(where)//': erode: needs failure or spall_strength (a '// &
          'zone is eroded when it fails)')
      fail%erode = erode
      ! epsdot* of Johnson-Cook's failure strain: over the strength model's
      ! reference rate, else over 1/s in the deck's units.
      if (mat%strength == STRENGTH_JOHNSON_COOK .and. mat%jc%eps_dot0 > 0.0_rk) then
        fail%rate_reference = mat%jc%eps_dot0
      else if (to_lower(units) == UNITS_SI .or. to_lower(units) == UNITS_NONE) then
        fail%rate_reference = 1.0_rk
      else
        fail%rate_reference = SI_TIME
      end if
    end subroutine read_failure

    !> A model parameter after library and key: required while UNSET, else valid.
    subroutine check_key(key, value, valid, rule, model, libs)
      character(len=*), intent(in) :: key, rule, model, libs
      real(rk), intent(in) :: value
      logical, intent(in) :: valid
      if (value == UNSET) then
        call status%add(trim(where)//': '//key//': required for strength = '''//model// &
            ''''//libs)
      else if (.not. valid) then
        call status%add(trim(where)//': '//key//': must be '//rule//' for strength = '''// &
            model//'''')
      end if
    end subroutine check_key

    !> Each key given that this material's strength model does not take.
    subroutine only_for(keys, values, models)
      character(len=*), intent(in) :: keys(:)
      real(rk), intent(in) :: values(:)
      character(len=*), intent(in) :: models
      integer :: k
      do k = 1, size(keys)
        if (values(k) /= UNSET) call status%add(trim(where)//': '//trim(keys(k))// &
            ': only for strength = '//models//', not '''//trim(to_lower(strength))//'''')
      end do
    end subroutine only_for

    subroutine reject_ep()
      call only_for([character(len=KEY_LEN) :: 'hardening_modulus'], [hardening_modulus], &
          '''elastic_plastic''')
    end subroutine reject_ep

    subroutine reject_sg()
      if (sg_cold_energy) call status%add(trim(where)//': sg_cold_energy: only for '// &
          'strength = ''steinberg_guinan'', not '''//trim(to_lower(strength))//'''')
      call only_for([character(len=KEY_LEN) :: 'sg_beta', 'sg_n', 'sg_ymax', 'sg_eps_i', &
          'sg_a', 'sg_b', 'sg_tmelt0', 'sg_gamma0', 'sg_a_melt'], [sg_beta, sg_n, sg_ymax, &
          sg_eps_i, sg_a, sg_b, sg_tmelt0, sg_gamma0, sg_a_melt], '''steinberg_guinan''')
    end subroutine reject_sg

    subroutine reject_jc()
      call only_for([character(len=KEY_LEN) :: 'jc_a', 'jc_b', 'jc_n', 'jc_c', 'jc_m', &
          'eps_dot0', 't_room', 't_melt'], [jc_a, jc_b, jc_n, jc_c, jc_m, eps_dot0, t_room, &
          t_melt], '''johnson_cook''')
    end subroutine reject_jc

    subroutine reject_cv()
      call only_for([character(len=KEY_LEN) :: 'cv'], [cv], '''steinberg_guinan'' or '// &
          '''johnson_cook'' (the models with a temperature)')
    end subroutine reject_cv

  end subroutine read_material

  !> Each material name once.
  subroutine check_material_names(materials, status)
    type(material_t), intent(in) :: materials(:)
    type(status_t), intent(inout) :: status
    integer :: i, j
    do i = 1, size(materials)
      do j = 1, i - 1
        if (len_trim(materials(i)%name) > 0 .and. &
            materials(i)%name == materials(j)%name) call status%add( &
            '&material: name: '''//trim(materials(i)%name)//''' is given twice')
      end do
    end do
  end subroutine check_material_names

  !> The index-th &block into blocks(index); its material is named among materials.
  subroutine read_block(sect, index, blocks, materials, materials_read, status)
    character(len=*), intent(in) :: sect(:) !< the group's text (io_deck: unknown keys blanked)
    integer, intent(in) :: index
    type(block_spec_t), intent(inout) :: blocks(:) !< the deck's blocks; this one is blocks(index)
    type(material_t), intent(in) :: materials(:) !< the deck's materials
    logical, intent(in) :: materials_read !< every &material could be read
    type(status_t), intent(inout) :: status
    character(len=NAME_LEN) :: name, material
    real(rk) :: box(6)
    integer :: ios, i
    character(len=256) :: msg
    character(len=16) :: where
    namelist /block/ name, material, box

    write(where, '(a,i0,a)') '&block(', index, ')'
    name = ''
    material = ''
    box = blocks(index)%box
    read(sect, nml=block, iostat=ios, iomsg=msg)
    if (ios /= 0) then
      call status%add(trim(where)//': cannot read the group: '//trim(msg))
      return
    end if
    if (len_trim(name) == 0) call status%add(trim(where)//': name: required')
    do i = 1, index - 1
      if (blocks(i)%name == name) call status%add(trim(where)//': name: '''// &
          trim(name)//''' is given twice')
    end do
    blocks(index)%name = name
    blocks(index)%box = box
    if (box(1) > box(2) .or. box(3) > box(4) .or. box(5) > box(6)) call status%add( &
        trim(where)//': box: needs xmin <= xmax, ymin <= ymax, zmin <= zmax')
    blocks(index)%material = 0
    do i = 1, size(materials)
      if (materials(i)%name == material) blocks(index)%material = i
    end do
    if (len_trim(material) == 0) then
      call status%add(trim(where)//': material: required')
    else if (blocks(index)%material == 0 .and. materials_read) then
      call status%add(trim(where)//': material: '''//trim(material)// &
          ''' is not a material of this deck'//name_hint(material, materials%name))
    end if
  end subroutine read_block

  !> &erosion (at most one): distortion erosion of the blocks named (all by
  !> default) by relative volume and by the zone's own stable step.
  subroutine read_erosion(sect, deck_blocks, spec, status)
    character(len=*), intent(in) :: sect(:) !< the group's text (io_deck: unknown keys blanked)
    type(block_spec_t), intent(in) :: deck_blocks(:) !< the deck's blocks
    type(erosion_spec_t), intent(inout) :: spec
    type(status_t), intent(inout) :: status
    real(rk) :: volume_ratio, dt_fraction
    character(len=512) :: blocks
    character(len=NAME_LEN) :: word
    character(len=256) :: msg
    integer :: ios, i, j, k, n
    namelist /erosion/ volume_ratio, dt_fraction, blocks
    volume_ratio = 0.0_rk
    dt_fraction = 0.0_rk
    blocks = ''
    read(sect, nml=erosion, iostat=ios, iomsg=msg)
    if (ios /= 0) then
      call status%add('&erosion: cannot read the group: '//trim(msg))
      return
    end if
    spec%given = .true.
    if (.not. (volume_ratio >= 0.0_rk .and. volume_ratio < 1.0_rk)) call status%add( &
        '&erosion: volume_ratio: must be in [0, 1) (0: off)')
    if (.not. (dt_fraction >= 0.0_rk .and. dt_fraction < 1.0_rk)) call status%add( &
        '&erosion: dt_fraction: must be in [0, 1) (0: off)')
    if (volume_ratio == 0.0_rk .and. dt_fraction == 0.0_rk) call status%add( &
        '&erosion: volume_ratio, dt_fraction: give at least one (> 0): the group erodes '// &
        'nothing otherwise')
    spec%volume_ratio = volume_ratio
    spec%dt_fraction = dt_fraction
    allocate(spec%block(size(deck_blocks)))
    spec%block = len_trim(blocks) == 0
    ! Names separated by commas or blanks.
    do i = 1, len_trim(blocks)
      if (blocks(i:i) == ',') blocks(i:i) = ' '
    end do
    n = len_trim(blocks)
    i = 1
    do while (i <= n)
      if (blocks(i:i) == ' ') then
        i = i + 1
        cycle
      end if
      j = index(blocks(i:n)//' ', ' ') + i - 2
      word = blocks(i:j)
      k = findloc(deck_blocks%name, word, dim=1)
      if (k == 0) then
        call status%add('&erosion: blocks: '''//trim(word)//''' is not a block of this '// &
            'deck'//name_hint(word, deck_blocks%name))
      else
        spec%block(k) = .true.
      end if
      i = j + 1
    end do
  end subroutine read_erosion

end module material_deck
