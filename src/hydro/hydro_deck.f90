!> The hydro package's deck groups, each key declared once in its table
!> (core_keys) next to the group's reader: &hydro (hydro_options_t), &region
!> (hydro_initial's region_t) and &boundary (hydro_boundary's
!> boundary_spec_t). io_deck has checked the key names and value types and
!> hands each reader the group's text; the reader does the namelist read and
!> the checks of the values.
module hydro_deck
  use core_kinds, only: rk
  use core_status, only: status_t
  use core_text, only: to_lower
  use core_names, only: name_hint
  use core_text, only: to_text
  use core_unit_checks, only: DENSITY_FACTOR, density_ratio_text, density_mistake
  use core_keys, only: UNSET, key_t
  use parallel_env, only: par_rank
  use mesh_global, only: NAME_LEN
  use material_table, only: material_t, EOS_MIE_GRUNEISEN
  use material_deck, only: block_spec_t
  use hydro_state, only: hydro_options_t, HOURGLASS_NONE, HOURGLASS_VISCOUS, HOURGLASS_STIFFNESS, &
      VISCOSITY_SCALAR, VISCOSITY_EDGE
  use hydro_boundary, only: boundary_spec_t, BC_FREE, BC_SYMMETRY, BC_VELOCITY, BC_PRESSURE, &
      BC_WALL
  use hydro_initial, only: region_t
  implicit none
  private
  public :: read_hydro, read_region, read_boundary

  !> &hydro: artificial viscosity and hourglass control.
  type(key_t), parameter, public :: HYDRO_KEYS(10) = [ &
      key_t("viscosity", "c", "'scalar'", "", &
      "artificial viscosity: 'scalar' (zone q) or 'edge' (Caramana-Shashkov-Whalen edge q)"), &
      key_t("q_linear", "r", "0.5", "", &
      "linear viscosity coefficient C1, >= 0"), &
      key_t("q_quadratic", "r", "2/3", "", &
      "quadratic viscosity coefficient C2, >= 0"), &
      key_t("q_limiter", "l", ".true.", "", &
      "monotonic limiter of the viscosity"), &
      key_t("q_linear_limited", "l", ".true.", "", &
      "the limiter acts on the linear term too (.false.: linear term kept in compression)"), &
      key_t("heat_flux_linear", "r", "0", "", &
      "artificial heat flux (Noh) coefficient a of rho L c, >= 0; 0 with heat_flux_quadratic = off"), &
      key_t("heat_flux_quadratic", "r", "0", "", &
      "artificial heat flux (Noh) coefficient b of rho L^2 abs(div v) in compression, >= 0"), &
      key_t("scheme", "c", "'predictor_corrector'", "", &
      "time integration: 'predictor_corrector' or 'single' (one force evaluation)"), &
      key_t("hourglass", "c", "'viscous'", "", &
      "'none', 'viscous' or 'stiffness' (Flanagan-Belytschko)"), &
      key_t("hourglass_coefficient", "r", "0.1", "", &
      "hourglass coefficient kappa, [0, 1]")]

  !> &region: initial state of the zones in a box and/or block.
  type(key_t), parameter, public :: REGION_KEYS(12) = [ &
      key_t("block", "c", "any", "", &
      "restrict to this block"), &
      key_t("box", "r", "everything", "length", &
      "xmin, xmax, ymin, ymax, zmin, zmax of zone centroids"), &
      key_t("density", "r", "-", "density", &
      "density (every zone must get one)"), &
      key_t("energy", "r", "-", "specific_energy", &
      "specific internal energy (or give pressure, not both)"), &
      key_t("pressure", "r", "-", "pressure", &
      "pressure (needs density in the same region)"), &
      key_t("velocity", "r", "0, 0, 0", "velocity", &
      "uniform velocity of the region's nodes"), &
      key_t("radial_u0", "r", "0", "velocity", &
      "radial velocity field u0 (r0/r)^k r_hat about center: u0"), &
      key_t("radial_r0", "r", "1", "length", &
      "radial velocity field: r0, > 0"), &
      key_t("radial_k", "r", "0", "", &
      "radial velocity field: k"), &
      key_t("center", "r", "0, 0, 0", "length", &
      "centre of the radial field"), &
      key_t("deposit_energy", "r", "0", "energy", &
      "energy (not specific) put in the zone nearest deposit_point (Sedov)"), &
      key_t("deposit_point", "r", "0, 0, 0", "length", &
      "where deposit_energy goes")]

  !> &boundary: the condition on a face set.
  type(key_t), parameter, public :: BOUNDARY_KEYS(7) = [ &
      key_t("set", "c", "required", "", &
      "face set name"), &
      key_t("type", "c", "required", "", &
      "'free', 'symmetry', 'wall', 'velocity' or 'pressure'"), &
      key_t("velocity", "r", "required for 'velocity'", "velocity", &
      "type 'velocity': the 3 components"), &
      key_t("pressure", "r", "required for 'pressure'", "pressure", &
      "applied pressure (positive pushes inward)"), &
      key_t("wall_point", "r", "none (the set's plane)", "length", &
      "'wall' only, with wall_normal: a point of the wall plane"), &
      key_t("wall_normal", "r", "none (the set's plane)", "", &
      "'wall' only, with wall_point: the plane's normal out of the wall into the body"), &
      key_t("friction", "r", "0", "", &
      "'wall' only: Coulomb friction coefficient, >= 0")]

contains

  !> &hydro into opt (its defaults are opt's on entry).
  subroutine read_hydro(sect, opt, status)
    character(len=*), intent(in) :: sect(:) !< the group's text (io_deck: unknown keys blanked)
    type(hydro_options_t), intent(inout) :: opt
    type(status_t), intent(inout) :: status
    real(rk) :: q_linear, q_quadratic, hourglass_coefficient, heat_flux_linear, heat_flux_quadratic
    character(len=32) :: hourglass, viscosity, scheme
    logical :: q_limiter, q_linear_limited
    integer :: ios
    character(len=256) :: msg
    namelist /hydro/ viscosity, q_linear, q_quadratic, q_limiter, q_linear_limited, hourglass, &
        heat_flux_linear, heat_flux_quadratic, scheme, &
        hourglass_coefficient

    q_limiter = opt%q_limiter
    q_linear_limited = opt%q_linear_limited
    q_linear = opt%q_linear
    q_quadratic = opt%q_quadratic
    heat_flux_linear = opt%heat_flux_linear
    heat_flux_quadratic = opt%heat_flux_quadratic
    hourglass = 'viscous'
    viscosity = 'scalar'
    if (opt%viscosity == VISCOSITY_EDGE) viscosity = 'edge'
    hourglass_coefficient = opt%hourglass_coefficient
    scheme = 'predictor_corrector'
    if (opt%single_stage) scheme = 'single'
    read(sect, nml=hydro, iostat=ios, iomsg=msg)
    if (ios /= 0) call status%add('&hydro: cannot read the group: '//trim(msg))
    if (ios /= 0) return
    if (q_linear < 0.0_rk) call status%add('&hydro: q_linear: must be >= 0')
    if (q_quadratic < 0.0_rk) call status%add('&hydro: q_quadratic: must be >= 0')
    if (heat_flux_linear < 0.0_rk) call status%add('&hydro: heat_flux_linear: must be >= 0')
    if (heat_flux_quadratic < 0.0_rk) call status%add('&hydro: heat_flux_quadratic: must be >= 0')
    if (hourglass_coefficient < 0.0_rk .or. hourglass_coefficient > 1.0_rk) call status%add( &
        '&hydro: hourglass_coefficient: must be in [0, 1]')
    select case (to_lower(hourglass))
    case ('none')
      opt%hourglass = HOURGLASS_NONE
    case ('viscous')
      opt%hourglass = HOURGLASS_VISCOUS
    case ('stiffness')
      opt%hourglass = HOURGLASS_STIFFNESS
    case default
      call status%add('&hydro: hourglass: '''//trim(hourglass)//''' is not a hourglass '// &
          'control (valid: none, viscous, stiffness)')
    end select
    select case (to_lower(viscosity))
    case ('scalar')
      opt%viscosity = VISCOSITY_SCALAR
    case ('edge')
      opt%viscosity = VISCOSITY_EDGE
    case default
      call status%add('&hydro: viscosity: '''//trim(viscosity)//''' is not a viscosity '// &
          '(valid: scalar, edge)')
    end select
    opt%q_linear = q_linear
    opt%q_quadratic = q_quadratic
    opt%heat_flux_linear = heat_flux_linear
    opt%heat_flux_quadratic = heat_flux_quadratic
    opt%q_limiter = q_limiter
    opt%q_linear_limited = q_linear_limited
    opt%hourglass_coefficient = hourglass_coefficient
    select case (to_lower(scheme))
    case ('predictor_corrector')
      opt%single_stage = .false.
    case ('single')
      opt%single_stage = .true.
    case default
      call status%add('&hydro: scheme: '''//trim(scheme)//''' is not a scheme '// &
          '(valid: predictor_corrector, single)')
    end select
  end subroutine read_hydro

  !> The index-th &region into spec; its block is named among blocks, and rank 0
  !> warns when its density is far from its material's rho0.
  subroutine read_region(sect, index, blocks, materials, materials_read, spec, status, units)
    character(len=*), intent(in) :: sect(:) !< the group's text (io_deck: unknown keys blanked)
    integer, intent(in) :: index
    type(block_spec_t), intent(in) :: blocks(:) !< the deck's blocks
    type(material_t), intent(in) :: materials(:) !< the deck's materials
    logical, intent(in) :: materials_read !< every &material could be read
    type(region_t), intent(inout) :: spec !< this &region
    type(status_t), intent(inout) :: status
    character(len=*), intent(in) :: units !< &control units, for the unit-mistake check
    character(len=NAME_LEN) :: block
    real(rk) :: box(6), density, energy, pressure, velocity(3), radial_u0, radial_r0, radial_k
    real(rk) :: center(3), deposit_energy, deposit_point(3)
    type(region_t) :: r
    integer :: ios, i
    character(len=256) :: msg
    character(len=16) :: where
    namelist /region/ block, box, density, energy, pressure, velocity, radial_u0, radial_r0, &
        radial_k, center, deposit_energy, deposit_point

    write(where, '(a,i0,a)') '&region(', index, ')'
    block = ''
    box = r%box
    density = r%density
    energy = r%energy
    pressure = r%pressure
    velocity = r%velocity
    radial_u0 = r%radial_u0
    radial_r0 = r%radial_r0
    radial_k = r%radial_k
    center = r%center
    deposit_energy = r%deposit_energy
    deposit_point = r%deposit_point
    read(sect, nml=region, iostat=ios, iomsg=msg)
    if (ios /= 0) then
      call status%add(trim(where)//': cannot read the group: '//trim(msg))
      return
    end if
    r%block = 0
    if (len_trim(block) > 0) then
      do i = 1, size(blocks)
        if (blocks(i)%name == block) r%block = i
      end do
      if (r%block == 0) call status%add(trim(where)//': block: '''//trim(block)// &
          ''' is not a block of this deck'//name_hint(block, blocks%name))
    end if
    if (box(1) > box(2) .or. box(3) > box(4) .or. box(5) > box(6)) call status%add( &
        trim(where)//': box: needs xmin <= xmax, ymin <= ymax, zmin <= zmax')
    if (density /= UNSET .and. .not. (density > 0.0_rk)) call status%add(trim(where)// &
        ': density: must be > 0')
    if (energy /= UNSET .and. pressure /= UNSET) call status%add(trim(where)// &
        ': pressure: give energy or pressure, not both')
    if (energy /= UNSET .and. energy < 0.0_rk) call status%add(trim(where)// &
        ': energy: must be >= 0')
    if (pressure /= UNSET .and. pressure < 0.0_rk) call status%add(trim(where)// &
        ': pressure: must be >= 0')
    if (pressure /= UNSET .and. density == UNSET) call status%add(trim(where)// &
        ': pressure: needs density in the same region (to find the energy)')
    if (.not. (radial_r0 > 0.0_rk)) call status%add(trim(where)//': radial_r0: must be > 0')
    if (deposit_energy < 0.0_rk) call status%add(trim(where)//': deposit_energy: must be >= 0')
    r%box = box
    r%density = density
    r%energy = energy
    r%pressure = pressure
    r%velocity = velocity
    r%radial_u0 = radial_u0
    r%radial_r0 = radial_r0
    r%radial_k = radial_k
    r%center = center
    r%deposit_energy = deposit_energy
    r%deposit_point = deposit_point
    spec = r
    ! A density far from the material's reference density is the usual sign of
    ! mixed units: more than DENSITY_FACTOR times is an error, more than 20% a
    ! warning (rank 0, once, before the run).
    if (density /= UNSET .and. density > 0.0_rk .and. materials_read) call check_density()

  contains

    !> The density against the rho0 of the region's material: that of its
    !> block, or without block that of every block whose box meets the region's
    !> box. Silent when any of them is within 20% or has no reference density;
    !> an error when it is more than DENSITY_FACTOR times from every one of
    !> them (naming the key, the value, the expected magnitude and the likely
    !> unit mistake), else a warning.
    subroutine check_density()
      use, intrinsic :: iso_fortran_env, only: error_unit
      real(rk), parameter :: TOLERANCE = 0.2_rk
      logical :: listed(size(materials)), far
      character(len=512) :: names
      character(len=16) :: text
      integer :: k, m
      real(rk) :: rho_ref, ratio
      listed = .false.
      far = .true.
      ratio = 1.0_rk
      names = ''
      do k = 1, size(blocks)
        if (r%block > 0 .and. k /= r%block) cycle
        if (r%block == 0 .and. .not. boxes_meet(blocks(k)%box, box)) cycle
        m = blocks(k)%material
        if (m == 0) cycle
        if (listed(m)) cycle
        if (materials(m)%eos /= EOS_MIE_GRUNEISEN) return
        rho_ref = materials(m)%mg%rho0
        if (.not. (rho_ref > 0.0_rk)) return
        if (abs(density - rho_ref) <= TOLERANCE * rho_ref) return
        listed(m) = .true.
        if (density < DENSITY_FACTOR * rho_ref .and. density * DENSITY_FACTOR > rho_ref) &
            far = .false.
        ratio = density / rho_ref
        write(text, '(es11.4)') rho_ref
        if (len_trim(names) > 0) names = trim(names)//', '
        names = trim(names)//''''//trim(materials(m)%name)//''' (rho0 = '// &
            trim(adjustl(text))//')'
      end do
      if (.not. any(listed)) return
      write(text, '(es11.4)') density
      if (far) then
        call status%add(trim(where)//': density: '//trim(adjustl(text))//' is '// &
            density_ratio_text(ratio)//' the rho0 of material '//trim(names)// &
            ', more than '//to_text(nint(DENSITY_FACTOR))//' times from it: expected '// &
            'about the rho0; '//density_mistake(units, ratio))
      else if (par_rank() == 0) then
        write(error_unit, '(a)') 'warning: '//trim(where)//': density: '// &
            trim(adjustl(text))//' differs by more than 20% from the rho0 of material '// &
            trim(names)//' (mixed units?)'
      end if
    end subroutine check_density

    logical function boxes_meet(a, b)
      real(rk), intent(in) :: a(6), b(6)
      boxes_meet = a(1) <= b(2) .and. b(1) <= a(2) .and. a(3) <= b(4) .and. b(3) <= a(4) &
          .and. a(5) <= b(6) .and. b(5) <= a(6)
    end function boxes_meet

  end subroutine read_region

  !> The index-th &boundary into bc.
  subroutine read_boundary(sect, index, bc, status)
    character(len=*), intent(in) :: sect(:) !< the group's text (io_deck: unknown keys blanked)
    integer, intent(in) :: index
    type(boundary_spec_t), intent(inout) :: bc
    type(status_t), intent(inout) :: status
    character(len=NAME_LEN) :: set
    character(len=32) :: type
    real(rk) :: velocity(3), pressure, wall_point(3), wall_normal(3), friction
    integer :: ios
    character(len=256) :: msg
    character(len=16) :: where
    namelist /boundary/ set, type, velocity, pressure, wall_point, wall_normal, friction

    write(where, '(a,i0,a)') '&boundary(', index, ')'
    set = ''
    type = ''
    velocity = UNSET
    pressure = UNSET
    wall_point = UNSET
    wall_normal = UNSET
    friction = UNSET
    read(sect, nml=boundary, iostat=ios, iomsg=msg)
    if (ios /= 0) then
      call status%add(trim(where)//': cannot read the group: '//trim(msg))
      return
    end if
    if (len_trim(set) == 0) call status%add(trim(where)//': set: required (a face set name)')
    bc%set = set
    select case (to_lower(type))
    case ('free')
      bc%kind = BC_FREE
    case ('symmetry')
      bc%kind = BC_SYMMETRY
    case ('wall')
      bc%kind = BC_WALL
    case ('velocity')
      bc%kind = BC_VELOCITY
      if (any(velocity == UNSET)) call status%add(trim(where)//': velocity: required '// &
          '(3 components) for type = ''velocity''')
      bc%velocity = velocity
    case ('pressure')
      bc%kind = BC_PRESSURE
      if (pressure == UNSET) call status%add(trim(where)//': pressure: required for '// &
          'type = ''pressure''')
      bc%pressure = pressure
    case ('')
      call status%add(trim(where)//': type: required (valid: free, symmetry, wall, velocity, pressure)')
    case default
      call status%add(trim(where)//': type: '''//trim(type)//''' is not a boundary '// &
          'condition (valid: free, symmetry, wall, velocity, pressure)')
    end select
    if (bc%kind /= BC_VELOCITY .and. any(velocity /= UNSET)) call status%add(trim(where)// &
        ': velocity: only for type = ''velocity''')
    if (bc%kind /= BC_PRESSURE .and. pressure /= UNSET) call status%add(trim(where)// &
        ': pressure: only for type = ''pressure''')
    if (friction /= UNSET) then
      if (bc%kind /= BC_WALL) then
        call status%add(trim(where)//': friction: only for type = ''wall'' (the Coulomb '// &
            'coefficient of the rigid wall)')
      else if (.not. (friction >= 0.0_rk)) then
        call status%add(trim(where)//': friction: must be >= 0 (the Coulomb coefficient)')
      else
        bc%friction = friction
      end if
    end if
    call read_wall_plane()

  contains

    !> Optional wall plane: both keys (3 components each) or neither.
    subroutine read_wall_plane()
      logical :: has_point, has_normal
      has_point = any(wall_point /= UNSET)
      has_normal = any(wall_normal /= UNSET)
      if (.not. (has_point .or. has_normal)) return
      if (bc%kind /= BC_WALL) then
        if (has_point) call status%add(trim(where)//': wall_point: only for type = ''wall''')
        if (has_normal) call status%add(trim(where)//': wall_normal: only for type = ''wall''')
        return
      end if
      if (has_point .and. any(wall_point == UNSET)) call status%add(trim(where)// &
          ': wall_point: needs 3 components (a point of the wall plane, cm)')
      if (has_normal .and. any(wall_normal == UNSET)) call status%add(trim(where)// &
          ': wall_normal: needs 3 components (the plane''s normal out of the wall into the body)')
      if (has_point .and. .not. has_normal) call status%add(trim(where)// &
          ': wall_normal: required with wall_point (give both to place the wall, or neither '// &
          'for the set''s plane at t = 0)')
      if (has_normal .and. .not. has_point) call status%add(trim(where)// &
          ': wall_point: required with wall_normal (give both to place the wall, or neither '// &
          'for the set''s plane at t = 0)')
      if (.not. (all(wall_point /= UNSET) .and. all(wall_normal /= UNSET))) return
      if (.not. norm2(wall_normal) > 0.0_rk) then
        call status%add(trim(where)//': wall_normal: must not be the zero vector (it points '// &
            'out of the wall into the body)')
        return
      end if
      bc%wall_point = wall_point
      bc%wall_normal = wall_normal / norm2(wall_normal)
    end subroutine read_wall_plane

  end subroutine read_boundary

end module hydro_deck
