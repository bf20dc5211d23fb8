!> The input deck: namelist groups &control, &hydro, &mesh, &material,
!> &block, &region, &boundary, &contact, &output and &probe. Rank 0 reads the file and
!> broadcasts its text; every rank then parses the same text, and rank 0
!> reports every problem found (group, key, reason) before any work starts.
module io_deck
  use core_kinds, only: rk
  use core_status, only: status_t
  use core_path, only: path_from_deck, path_directory, path_absolute
  use core_units, only: units_valid, UNITS_CGSUS, UNITS_LIST, UNITS_SI, UNITS_NONE, &
      SI_DENSITY, SI_VELOCITY, SI_PRESSURE, SI_SPECIFIC_ENERGY, SI_TIME
  use io_deck_scan, only: deck_scan, group_instance_t, to_lower, group_text, value_problem, &
      closest_name, LINE_LEN, KEY_LEN
  use mesh_global, only: box_spec_t, MAX_INTERVALS, NAME_LEN
  use mesh_curved, only: rod_spec_t, tube_spec_t, shell_spec_t, ball_spec_t, &
      box_minus_ball_spec_t
  use material_table, only: material_t, EOS_IDEAL_GAS, EOS_MIE_GRUNEISEN, material_library, &
      STRENGTH_NONE, STRENGTH_ELASTIC_PLASTIC, STRENGTH_STEINBERG_GUINAN, STRENGTH_JOHNSON_COOK
  use material_flow_stress, only: sg_set, jc_set, SG_SET_NAMES, JC_SET_NAMES
  use hydro_state, only: hydro_options_t, HOURGLASS_NONE, HOURGLASS_VISCOUS, HOURGLASS_STIFFNESS
  use hydro_boundary, only: boundary_spec_t, BC_FREE, BC_SYMMETRY, BC_VELOCITY, BC_PRESSURE, &
      BC_WALL
  use hydro_initial, only: region_t, UNSET
  use parallel_env, only: par_rank, par_bcast
  use contact_enforce, only: contact_spec_t, SURFACE_LEN
  implicit none
  private
  public :: deck_read, deck_known_keys, deck_key_types, deck_restart_check
  public :: output_directory_create

  integer, parameter, public :: DECK_FORMAT_VERSION = 1
  integer, parameter, public :: PATH_LEN = 256
  integer, parameter :: NGROUP_KNOWN = 10
  character(len=*), parameter :: GROUP_NAMES(NGROUP_KNOWN) = [character(len=8) :: &
      'control', 'hydro', 'mesh', 'material', 'block', 'region', 'boundary', 'output', 'contact', &
      'probe']

  !> Fields a &probe may record (docs/user-guide.md, &probe).
  integer, parameter, public :: PROBE_FIELD_LEN = 16
  character(len=*), parameter, public :: PROBE_FIELDS(9) = [character(len=PROBE_FIELD_LEN) :: &
      'velocity', 'position', 'pressure', 'density', 'energy', 'stress', 'plastic_strain', &
      'viscosity', 'sound_speed']

  !> One &probe group: a time history of chosen fields at one node / zone.
  type, public :: probe_spec_t
    character(len=NAME_LEN) :: name = ''
    integer :: node = 0 !< global node id (0: given by point)
    logical :: at_point = .false. !< point given
    real(rk) :: point(3) = 0.0_rk
    character(len=PROBE_FIELD_LEN), allocatable :: fields(:)
    integer :: every = 0 !< cycles between rows (0: by interval)
    real(rk) :: interval = 0.0_rk !< simulated time between rows (0: by every)
  end type probe_spec_t

  !> A block: zones whose centroid lies in box, made of one material.
  type, public :: block_spec_t
    character(len=NAME_LEN) :: name = ''
    integer :: material = 0 !< index into config%materials
    real(rk) :: box(6) = [-huge(1.0_rk), huge(1.0_rk), -huge(1.0_rk), huge(1.0_rk), &
        -huge(1.0_rk), huge(1.0_rk)]
  end type block_spec_t

  !> Output controls.
  type, public :: output_options_t
    character(len=PATH_LEN) :: directory = '.' !< where dumps and history go
    character(len=NAME_LEN) :: prefix = 'dump' !< dump file prefix
    real(rk) :: dump_interval = 0.0_rk !< simulated time between dumps (0 = none)
    integer :: dump_cycles = 0 !< cycles between dumps (0 = none)
    integer :: status_every = 10 !< cycles between status lines
    integer :: history_every = 1 !< cycles between history lines
  end type output_options_t


  !> One &mesh group: a generated or imported mesh part. Parts share no
  !> nodes; several parts make separate bodies (which meet through &contact).
  type, public :: mesh_part_t
    character(len=NAME_LEN) :: name = '' !< prefix of the part's own face sets
    character(len=16) :: mesh_type = 'box'
    type(box_spec_t) :: box
    type(rod_spec_t) :: rod
    type(tube_spec_t) :: tube
    type(shell_spec_t) :: shell
    type(ball_spec_t) :: ball
    type(box_minus_ball_spec_t) :: box_minus_ball
    character(len=PATH_LEN) :: mesh_file = '' !< the file key as given (gmsh, exodus)
    !> The file to read: mesh_file relative to the deck's directory, made absolute.
    character(len=:), allocatable :: mesh_path
    real(rk) :: offset(3) = 0.0_rk !< translation applied to the part
    real(rk) :: rotation_axis(3) = 0.0_rk !< rotation of the part about the origin (before offset)
    real(rk) :: rotation_angle = 0.0_rk !< degrees, right-handed about rotation_axis
    character(len=NAME_LEN) :: block = '' !< every zone of the part in this &block
  end type mesh_part_t

  !> A group's text as read (unknown keys blanked).
  type :: section_t
    character(len=LINE_LEN), allocatable :: text(:)
  end type section_t

  !> Keys of a group instance left out of its namelist read (bad values).
  type :: skip_t
    logical, allocatable :: key(:)
  end type skip_t

  !> Everything the deck says.
  type, public :: config_t
    character(len=80) :: title = ''
    real(rk) :: t_end = UNSET
    integer :: max_cycles = 10000000
    real(rk) :: wall_limit = 0.0_rk !< wall-clock seconds; stop cleanly before (0 = none)
    character(len=PATH_LEN) :: stop_file = 'STOP' !< its existence stops the run cleanly
    integer :: stop_check_every = 10 !< cycles between looks for the stop file
    integer :: fault_cycle = 0 !< testing aid: inject a fault at this cycle (0 = never)
    character(len=8) :: fault_kind = 'nan' !< 'nan' (NaN energy) or 'tangle' (mirror zone 1)
    character(len=PATH_LEN) :: restart = ''
    type(hydro_options_t) :: hydro
    type(mesh_part_t), allocatable :: parts(:) !< one per &mesh group, appended in order
    type(material_t), allocatable :: materials(:)
    type(block_spec_t), allocatable :: blocks(:)
    type(region_t), allocatable :: regions(:)
    type(boundary_spec_t), allocatable :: boundaries(:)
    type(contact_spec_t), allocatable :: contacts(:)
    type(output_options_t) :: output
    type(probe_spec_t), allocatable :: probes(:) !< one per &probe group
    character(len=16) :: units = UNITS_CGSUS !< &control units: unit system of the deck
    logical :: materials_read = .true. !< false when a &material could not be read
    character(len=:), allocatable :: deck_text !< the deck file as read (for the dumps)
  end type config_t

contains

  !> Known keys of a group (the deck reference in docs is checked against it).
  function deck_known_keys(group) result(keys)
    character(len=*), intent(in) :: group
    character(len=KEY_LEN), allocatable :: keys(:)
    select case (group)
    case ('control')
      keys = [character(len=KEY_LEN) :: 'title', 't_end', 'max_cycles', 'deck_version', &
          'restart', 'cfl', 'dt_initial', 'dt_max', 'dt_min', 'dt_growth', 'dvol_max', &
          'fault_cycle', 'fault_kind', 'wall_limit', 'stop_file', 'stop_check_every', 'units']
    case ('hydro')
      keys = [character(len=KEY_LEN) :: 'q_linear', 'q_quadratic', 'q_limiter', &
          'q_linear_limited', 'hourglass', 'hourglass_coefficient']
    case ('mesh')
      keys = [character(len=KEY_LEN) :: 'type', 'x', 'y', 'z', 'nx', 'ny', 'nz', 'ratio_x', &
          'ratio_y', 'ratio_z', 'skew_amplitude', 'perturb', 'radius', 'length', 'z0', 'sector', &
          'n_core', 'n_radial', 'n_axial', 'axial_ratio', 'core_fraction', 'ri', 'ro', 'n_theta', &
          'axis', 'origin', 'radial_reference', 'n_patch', 'radial_ratio', 'file', 'name', &
          'offset', 'block', 'rotation_axis', 'rotation_angle']
    case ('material')
      keys = [character(len=KEY_LEN) :: 'name', 'eos', 'gamma', 'library', 'rho0', 'c0', 's1', &
          'gamma0', 'b', 'p_min', 'strength', 'shear_modulus', 'yield_stress', &
          'hardening_modulus', 'cv', 'jc_a', 'jc_b', 'jc_n', 'jc_c', 'jc_m', 'eps_dot0', &
          't_room', 't_melt', 'sg_beta', 'sg_n', 'sg_ymax', 'sg_eps_i', 'sg_a', 'sg_b', &
          'sg_tmelt0', 'sg_gamma0', 'sg_a_melt', 'sg_cold_energy']
    case ('block')
      keys = [character(len=KEY_LEN) :: 'name', 'material', 'box']
    case ('region')
      keys = [character(len=KEY_LEN) :: 'block', 'box', 'density', 'energy', 'pressure', &
          'velocity', 'radial_u0', 'radial_r0', 'radial_k', 'center', 'deposit_energy', &
          'deposit_point']
    case ('boundary')
      keys = [character(len=KEY_LEN) :: 'set', 'type', 'velocity', 'pressure', 'wall_point', &
          'wall_normal', 'friction']
    case ('output')
      keys = [character(len=KEY_LEN) :: 'directory', 'prefix', 'dump_interval', &
          'dump_cycles', 'status_every', 'history_every']
    case ('contact')
      keys = [character(len=KEY_LEN) :: 'name', 'surface_a', 'surface_b', 'method', 'master', &
          'capture', 'penetration_warning', 'search_margin', 'search_every', 'form', &
          'sweeps', 'recovery', 'normal', 'penetration_tolerance', 'on_penetration', &
          'initial_penetration', 'friction', 'symmetric']
    case ('probe')
      keys = [character(len=KEY_LEN) :: 'name', 'node', 'point', 'fields', 'every', 'interval']
    case default
      allocate(keys(0))
    end select
  end function deck_known_keys

  !> The type of each key of deck_known_keys(group), in the same order: 'r'
  !> real, 'i' integer, 'l' logical, 'c' character.
  function deck_key_types(group) result(types)
    character(len=*), intent(in) :: group
    character(len=:), allocatable :: types
    select case (group)
    case ('control')
      types = 'crii' // 'crrrrrr' // 'icrci' // 'c'
    case ('hydro')
      types = 'rrllcr'
    case ('mesh')
      types = 'crrriii' // 'rrrrrrrr' // 'ciiirrrr' // 'irrrir' // 'ccrc' // 'rr'
    case ('material')
      types = 'cc' // 'rc' // 'rrrrrr' // 'crr' // 'rr' // 'rrrrr' // 'rrr' // 'rrrrrrrrr' // 'l'
    case ('block')
      types = 'ccr'
    case ('region')
      types = 'crrrrrrrrrrr'
    case ('boundary')
      types = 'ccrrrrr'
    case ('output')
      types = 'ccriii'
    case ('contact')
      types = 'cccccrrrici' // 'rc' // 'rcc' // 'rl'
    case ('probe')
      types = 'circir'
    case default
      types = ''
    end select
  end function deck_key_types

  !> Read, check and distribute the deck. On return status%count is the same
  !> on every rank; rank 0 holds the messages.
  subroutine deck_read(path, config, status)
    character(len=*), intent(in) :: path
    type(config_t), intent(out) :: config
    type(status_t), intent(inout) :: status
    character(len=LINE_LEN), allocatable :: lines(:)
    type(group_instance_t), allocatable :: groups(:)
    integer :: nline, ngroup, ig, ik, k, counts(NGROUP_KNOWN), first_read, nbad
    character(len=KEY_LEN), allocatable :: known(:)
    logical :: found
    type(section_t), allocatable :: sections(:)
    type(skip_t), allocatable :: skips(:)
    character(len=:), allocatable :: types, problem, guess
    character(len=KEY_LEN + 20), allocatable :: bad(:)
    character(len=16) :: lnum

    call read_lines(path, lines, nline, config%deck_text, status)
    if (.not. status%ok()) return
    call deck_scan(lines, groups, ngroup, status)

    ! Unknown groups and keys, every one of them.
    counts = 0
    do ig = 1, ngroup
      found = .false.
      do k = 1, NGROUP_KNOWN
        if (trim(groups(ig)%name) == trim(GROUP_NAMES(k))) then
          found = .true.
          counts(k) = counts(k) + 1
        end if
      end do
      if (.not. found) then
        write(lnum, '(i0)') groups(ig)%first_line
        call status%add('&'//trim(groups(ig)%name)//': unknown group on deck line '// &
            trim(lnum)//did_you_mean(closest_name(groups(ig)%name, GROUP_NAMES), '&')// &
            ' (valid groups: '//join(GROUP_NAMES)//')')
        cycle
      end if
      known = deck_known_keys(trim(groups(ig)%name))
      do ik = 1, groups(ig)%nkey
        if (any(known == groups(ig)%key(ik))) cycle
        write(lnum, '(i0)') groups(ig)%key_line(ik)
        guess = closest_name(groups(ig)%key(ik), known)
        call status%add('&'//trim(groups(ig)%name)//': '//trim(groups(ig)%key(ik))// &
            ': unknown key on deck line '//trim(lnum)//did_you_mean(guess, '')// &
            ' (valid keys: '//join(known)//')')
      end do
    end do
    ! Every value of a known key against the key's type, reals finite: the
    ! key is named with its deck line, then left out of the namelist read (so
    ! that the read does not stop on it).
    allocate(skips(ngroup), bad(0))
    do ig = 1, ngroup
      allocate(skips(ig)%key(max(groups(ig)%nkey, 1)))
      skips(ig)%key = .false.
      known = deck_known_keys(trim(groups(ig)%name))
      types = deck_key_types(trim(groups(ig)%name))
      if (len(types) /= size(known)) call status%add('&'//trim(groups(ig)%name)// &
          ': internal error: the key types do not match the keys')
      if (len(types) /= size(known)) cycle
      do ik = 1, groups(ig)%nkey
        do k = 1, size(known)
          if (known(k) /= groups(ig)%key(ik)) cycle
          problem = value_problem(groups(ig)%value(ik), types(k:k))
          if (len(problem) == 0) exit
          write(lnum, '(i0)') groups(ig)%key_line(ik)
          skips(ig)%key(ik) = .true.
          bad = [character(len=KEY_LEN + 20) :: bad, instance_name(groups, ig)//': '// &
              trim(groups(ig)%key(ik))//':']
          call status%add(instance_name(groups, ig)//': '//trim(groups(ig)%key(ik))// &
              ': deck line '//trim(lnum)//': '//problem)
          exit
        end do
      end do
    end do
    nbad = size(bad)
    first_read = status%count

    do k = 1, NGROUP_KNOWN
      select case (GROUP_NAMES(k))
      case ('control')
        if (counts(k) == 0) call status%add('&'//trim(GROUP_NAMES(k))// &
            ': required group is missing')
        if (counts(k) > 1) call status%add('&'//trim(GROUP_NAMES(k))// &
            ': group given more than once')
      case ('mesh')
        if (counts(k) == 0) call status%add('&mesh: required group is missing')
      case ('hydro', 'output')
        if (counts(k) > 1) call status%add('&'//trim(GROUP_NAMES(k))// &
            ': group given more than once')
      case ('material', 'block', 'region')
        if (counts(k) == 0) call status%add('&'//trim(GROUP_NAMES(k))// &
            ': at least one is required')
      end select
    end do
    ! Read every known group, unknown keys blanked out, so that every problem
    ! of the deck is reported in this one run.

    allocate(config%materials(counts(4)), config%blocks(counts(5)), config%regions(counts(6)))
    allocate(config%boundaries(counts(7)), config%contacts(counts(9)))
    allocate(config%parts(counts(3)), config%probes(counts(10)))
    counts = 0
    allocate(sections(ngroup))
    do ig = 1, ngroup
      known = deck_known_keys(trim(groups(ig)%name))
      sections(ig)%text = group_text(lines, groups(ig), known, skips(ig)%key)
    end do
    ! &control first: its units decide how library data are read.
    do ig = 1, ngroup
      if (trim(groups(ig)%name) == 'control') call read_control(sections(ig)%text, config, status)
    end do
    do ig = 1, ngroup
      associate(sect => sections(ig)%text)
        select case (trim(groups(ig)%name))
        case ('hydro')
          call read_hydro(sect, config%hydro, status)
        case ('mesh')
          counts(3) = counts(3) + 1
          call read_mesh(sect, counts(3), size(config%parts), config%parts(counts(3)), status, &
              path)
        case ('material')
          counts(4) = counts(4) + 1
          call read_material(sect, counts(4), config%materials(counts(4)), status, &
              config%materials_read, config%units)
        case ('output')
          call read_output(sect, config%output, status)
        end select
      end associate
    end do
    ! Groups that refer to others by name come after those are known.
    call check_material_names(config, status)
    do ig = 1, ngroup
      associate(sect => sections(ig)%text)
        select case (trim(groups(ig)%name))
        case ('block')
          counts(5) = counts(5) + 1
          call read_block(sect, counts(5), config, status)
        case ('region')
          counts(6) = counts(6) + 1
          call read_region(sect, counts(6), config, status)
        case ('boundary')
          counts(7) = counts(7) + 1
          call read_boundary(sect, counts(7), config%boundaries(counts(7)), status)
        case ('contact')
          counts(9) = counts(9) + 1
          call read_contact(sect, counts(9), config%contacts(counts(9)), status, &
              any(groups(ig)%key(:groups(ig)%nkey) == 'symmetric'))
        case ('probe')
          counts(10) = counts(10) + 1
          call read_probe(sect, counts(10), config, status)
        end select
      end associate
    end do
    ! A key whose value was rejected above was not read: what the groups then
    ! say about that key (required, out of range) is not news.
    do k = 1, nbad
      call status%forget(first_read, trim(bad(k)))
    end do
  end subroutine deck_read

  !> Before a restart: the deck against the one stored in the dump. Every key
  !> of &mesh, &material, &block, &region, &boundary, &contact and &hydro must
  !> be the same (compared as parsed key = value, so comments and blanks may
  !> change); &control and &output may change. Each difference is one problem
  !> in status ('&material(1): gamma: changed since the restart dump ...').
  subroutine deck_restart_check(stored_text, deck_text, status)
    character(len=*), intent(in) :: stored_text !< deck text stored in the dump
    character(len=*), intent(in) :: deck_text !< this run's deck text
    type(status_t), intent(inout) :: status
    character(len=8), parameter :: FIXED(7) = [character(len=8) :: 'mesh', 'material', &
        'block', 'region', 'boundary', 'contact', 'hydro']
    type(group_instance_t), allocatable :: old(:), new(:)
    integer :: nold, nnew, g, i, j, k, io, in, count_old, count_new
    type(status_t) :: scratch
    character(len=16) :: a, b
    character(len=:), allocatable :: where

    call deck_scan(split_lines(stored_text), old, nold, scratch)
    call deck_scan(split_lines(deck_text), new, nnew, scratch)
    do g = 1, size(FIXED)
      count_old = count(old(1:nold)%name == FIXED(g))
      count_new = count(new(1:nnew)%name == FIXED(g))
      if (count_old /= count_new) then
        write(a, '(i0)') count_old
        write(b, '(i0)') count_new
        call status%add('&'//trim(FIXED(g))//': the restart dump''s deck has '//trim(a)// &
            ' such group(s), this deck '//trim(b))
        cycle
      end if
      ! The i-th instance in one deck against the i-th in the other.
      io = 0
      in = 0
      do i = 1, count_new
        io = next_instance(old, nold, FIXED(g), io)
        in = next_instance(new, nnew, FIXED(g), in)
        where = instance_name(new(1:nnew), in)
        do k = 1, new(in)%nkey
          j = find_key(old(io), new(in)%key_full(k))
          if (j == 0) then
            call status%add(where//': '//trim(new(in)%key_full(k))//': not in the restart '// &
                'dump''s deck (given here as '//quoted(new(in)%value(k))//')')
          else if (old(io)%value(j) /= new(in)%value(k)) then
            call status%add(where//': '//trim(new(in)%key_full(k))//': changed since the '// &
                'restart dump ('//quoted(old(io)%value(j))//' -> '//quoted(new(in)%value(k))//')')
          end if
        end do
        do j = 1, old(io)%nkey
          if (find_key(new(in), old(io)%key_full(j)) == 0) call status%add(where//': '// &
              trim(old(io)%key_full(j))//': given in the restart dump''s deck ('// &
              quoted(old(io)%value(j))//'), missing here')
        end do
      end do
    end do
    ! &control may change, except its unit system (the numbers would change
    ! meaning; library data are converted with it).
    a = units_of(old, nold)
    b = units_of(new, nnew)
    if (a /= b) call status%add('&control: units: changed since the restart dump ('// &
        quoted(a)//' -> '//quoted(b)//')')

  contains

    !> The unit system a deck's &control gives (lower case, no quotes).
    function units_of(groups, n) result(units)
      type(group_instance_t), intent(in) :: groups(:)
      integer, intent(in) :: n
      character(len=16) :: units
      integer :: m, j
      units = UNITS_CGSUS
      do m = 1, n
        if (groups(m)%name /= 'control') cycle
        j = find_key(groups(m), 'units')
        if (j > 0) units = to_lower(groups(m)%value(j)(2:max(2, len_trim(groups(m)%value(j)) - 1)))
      end do
    end function units_of

    integer function next_instance(groups, n, name, after)
      type(group_instance_t), intent(in) :: groups(:)
      integer, intent(in) :: n, after
      character(len=*), intent(in) :: name
      integer :: m
      next_instance = 0
      do m = after + 1, n
        if (groups(m)%name == name) then
          next_instance = m
          return
        end if
      end do
    end function next_instance

    integer function find_key(group, key)
      type(group_instance_t), intent(in) :: group
      character(len=*), intent(in) :: key
      integer :: m
      find_key = 0
      do m = 1, group%nkey
        if (group%key_full(m) == key) then
          find_key = m
          return
        end if
      end do
    end function find_key

    function quoted(value) result(text)
      character(len=*), intent(in) :: value
      character(len=:), allocatable :: text
      if (len_trim(value) > 60) then
        text = '"'//value(1:57)//'..."'
      else
        text = '"'//trim(value)//'"'
      end if
    end function quoted

  end subroutine deck_restart_check

  !> A text split at its line ends (LF, CR LF) into deck lines.
  function split_lines(text) result(lines)
    character(len=*), intent(in) :: text
    character(len=LINE_LEN), allocatable :: lines(:)
    integer :: n, i, start, last
    n = 0
    do i = 1, len(text)
      if (text(i:i) == achar(10)) n = n + 1
    end do
    if (len(text) > 0) then
      if (text(len(text):len(text)) /= achar(10)) n = n + 1
    end if
    allocate(lines(max(n, 1)))
    lines = ''
    n = 0
    start = 1
    do i = 1, len(text) + 1
      if (i <= len(text)) then
        if (text(i:i) /= achar(10)) cycle
      else if (start > len(text)) then
        exit
      end if
      last = i - 1
      if (last >= start) then
        if (text(last:last) == achar(13)) last = last - 1
      end if
      n = n + 1
      lines(n) = text(start:last)
      start = i + 1
    end do
  end function split_lines

  !> ' (did you mean 'x'?)' when there is a guess, else ''.
  function did_you_mean(guess, prefix) result(text)
    character(len=*), intent(in) :: guess, prefix
    character(len=:), allocatable :: text
    text = ''
    if (len(guess) > 0) text = '; did you mean '''//prefix//guess//'''?'
  end function did_you_mean

  !> A group instance as the messages name it: '&control', '&mesh' (one part)
  !> or '&mesh(2)', '&material(1)', ... (counted in deck order).
  function instance_name(groups, ig) result(name)
    type(group_instance_t), intent(in) :: groups(:)
    integer, intent(in) :: ig
    character(len=:), allocatable :: name
    integer :: n, total, j
    character(len=16) :: buffer
    name = '&'//trim(groups(ig)%name)
    select case (trim(groups(ig)%name))
    case ('control', 'hydro', 'output')
      return
    end select
    n = 0
    total = 0
    do j = 1, size(groups)
      if (groups(j)%name /= groups(ig)%name) cycle
      total = total + 1
      if (j <= ig) n = n + 1
    end do
    if (trim(groups(ig)%name) == 'mesh' .and. total == 1) return
    write(buffer, '(a,i0,a)') '(', n, ')'
    name = name//trim(buffer)
  end function instance_name

  function join(words) result(text)
    character(len=*), intent(in) :: words(:)
    character(len=:), allocatable :: text
    integer :: i
    text = ''
    do i = 1, size(words)
      if (i > 1) text = text//', '
      text = text//trim(words(i))
    end do
  end function join

  !> Rank 0 reads the file; every rank gets the lines and the file's text.
  subroutine read_lines(path, lines, nline, text, status)
    character(len=*), intent(in) :: path
    character(len=LINE_LEN), allocatable, intent(out) :: lines(:)
    integer, intent(out) :: nline
    character(len=:), allocatable, intent(out) :: text !< the file, byte for byte
    type(status_t), intent(inout) :: status
    integer :: unit, ios, i, nbyte
    character(len=LINE_LEN) :: buffer
    character(len=256) :: msg
    logical :: exists

    nline = -1
    if (par_rank() == 0) then
      inquire(file=path, exist=exists)
      if (.not. exists) then
        nline = -1
      else
        open(newunit=unit, file=path, status='old', action='read', iostat=ios, iomsg=msg)
        if (ios /= 0) then
          nline = -2
        else
          nline = 0
          do
            read(unit, '(a)', iostat=ios) buffer
            if (ios /= 0) exit
            nline = nline + 1
          end do
          rewind(unit)
          allocate(lines(nline))
          do i = 1, nline
            read(unit, '(a)') lines(i)
            if (len_trim(lines(i)) == LINE_LEN) nline = -3 - i
          end do
          close(unit)
        end if
      end if
    end if
    nbyte = 0
    if (par_rank() == 0 .and. nline > 0) then
      open(newunit=unit, file=path, status='old', action='read', access='stream', &
          form='unformatted', iostat=ios)
      if (ios == 0) inquire(unit=unit, size=nbyte)
      nbyte = max(nbyte, 0)
      allocate(character(len=nbyte) :: text)
      if (ios == 0 .and. nbyte > 0) read(unit, iostat=ios) text
      if (ios == 0) close(unit)
    end if
    call par_bcast(nline)
    call par_bcast(nbyte)
    if (.not. allocated(text)) allocate(character(len=nbyte) :: text)
    if (nbyte > 0) call par_bcast(text)
    if (nline < -2) then
      write(msg, '(i0,a,i0,a)') -3 - nline, ': longer than ', LINE_LEN - 1, ' characters'
      call status%add('deck: line '//trim(msg))
      return
    end if
    if (nline == 0) then
      call status%add('deck: file '''//trim(path)//''' is empty or not a text file')
      return
    else if (nline == -1) then
      call status%add('deck: file '''//trim(path)//''' does not exist')
      return
    else if (nline == -2) then
      call status%add('deck: file '''//trim(path)//''' cannot be opened')
      return
    end if
    if (.not. allocated(lines)) allocate(lines(nline))
    if (nline > 0) call par_bcast(lines)
  end subroutine read_lines

  subroutine nml_error(group, ios, msg, status)
    character(len=*), intent(in) :: group, msg
    integer, intent(in) :: ios
    type(status_t), intent(inout) :: status
    if (ios /= 0) call status%add('&'//group//': cannot read the group: '//trim(msg))
  end subroutine nml_error

  subroutine read_control(sect, config, status)
    character(len=LINE_LEN), intent(in) :: sect(:)
    type(config_t), intent(inout) :: config
    type(status_t), intent(inout) :: status
    character(len=80) :: title
    character(len=PATH_LEN) :: restart
    real(rk) :: t_end, cfl, dt_initial, dt_max, dt_min, dt_growth, dvol_max
    integer :: max_cycles, deck_version, ios, fault_cycle, stop_check_every
    character(len=8) :: fault_kind
    character(len=PATH_LEN) :: stop_file
    real(rk) :: wall_limit
    character(len=256) :: msg
    character(len=16) :: units
    namelist /control/ title, t_end, max_cycles, deck_version, restart, cfl, dt_initial, &
        dt_max, dt_min, dt_growth, dvol_max, fault_cycle, fault_kind, wall_limit, stop_file, &
        stop_check_every, units

    title = config%title
    t_end = config%t_end
    max_cycles = config%max_cycles
    fault_cycle = 0
    fault_kind = 'nan'
    wall_limit = config%wall_limit
    stop_file = config%stop_file
    stop_check_every = config%stop_check_every
    deck_version = DECK_FORMAT_VERSION
    restart = ''
    units = config%units
    cfl = config%hydro%cfl
    dt_initial = config%hydro%dt_initial
    dt_max = config%hydro%dt_max
    dt_min = config%hydro%dt_min
    dt_growth = config%hydro%dt_growth
    dvol_max = config%hydro%dvol_max
    read(sect, nml=control, iostat=ios, iomsg=msg)
    call nml_error('control', ios, msg, status)
    if (ios /= 0) return
    if (deck_version /= DECK_FORMAT_VERSION) call status%add('&control: deck_version: this code '// &
        'reads deck version 1 only')
    if (t_end == UNSET) then
      call status%add('&control: t_end: required (end time of the run, > 0)')
    else if (.not. (t_end > 0.0_rk)) then
      call status%add('&control: t_end: must be > 0')
    end if
    if (max_cycles < 1) call status%add('&control: max_cycles: must be >= 1')
    if (fault_cycle < 0) call status%add('&control: fault_cycle: must be >= 0')
    if (fault_kind /= 'nan' .and. fault_kind /= 'tangle') call status%add('&control: '// &
        'fault_kind: '''//trim(fault_kind)//''' is not a fault (valid: nan, tangle)')
    config%fault_cycle = fault_cycle
    if (wall_limit < 0.0_rk) call status%add('&control: wall_limit: must be >= 0 '// &
        '(seconds; 0 = none)')
    if (len_trim(stop_file) == 0 .or. index(stop_file, '/') > 0) call status%add('&control: '// &
        'stop_file: must be a file name (in the output directory) without ''/''')
    if (stop_check_every < 1) call status%add('&control: stop_check_every: must be >= 1')
    config%wall_limit = wall_limit
    config%stop_file = stop_file
    config%stop_check_every = stop_check_every
    config%fault_kind = fault_kind
    if (.not. units_valid(to_lower(units))) call status%add('&control: units: '''// &
        trim(units)//''' is not a unit system (valid: '//UNITS_LIST//')')
    config%units = to_lower(units)
    if (.not. (cfl > 0.0_rk .and. cfl <= 1.0_rk)) call status%add('&control: cfl: must be '// &
        'in (0, 1]')
    if (dt_initial < 0.0_rk) call status%add('&control: dt_initial: must be >= 0 '// &
        '(0 = from the stability limit)')
    if (.not. (dt_max > 0.0_rk)) call status%add('&control: dt_max: must be > 0')
    if (.not. (dt_min > 0.0_rk)) call status%add('&control: dt_min: must be > 0')
    if (dt_min > 0.0_rk .and. dt_max > 0.0_rk .and. dt_min >= dt_max) call status%add( &
        '&control: dt_min: must be smaller than dt_max')
    if (dt_initial > 0.0_rk .and. dt_initial < dt_min) call status%add('&control: '// &
        'dt_initial: must be >= dt_min')
    if (.not. (dt_growth >= 1.0_rk)) call status%add('&control: dt_growth: must be >= 1')
    if (.not. (dvol_max > 0.0_rk .and. dvol_max < 1.0_rk)) call status%add('&control: '// &
        'dvol_max: must be in (0, 1)')
    config%title = title
    config%t_end = t_end
    config%max_cycles = max_cycles
    config%restart = restart
    config%hydro%cfl = cfl
    config%hydro%dt_initial = dt_initial
    config%hydro%dt_max = dt_max
    config%hydro%dt_min = dt_min
    config%hydro%dt_growth = dt_growth
    config%hydro%dvol_max = dvol_max
  end subroutine read_control

  subroutine read_hydro(sect, opt, status)
    character(len=LINE_LEN), intent(in) :: sect(:)
    type(hydro_options_t), intent(inout) :: opt
    type(status_t), intent(inout) :: status
    real(rk) :: q_linear, q_quadratic, hourglass_coefficient
    character(len=32) :: hourglass
    logical :: q_limiter, q_linear_limited
    integer :: ios
    character(len=256) :: msg
    namelist /hydro/ q_linear, q_quadratic, q_limiter, q_linear_limited, hourglass, &
        hourglass_coefficient

    q_limiter = opt%q_limiter
    q_linear_limited = opt%q_linear_limited
    q_linear = opt%q_linear
    q_quadratic = opt%q_quadratic
    hourglass = 'viscous'
    hourglass_coefficient = opt%hourglass_coefficient
    read(sect, nml=hydro, iostat=ios, iomsg=msg)
    call nml_error('hydro', ios, msg, status)
    if (ios /= 0) return
    if (q_linear < 0.0_rk) call status%add('&hydro: q_linear: must be >= 0')
    if (q_quadratic < 0.0_rk) call status%add('&hydro: q_quadratic: must be >= 0')
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
    opt%q_linear = q_linear
    opt%q_quadratic = q_quadratic
    opt%q_limiter = q_limiter
    opt%q_linear_limited = q_linear_limited
    opt%hourglass_coefficient = hourglass_coefficient
  end subroutine read_hydro

  subroutine read_mesh(sect, index, nparts, part, status, deck_path)
    character(len=LINE_LEN), intent(in) :: sect(:)
    integer, intent(in) :: index !< this group's place among the &mesh groups
    integer, intent(in) :: nparts !< number of &mesh groups
    type(mesh_part_t), intent(inout) :: part
    type(status_t), intent(inout) :: status
    character(len=*), intent(in) :: deck_path !< mesh files are relative to its directory
    character(len=16) :: type, sector
    real(rk) :: x(MAX_INTERVALS + 1), y(MAX_INTERVALS + 1), z(MAX_INTERVALS + 1)
    real(rk) :: ratio_x(MAX_INTERVALS), ratio_y(MAX_INTERVALS), ratio_z(MAX_INTERVALS)
    integer :: nx(MAX_INTERVALS), ny(MAX_INTERVALS), nz(MAX_INTERVALS)
    real(rk) :: skew_amplitude, perturb
    real(rk) :: radius, length, z0, axial_ratio, core_fraction, ri, ro, axis(3), origin(3)
    real(rk) :: radial_reference(3)
    real(rk) :: radial_ratio
    integer :: n_core, n_radial, n_axial, n_theta, n_patch
    character(len=PATH_LEN) :: file
    character(len=NAME_LEN) :: name, block
    real(rk) :: offset(3), rotation_axis(3), rotation_angle
    character(len=16) :: where
    integer :: ios
    character(len=256) :: msg
    logical :: box_keys, curved_keys, exists
    namelist /mesh/ type, x, y, z, nx, ny, nz, ratio_x, ratio_y, ratio_z, skew_amplitude, perturb, &
        radius, length, z0, sector, n_core, n_radial, n_axial, axial_ratio, core_fraction, ri, ro, &
        n_theta, axis, origin, radial_reference, n_patch, radial_ratio, file, name, offset, block, &
        rotation_axis, rotation_angle

    type = 'box'
    x = UNSET
    y = UNSET
    z = UNSET
    nx = 0
    ny = 0
    nz = 0
    ratio_x = 1.0_rk
    ratio_y = 1.0_rk
    ratio_z = 1.0_rk
    skew_amplitude = 0.0_rk
    perturb = 0.0_rk
    radius = UNSET
    length = UNSET
    z0 = UNSET
    sector = ''
    n_core = -1
    n_radial = -1
    n_axial = -1
    axial_ratio = UNSET
    core_fraction = UNSET
    ri = UNSET
    ro = UNSET
    n_theta = -1
    axis = UNSET
    origin = UNSET
    radial_reference = UNSET
    n_patch = -1
    radial_ratio = UNSET
    file = ''
    name = ''
    offset = 0.0_rk
    rotation_axis = 0.0_rk
    rotation_angle = 0.0_rk
    block = ''
    where = '&mesh'
    if (nparts > 1) write(where, '(a,i0,a)') '&mesh(', index, ')'
    read(sect, nml=mesh, iostat=ios, iomsg=msg)
    call nml_error(trim(where(2:)), ios, msg, status)
    if (ios /= 0) return
    part%mesh_type = to_lower(type)
    part%name = name
    part%offset = offset
    part%rotation_axis = rotation_axis
    part%rotation_angle = rotation_angle
    part%block = block
    if (.not. (abs(rotation_angle) < huge(1.0_rk))) call status%add(trim(where)// &
        ': rotation_angle: must be finite (degrees)')
    if (rotation_angle /= 0.0_rk .and. .not. norm2(rotation_axis) > 0.0_rk) &
        call status%add(trim(where)//': rotation_axis: required with rotation_angle '// &
        '(a nonzero vector)')
    if (nparts > 1 .and. len_trim(name) == 0) call status%add(trim(where)//': name: required '// &
        'when the deck has several &mesh parts (it prefixes the part''s face sets)')
    if (.not. all(abs(offset) < huge(1.0_rk))) call status%add(trim(where)//': offset: '// &
        'must be finite')
    box_keys = any(x /= UNSET) .or. any(nx /= 0) .or. skew_amplitude /= 0.0_rk .or. &
        perturb /= 0.0_rk
    curved_keys = radius /= UNSET .or. length /= UNSET .or. ri /= UNSET .or. ro /= UNSET .or. &
        n_radial /= -1 .or. n_axial /= -1 .or. n_theta /= -1 .or. n_patch /= -1 .or. &
        n_core /= -1
    select case (part%mesh_type)
    case ('box')
      if (curved_keys) call status%add(trim(where)//': type: ''box'' takes x, y, z, nx, ny, nz, '// &
          'ratio_*, skew_amplitude, perturb (radius, ri, ro, n_* belong to the curved types)')
      call direction('x', x, nx, ratio_x, 1)
      call direction('y', y, ny, ratio_y, 2)
      call direction('z', z, nz, ratio_z, 3)
      part%box%skew_amplitude = skew_amplitude
      if (perturb < 0.0_rk .or. perturb >= 0.5_rk) call status%add(trim(where)//': perturb: must be '// &
          'in [0, 0.5) (fraction of the local zone size)')
      part%box%perturb = perturb
    case ('rod')
      if (box_keys) call status%add(trim(where)//': type: ''rod'' does not take box keys (x, nx, ...)')
      if (radius /= UNSET) part%rod%radius = radius
      if (length /= UNSET) part%rod%length = length
      if (z0 /= UNSET) part%rod%z0 = z0
      if (len_trim(sector) > 0) part%rod%sector = to_lower(sector)
      if (n_core /= -1) part%rod%n_core = n_core
      if (n_radial /= -1) part%rod%n_radial = n_radial
      if (n_axial /= -1) part%rod%n_axial = n_axial
      if (axial_ratio /= UNSET) part%rod%axial_ratio = axial_ratio
      if (core_fraction /= UNSET) part%rod%core_fraction = core_fraction
    case ('tube')
      if (box_keys) call status%add(trim(where)//': type: ''tube'' does not take box keys (x, nx, ...)')
      if (ri /= UNSET) part%tube%ri = ri
      if (ro /= UNSET) part%tube%ro = ro
      if (length /= UNSET) part%tube%length = length
      if (len_trim(sector) > 0) part%tube%sector = to_lower(sector)
      if (n_theta /= -1) part%tube%n_theta = n_theta
      if (n_radial /= -1) part%tube%n_radial = n_radial
      if (n_axial /= -1) part%tube%n_axial = n_axial
      if (axial_ratio /= UNSET) part%tube%axial_ratio = axial_ratio
      if (all(axis /= UNSET)) part%tube%axis = axis
      if (all(origin /= UNSET)) part%tube%origin = origin
      if (all(radial_reference /= UNSET)) part%tube%radial_reference = radial_reference
    case ('shell')
      if (box_keys) call status%add(trim(where)//': type: ''shell'' does not take box keys (x, nx, ...)')
      if (ri /= UNSET) part%shell%ri = ri
      if (ro /= UNSET) part%shell%ro = ro
      if (n_patch /= -1) part%shell%n_patch = n_patch
      if (n_radial /= -1) part%shell%n_radial = n_radial
      if (radial_ratio /= UNSET) part%shell%radial_ratio = radial_ratio
    case ('ball')
      if (box_keys) call status%add(trim(where)//': type: ''ball'' does not take box keys '// &
          '(x, nx, ...)')
      if (length /= UNSET .or. ri /= UNSET .or. ro /= UNSET .or. n_axial /= -1 .or. &
          n_theta /= -1 .or. n_patch /= -1) call status%add(trim(where)//': type: ''ball'' '// &
          'takes radius, n_core, n_radial, radial_ratio, core_fraction')
      if (radius /= UNSET) part%ball%radius = radius
      if (n_core /= -1) part%ball%n_core = n_core
      if (n_radial /= -1) part%ball%n_radial = n_radial
      if (radial_ratio /= UNSET) part%ball%radial_ratio = radial_ratio
      if (core_fraction /= UNSET) part%ball%core_fraction = core_fraction
      associate(ball => part%ball)
        if (.not. (ball%radius > 0.0_rk)) call status%add(trim(where)//': radius: must be > 0')
        if (ball%n_core < 1) call status%add(trim(where)//': n_core: must be >= 1')
        if (ball%n_radial < 1) call status%add(trim(where)//': n_radial: must be >= 1')
        if (.not. (ball%radial_ratio > 0.0_rk)) call status%add(trim(where)//': radial_ratio: '// &
            'must be > 0')
        if (.not. (ball%core_fraction >= 0.2_rk .and. ball%core_fraction <= 0.5_rk)) &
            call status%add(trim(where)//': core_fraction: must be in [0.2, 0.5] (the core '// &
            'corner inside the sphere)')
      end associate
    case ('box_minus_ball')
      if (box_keys) call status%add(trim(where)//': type: ''box_minus_ball'' does not take box '// &
          'keys (x, nx, ...)')
      if (ri /= UNSET .or. ro /= UNSET .or. n_axial /= -1 .or. n_theta /= -1 .or. &
          n_core /= -1) call status%add(trim(where)//': type: ''box_minus_ball'' takes '// &
          'radius, length, n_patch, n_radial, radial_ratio')
      if (radius /= UNSET) part%box_minus_ball%radius = radius
      if (length /= UNSET) part%box_minus_ball%length = length
      if (n_patch /= -1) part%box_minus_ball%n_patch = n_patch
      if (n_radial /= -1) part%box_minus_ball%n_radial = n_radial
      if (radial_ratio /= UNSET) part%box_minus_ball%radial_ratio = radial_ratio
      associate(cavity => part%box_minus_ball)
        if (.not. (cavity%radius > 0.0_rk)) call status%add(trim(where)//': radius: must be > 0')
        if (.not. (cavity%length > cavity%radius)) call status%add(trim(where)//': length: '// &
            'must be > radius (the box edge beyond the sphere)')
        if (cavity%n_patch < 1) call status%add(trim(where)//': n_patch: must be >= 1')
        if (cavity%n_radial < 1) call status%add(trim(where)//': n_radial: must be >= 1')
        if (.not. (cavity%radial_ratio > 0.0_rk)) call status%add(trim(where)//': '// &
            'radial_ratio: must be > 0')
      end associate
    case ('gmsh', 'exodus')
      if (box_keys .or. curved_keys) call status%add(trim(where)//': type: '''//trim(type)// &
          ''' takes only file')
      if (len_trim(file) == 0) then
        if (part%mesh_type == 'gmsh') then
          call status%add(trim(where)//': file: required for type = ''gmsh'' (a .msh file)')
        else
          call status%add(trim(where)//': file: required for type = ''exodus'' (an Exodus II '// &
              'file, .exo or .e)')
        end if
      else
        part%mesh_file = file
        part%mesh_path = path_from_deck(deck_path, file)
        exists = .false.
        if (par_rank() == 0) inquire(file=part%mesh_path, exist=exists)
        call par_bcast(exists)
        if (.not. exists) then
          if (file(1:1) == '/') then
            call status%add(trim(where)//': file: '''//part%mesh_path//''' does not exist')
          else
            call status%add(trim(where)//': file: '''//part%mesh_path//''' does not exist '// &
                '(a relative path is taken from the deck''s directory, '''// &
                path_absolute(path_directory(deck_path))//''')')
          end if
        end if
      end if
    case default
      call status%add(trim(where)//': type: '''//trim(type)//''' is not a mesh type (valid: box, '// &
          'rod, tube, shell, ball, box_minus_ball, gmsh, exodus)')
    end select

  contains

    subroutine direction(axis, points, zones, ratio, d)
      character(len=1), intent(in) :: axis
      real(rk), intent(in) :: points(:), ratio(:)
      integer, intent(in) :: zones(:), d
      integer :: nint, npoint, i
      nint = count(zones /= 0)
      npoint = count(points /= UNSET)
      if (nint == 0) then
        call status%add(trim(where)//': n'//axis//': required (zones in each interval along '//axis//')')
        return
      end if
      if (any(zones(1:nint) < 1) .or. any(zones(nint + 1:) /= 0)) then
        call status%add(trim(where)//': n'//axis//': every interval needs >= 1 zone')
        return
      end if
      if (npoint /= nint + 1 .or. any(points(1:npoint) == UNSET)) then
        call status%add(trim(where)//': '//axis//': needs one more point than n'//axis// &
            ' has intervals (the interval ends)')
        return
      end if
      do i = 1, nint
        if (.not. (points(i + 1) > points(i))) then
          call status%add(trim(where)//': '//axis//': points must increase')
          return
        end if
        if (.not. (ratio(i) > 0.0_rk)) then
          call status%add(trim(where)//': ratio_'//axis//': must be > 0')
          return
        end if
      end do
      part%box%nint(d) = nint
      part%box%breaks(0:nint, d) = points(1:nint + 1)
      part%box%zones(1:nint, d) = zones(1:nint)
      part%box%ratio(1:nint, d) = ratio(1:nint)
    end subroutine direction

  end subroutine read_mesh

  subroutine read_material(sect, index, mat, status, read_ok, units)
    use material_flow_stress, only: steinberg_guinan_t, johnson_cook_t, SG_REFERENCE_TEMPERATURE
    character(len=LINE_LEN), intent(in) :: sect(:)
    integer, intent(in) :: index
    type(material_t), intent(inout) :: mat
    type(status_t), intent(inout) :: status
    logical, intent(inout) :: read_ok !< set false when the group cannot be read
    character(len=*), intent(in) :: units !< &control units: library data are converted to it
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
    integer :: ios
    logical :: found, sg_cold_energy
    character(len=256) :: msg
    character(len=16) :: where
    namelist /material/ name, eos, gamma, library, rho0, c0, s1, gamma0, b, p_min, strength, &
        shear_modulus, yield_stress, hardening_modulus, cv, jc_a, jc_b, jc_n, jc_c, jc_m, &
        eps_dot0, t_room, t_melt, sg_beta, sg_n, sg_ymax, sg_eps_i, sg_a, sg_b, sg_tmelt0, &
        sg_gamma0, sg_a_melt, sg_cold_energy

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
            ''' is not a built-in material (valid: al6061, cu_ofhc, cu_taylor, ss304, be_verney)')
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
      if (rho0 /= UNSET) mat%mg%rho0 = rho0
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

  contains

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

  subroutine check_material_names(config, status)
    type(config_t), intent(in) :: config
    type(status_t), intent(inout) :: status
    integer :: i, j
    do i = 1, size(config%materials)
      do j = 1, i - 1
        if (len_trim(config%materials(i)%name) > 0 .and. &
            config%materials(i)%name == config%materials(j)%name) call status%add( &
            '&material: name: '''//trim(config%materials(i)%name)//''' is given twice')
      end do
    end do
  end subroutine check_material_names

  subroutine read_block(sect, index, config, status)
    character(len=LINE_LEN), intent(in) :: sect(:)
    integer, intent(in) :: index
    type(config_t), intent(inout) :: config
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
    box = config%blocks(index)%box
    read(sect, nml=block, iostat=ios, iomsg=msg)
    if (ios /= 0) then
      call status%add(trim(where)//': cannot read the group: '//trim(msg))
      return
    end if
    if (len_trim(name) == 0) call status%add(trim(where)//': name: required')
    do i = 1, index - 1
      if (config%blocks(i)%name == name) call status%add(trim(where)//': name: '''// &
          trim(name)//''' is given twice')
    end do
    config%blocks(index)%name = name
    config%blocks(index)%box = box
    if (box(1) > box(2) .or. box(3) > box(4) .or. box(5) > box(6)) call status%add( &
        trim(where)//': box: needs xmin <= xmax, ymin <= ymax, zmin <= zmax')
    config%blocks(index)%material = 0
    do i = 1, size(config%materials)
      if (config%materials(i)%name == material) config%blocks(index)%material = i
    end do
    if (len_trim(material) == 0) then
      call status%add(trim(where)//': material: required')
    else if (config%blocks(index)%material == 0 .and. config%materials_read) then
      call status%add(trim(where)//': material: '''//trim(material)// &
          ''' is not a material of this deck')
    end if
  end subroutine read_block

  subroutine read_region(sect, index, config, status)
    character(len=LINE_LEN), intent(in) :: sect(:)
    integer, intent(in) :: index
    type(config_t), intent(inout) :: config
    type(status_t), intent(inout) :: status
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
      do i = 1, size(config%blocks)
        if (config%blocks(i)%name == block) r%block = i
      end do
      if (r%block == 0) call status%add(trim(where)//': block: '''//trim(block)// &
          ''' is not a block of this deck')
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
    config%regions(index) = r
    ! A density far from the material's reference density is the usual sign of
    ! mixed units: rank 0 warns, once, before the run.
    if (par_rank() == 0 .and. density /= UNSET .and. density > 0.0_rk .and. &
        config%materials_read) call warn_density()

  contains

    !> Warn when the density is more than 20% from the rho0 of the region's
    !> material: that of its block, or without block that of every block whose
    !> box meets the region's box (silent when any of them is within 20%, or
    !> has no reference density).
    subroutine warn_density()
      use, intrinsic :: iso_fortran_env, only: error_unit
      real(rk), parameter :: TOLERANCE = 0.2_rk
      logical :: listed(size(config%materials))
      character(len=512) :: names
      character(len=16) :: text
      integer :: k, m
      real(rk) :: rho_ref
      listed = .false.
      names = ''
      do k = 1, size(config%blocks)
        if (r%block > 0 .and. k /= r%block) cycle
        if (r%block == 0 .and. .not. boxes_meet(config%blocks(k)%box, box)) cycle
        m = config%blocks(k)%material
        if (m == 0) cycle
        if (listed(m)) cycle
        if (config%materials(m)%eos /= EOS_MIE_GRUNEISEN) return
        rho_ref = config%materials(m)%mg%rho0
        if (.not. (rho_ref > 0.0_rk)) return
        if (abs(density - rho_ref) <= TOLERANCE * rho_ref) return
        listed(m) = .true.
        write(text, '(es11.4)') rho_ref
        if (len_trim(names) > 0) names = trim(names)//', '
        names = trim(names)//''''//trim(config%materials(m)%name)//''' (rho0 = '// &
            trim(adjustl(text))//')'
      end do
      if (.not. any(listed)) return
      write(text, '(es11.4)') density
      write(error_unit, '(a)') 'warning: '//trim(where)//': density: '// &
          trim(adjustl(text))//' differs by more than 20% from the rho0 of material '// &
          trim(names)//' (mixed units?)'
    end subroutine warn_density

    logical function boxes_meet(a, b)
      real(rk), intent(in) :: a(6), b(6)
      boxes_meet = a(1) <= b(2) .and. b(1) <= a(2) .and. a(3) <= b(4) .and. b(3) <= a(4) &
          .and. a(5) <= b(6) .and. b(5) <= a(6)
    end function boxes_meet

  end subroutine read_region

  subroutine read_boundary(sect, index, bc, status)
    character(len=LINE_LEN), intent(in) :: sect(:)
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

  subroutine read_contact(sect, index, pair, status, symmetric_given)
    character(len=LINE_LEN), intent(in) :: sect(:)
    integer, intent(in) :: index
    type(contact_spec_t), intent(inout) :: pair
    type(status_t), intent(inout) :: status
    logical, intent(in) :: symmetric_given !< the deck sets symmetric
    character(len=NAME_LEN) :: name, master
    character(len=SURFACE_LEN) :: surface_a, surface_b
    character(len=16) :: method, form, normal, on_penetration, initial_penetration
    real(rk) :: capture, penetration_warning, search_margin, recovery, penetration_tolerance
    real(rk) :: friction
    logical :: symmetric
    integer :: search_every, sweeps, ios
    character(len=256) :: msg
    character(len=16) :: where
    namelist /contact/ name, surface_a, surface_b, method, master, capture, &
        penetration_warning, search_margin, search_every, form, sweeps, recovery, normal, &
        penetration_tolerance, on_penetration, initial_penetration, friction, symmetric

    write(where, '(a,i0,a)') '&contact(', index, ')'
    name = ''
    surface_a = ''
    surface_b = ''
    method = ''
    master = ''
    capture = pair%capture
    penetration_warning = -1.0_rk
    penetration_tolerance = pair%penetration_tolerance
    on_penetration = pair%on_penetration
    initial_penetration = pair%initial_penetration
    search_margin = pair%search_margin
    search_every = pair%search_every
    sweeps = pair%sweeps
    recovery = pair%recovery
    friction = pair%friction
    symmetric = pair%symmetric
    form = ''
    normal = ''
    read(sect, nml=contact, iostat=ios, iomsg=msg)
    if (ios /= 0) then
      call status%add(trim(where)//': cannot read the group: '//trim(msg))
      return
    end if
    pair%name = name
    if (len_trim(surface_a) == 0) call status%add(trim(where)//': surface_a: required '// &
        '(a face set)')
    pair%surface_a = surface_a
    pair%surface_b = surface_b
    if (len_trim(surface_b) == 0) pair%surface_b = surface_a
    select case (to_lower(method))
    case ('dam', 'dlm')
      pair%method = to_lower(method)
    case ('')
      call status%add(trim(where)//': method: required (valid: dam, dlm)')
    case default
      call status%add(trim(where)//': method: '''//trim(method)//''' is not a contact '// &
          'method (valid: dam, dlm)')
    end select
    select case (to_lower(master))
    case ('')
      pair%master = 'b'
    case ('a', 'b')
      pair%master = to_lower(master)
      if (to_lower(method) == 'dlm') call status%add(trim(where)//': master: DLM is '// &
          'symmetric and has no master side')
    case default
      call status%add(trim(where)//': master: must be ''a'' or ''b'' (the master side for DAM)')
    end select
    select case (to_lower(form))
    case ('')
    case ('coordinate', 'velocity', 'combined')
      pair%form = to_lower(form)
      if (to_lower(method) == 'dam') call status%add(trim(where)//': form: only DLM has '// &
          'forms (coordinate, velocity, combined)')
    case default
      call status%add(trim(where)//': form: '''//trim(form)//''' is not a DLM form (valid: '// &
          'coordinate, velocity, combined)')
    end select
    select case (to_lower(normal))
    case ('')
    case ('master', 'slave')
      pair%normal = to_lower(normal)
      if (to_lower(method) == 'dlm') call status%add(trim(where)//': normal: only for DAM '// &
          '(DLM uses the common normal of each segment pair)')
    case default
      call status%add(trim(where)//': normal: '''//trim(normal)//''' is not a DAM normal '// &
          '(valid: master, slave)')
    end select
    if (.not. (capture >= 0.0_rk)) call status%add(trim(where)//': capture: must be >= 0')
    if (penetration_warning /= -1.0_rk) call status%add(trim(where)// &
        ': penetration_warning: replaced by penetration_tolerance (a length; default the '// &
        'larger of 5% of the smaller adjacent segment and the faceting sagitta)')
    if (.not. (penetration_tolerance >= 0.0_rk)) call status%add(trim(where)// &
        ': penetration_tolerance: must be >= 0 (a length; 0 = automatic)')
    select case (to_lower(on_penetration))
    case ('warn', 'stop')
      pair%on_penetration = to_lower(on_penetration)
    case default
      call status%add(trim(where)//': on_penetration: '''//trim(on_penetration)// &
          ''' is not a choice (valid: warn, stop)')
    end select
    select case (to_lower(initial_penetration))
    case ('error', 'adjust', 'ignore')
      pair%initial_penetration = to_lower(initial_penetration)
    case default
      call status%add(trim(where)//': initial_penetration: '''//trim(initial_penetration)// &
          ''' is not a choice (valid: error, adjust, ignore)')
    end select
    if (.not. (search_margin >= 0.0_rk)) call status%add(trim(where)// &
        ': search_margin: must be >= 0 (0 = automatic)')
    if (search_every < 0) call status%add(trim(where)//': search_every: must be >= 0 '// &
        '(0 = automatic)')
    pair%capture = capture
    pair%penetration_tolerance = penetration_tolerance
    pair%search_margin = search_margin
    pair%search_every = search_every
    if (sweeps < 1) call status%add(trim(where)//': sweeps: must be >= 1')
    pair%sweeps = sweeps
    if (recovery /= pair%recovery) then
      if (.not. (recovery >= 0.0_rk .and. recovery <= 0.5_rk)) call status%add(trim(where)// &
          ': recovery: must be in [0, 0.5] (fraction of the penetration removed per step)')
      if (to_lower(method) == 'dam' .or. .not. (form == '' .or. to_lower(form) == 'velocity')) &
          call status%add(trim(where)//': recovery: only for the DLM velocity form')
    end if
    pair%recovery = recovery
    if (.not. (friction >= 0.0_rk)) call status%add(trim(where)// &
        ': friction: must be >= 0 (the Coulomb coefficient; 0 = frictionless)')
    pair%friction = friction
    if (symmetric_given .and. to_lower(method) == 'dlm') call status%add(trim(where)// &
        ': symmetric: only for DAM (DLM is symmetric: every facet pair acts on both sides)')
    if (symmetric_given .and. (surface_a == surface_b .or. len_trim(surface_b) == 0)) &
        call status%add(trim(where)//': symmetric: not for self-contact (every node of '// &
        'the surface is a slave already)')
    pair%symmetric = symmetric .and. to_lower(method) == 'dam'
  end subroutine read_contact

  !> One &probe group. The node range and whether the point lies in the mesh
  !> are checked when the mesh is built (io_probe).
  subroutine read_probe(sect, index, config, status)
    character(len=LINE_LEN), intent(in) :: sect(:)
    integer, intent(in) :: index
    type(config_t), intent(inout) :: config
    type(status_t), intent(inout) :: status
    character(len=NAME_LEN) :: name
    character(len=256) :: fields
    integer :: node, every, ios, i, k, start
    real(rk) :: point(3), interval
    character(len=256) :: msg
    character(len=:), allocatable :: where, word
    character(len=PROBE_FIELD_LEN), allocatable :: list(:)
    logical :: strength
    namelist /probe/ name, node, point, fields, every, interval

    name = ''
    node = 0
    point = huge(1.0_rk)
    fields = ''
    every = 0
    interval = 0.0_rk
    read(sect, nml=probe, iostat=ios, iomsg=msg)
    if (ios /= 0) then
      write(msg, '(a,i0,a)') '&probe(', index, '): cannot read the group: '//trim(msg)
      call status%add(trim(msg))
      return
    end if
    if (len_trim(name) == 0) then
      write(msg, '(a,i0,a)') '&probe(', index, ')'
      where = trim(msg)
      call status%add(where//': name: required (the file is probe_<name>.csv)')
    else
      where = '&probe '''//trim(name)//''''
    end if
    if (verify(trim(name), 'abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ0123456789_-.') &
        /= 0) call status%add(where//': name: only letters, digits, ''_'', ''-'' and ''.'' '// &
        '(it names the file probe_<name>.csv)')
    do i = 1, index - 1
      if (config%probes(i)%name == name .and. len_trim(name) > 0) call status%add(where// &
          ': name: given to two probes')
    end do
    config%probes(index)%name = name
    config%probes(index)%at_point = any(point /= huge(1.0_rk))
    if (config%probes(index)%at_point .and. any(point == huge(1.0_rk))) call status%add( &
        where//': point: needs 3 coordinates x, y, z')
    if (node /= 0 .and. config%probes(index)%at_point) then
      call status%add(where//': node: give either node or point, not both')
    else if (node == 0 .and. .not. config%probes(index)%at_point) then
      call status%add(where//': node: required, or point (where the probe is)')
    else if (node < 0) then
      call status%add(where//': node: must be a global node id >= 1')
    end if
    config%probes(index)%node = node
    if (config%probes(index)%at_point) config%probes(index)%point = point
    ! Fields: names separated by blanks or commas.
    allocate(list(0))
    start = 0
    do k = 1, len_trim(fields) + 1
      if (k <= len_trim(fields)) then
        if (fields(k:k) /= ' ' .and. fields(k:k) /= ',') then
          if (start == 0) start = k
          cycle
        end if
      end if
      if (start == 0) cycle
      word = to_lower(fields(start:k - 1))
      start = 0
      if (.not. any(PROBE_FIELDS == word)) then
        call status%add(where//': fields: '''//word//''' is not a probe field (valid: '// &
            join(PROBE_FIELDS)//')')
      else if (any(list == word)) then
        call status%add(where//': fields: '''//word//''' is given twice')
      else
        list = [character(len=PROBE_FIELD_LEN) :: list, word]
      end if
    end do
    if (len_trim(fields) == 0) call status%add(where//': fields: required (one or more of: '// &
        join(PROBE_FIELDS)//')')
    strength = .false.
    if (allocated(config%materials)) strength = any(config%materials%strength /= STRENGTH_NONE)
    if ((any(list == 'stress') .or. any(list == 'plastic_strain')) .and. .not. strength .and. &
        config%materials_read) call status%add(where//': fields: stress and plastic_strain '// &
        'need a &material with strength')
    config%probes(index)%fields = list
    if (every /= 0 .and. interval /= 0.0_rk) then
      call status%add(where//': every: give either every (cycles) or interval (time), not both')
    else if (every < 0) then
      call status%add(where//': every: must be >= 1 (cycles between rows)')
    else if (.not. (interval >= 0.0_rk)) then
      call status%add(where//': interval: must be > 0 (simulated time between rows)')
    end if
    if (every == 0 .and. interval == 0.0_rk) every = 1
    config%probes(index)%every = every
    config%probes(index)%interval = interval
  end subroutine read_probe

  subroutine read_output(sect, out, status)
    character(len=LINE_LEN), intent(in) :: sect(:)
    type(output_options_t), intent(inout) :: out
    type(status_t), intent(inout) :: status
    character(len=PATH_LEN) :: directory
    character(len=NAME_LEN) :: prefix
    real(rk) :: dump_interval
    integer :: dump_cycles, status_every, history_every, ios
    character(len=256) :: msg
    namelist /output/ directory, prefix, dump_interval, dump_cycles, status_every, history_every

    directory = out%directory
    prefix = out%prefix
    dump_interval = out%dump_interval
    dump_cycles = out%dump_cycles
    status_every = out%status_every
    history_every = out%history_every
    read(sect, nml=output, iostat=ios, iomsg=msg)
    call nml_error('output', ios, msg, status)
    if (ios /= 0) return
    if (dump_interval < 0.0_rk) call status%add('&output: dump_interval: must be >= 0')
    if (dump_cycles < 0) call status%add('&output: dump_cycles: must be >= 0')
    if (status_every < 1) call status%add('&output: status_every: must be >= 1')
    if (history_every < 1) call status%add('&output: history_every: must be >= 1')
    if (len_trim(prefix) == 0 .or. index(prefix, '/') > 0) call status%add('&output: '// &
        'prefix: must be a non-empty file name without ''/''')
    if (len_trim(directory) == 0) call status%add('&output: directory: must not be empty')
    out%directory = directory
    out%prefix = prefix
    out%dump_interval = dump_interval
    out%dump_cycles = dump_cycles
    out%status_every = status_every
    out%history_every = history_every
  end subroutine read_output

  !> Rank 0 creates the output directory with its parents when it is missing
  !> (mkdir -p); a failure is a problem in status on every rank.
  subroutine output_directory_create(directory, status)
    character(len=*), intent(in) :: directory
    type(status_t), intent(inout) :: status
    logical :: exists
    integer :: stat, cmdstat
    character(len=:), allocatable :: quoted
    integer :: i
    stat = 0
    if (par_rank() == 0) then
      inquire(file=trim(directory)//'/.', exist=exists)
      if (.not. exists) then
        ! Single quotes for the shell, a quote inside as '\''.
        quoted = ''''
        do i = 1, len_trim(directory)
          if (directory(i:i) == '''') then
            quoted = quoted//'''\'''''
          else
            quoted = quoted//directory(i:i)
          end if
        end do
        quoted = quoted//''''
        cmdstat = 0
        call execute_command_line('mkdir -p -- '//quoted//' 2>/dev/null', exitstat=stat, &
            cmdstat=cmdstat)
        if (cmdstat /= 0) stat = 1
        inquire(file=trim(directory)//'/.', exist=exists)
        if (.not. exists) stat = max(stat, 1)
      end if
    end if
    call par_bcast(stat)
    if (stat /= 0) call status%add('&output: directory: '''//trim(directory)// &
        ''' does not exist and cannot be created')
  end subroutine output_directory_create

end module io_deck
