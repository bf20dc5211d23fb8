!> Everything the deck says (config_t), and io's own deck groups: &control,
!> &output and &probe, each key declared once in its table (core_keys) next to
!> the group's reader. io_deck has checked the key names and value types and
!> hands each reader the group's text; the reader does the namelist read and
!> the checks of the values.
module io_config
  use core_kinds, only: rk
  use core_status, only: status_t
  use core_text, only: to_lower, join
  use core_keys, only: UNSET, key_t
  use core_path, only: PATH_LEN
  use core_units, only: units_valid, UNITS_CGSUS, UNITS_LIST
  use mesh_global, only: NAME_LEN
  use mesh_deck, only: mesh_part_t
  use material_table, only: material_t, STRENGTH_NONE
  use material_deck, only: block_spec_t
  use material_failure, only: failure_t, erosion_spec_t
  use hydro_state, only: hydro_options_t
  use hydro_boundary, only: boundary_spec_t
  use hydro_initial, only: region_t
  use contact_enforce, only: contact_spec_t
  implicit none
  private
  public :: read_control, read_output, read_probe

  integer, parameter, public :: DECK_FORMAT_VERSION = 1

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

  !> Output controls.
  type, public :: output_options_t
    character(len=PATH_LEN) :: directory = '.' !< where dumps and history go
    character(len=NAME_LEN) :: prefix = 'dump' !< dump file prefix
    real(rk) :: dump_interval = 0.0_rk !< simulated time between dumps (0 = none)
    integer :: dump_cycles = 0 !< cycles between dumps (0 = none)
    integer :: status_every = 10 !< cycles between status lines
    integer :: history_every = 1 !< cycles between history lines
  end type output_options_t

  !> Everything the deck says.
  type, public :: config_t
    character(len=80) :: title = ''
    real(rk) :: t_end = UNSET
    integer :: max_cycles = 10000000
    real(rk) :: wall_limit = 0.0_rk !< wall-clock seconds; stop cleanly before (0 = none)
    character(len=PATH_LEN) :: stop_file = 'STOP' !< its existence stops the run cleanly
    character(len=8) :: partitioner = 'scotch' !< 'scotch' (parallel) or 'metis' (rank 0)
    integer :: stop_check_every = 10 !< cycles between looks for the stop file
    integer :: fault_cycle = 0 !< testing aid: inject a fault at this cycle (0 = never)
    character(len=8) :: fault_kind = 'nan' !< 'nan' (NaN energy) or 'tangle' (mirror zone 1)
    character(len=PATH_LEN) :: restart = ''
    type(hydro_options_t) :: hydro
    type(mesh_part_t), allocatable :: parts(:) !< one per &mesh group, appended in order
    type(material_t), allocatable :: materials(:)
    type(failure_t), allocatable :: failures(:) !< each material's failure (&material failure keys)
    type(erosion_spec_t) :: erosion !< &erosion: distortion erosion
    !> &control stop_block: the run ends when this block's kinetic energy falls
    !> below stop_kinetic_fraction of its initial value ('' = never)
    character(len=NAME_LEN) :: stop_block = ''
    integer :: stop_block_index = 0 !< its index in blocks (io_deck resolves it)
    real(rk) :: stop_kinetic_fraction = 0.0_rk
    type(block_spec_t), allocatable :: blocks(:)
    type(region_t), allocatable :: regions(:)
    type(boundary_spec_t), allocatable :: boundaries(:)
    type(contact_spec_t), allocatable :: contacts(:)
    type(output_options_t) :: output
    type(probe_spec_t), allocatable :: probes(:) !< one per &probe group
    character(len=16) :: units = UNITS_CGSUS !< &control units: unit system of the deck
    logical :: materials_read = .true. !< false when a &material could not be read
    !> initial node speeds above SPEED_LIMIT_CGSUS (a velocity in the wrong
    !> units) are accepted
    logical :: allow_high_speed = .false.
    character(len=:), allocatable :: deck_text !< the deck file as read (for the dumps)
  end type config_t

  !> &control: the run (end, steps, stops, units).
  type(key_t), parameter, public :: CONTROL_KEYS(21) = [ &
      key_t("title", "c", "''", "", &
      "run title (dumps, status)"), &
      key_t("t_end", "r", "required", "time", &
      "end time, > 0"), &
      key_t("max_cycles", "i", "10000000", "cycles", &
      "stop (exit 3, with a dump) after this many cycles"), &
      key_t("deck_version", "i", "1", "", &
      "deck format version; only 1 is accepted"), &
      key_t("restart", "c", "''", "", &
      "dump to restart from (the --restart option overrides it)"), &
      key_t("cfl", "r", "0.5", "", &
      "Courant factor, (0, 1]"), &
      key_t("dt_initial", "r", "0", "time", &
      "first step; 0 = from the stability limit"), &
      key_t("dt_max", "r", "huge", "time", &
      "largest step"), &
      key_t("dt_min", "r", "1e-12", "time", &
      "a step below this stops the run (exit 2)"), &
      key_t("dt_growth", "r", "1.1", "", &
      "largest growth of dt per cycle, >= 1"), &
      key_t("dvol_max", "r", "0.1", "", &
      "largest relative volume change of a zone per cycle, (0, 1)"), &
      key_t("fault_cycle", "i", "0", "cycles", &
      "testing aid: inject a fault at this cycle (0 = never)"), &
      key_t("fault_kind", "c", "'nan'", "", &
      "testing aid: 'nan' (NaN energy in zone 1) or 'tangle' (zone 1 turned inside out)"), &
      key_t("wall_limit", "r", "0", "s", &
      "wall-clock seconds allowed (0 = none): a restart dump and exit 3 shortly before"), &
      key_t("stop_file", "c", "'STOP'", "", &
      "a file in the output directory whose appearance stops the run (restart dump, exit 3)"), &
      key_t("stop_check_every", "i", "10", "cycles", &
      "cycles between looks for the stop file"), &
      key_t("units", "c", "'cm-g-us-mbar'", "", &
      "unit system of the deck: 'cm-g-us-mbar', 'si' or 'none'"), &
      key_t("allow_high_speed", "l", ".false.", "", &
      "accept initial node speeds above 10 cm/us (100 km/s; refused otherwise as a unit mistake)"), &
      key_t("partitioner", "c", "'scotch'", "", &
      "zone partition: 'scotch' (PT-Scotch, in parallel) or 'metis' (serial METIS on rank 0)"), &
      key_t("stop_block", "c", "''", "", &
      "the run ends (final dump, exit 0) when this block's kinetic energy falls below the fraction"), &
      key_t("stop_kinetic_fraction", "r", "required with stop_block", "", &
      "fraction of stop_block's initial kinetic energy that ends the run, in (0, 1)")]

  !> &output: dumps, history and status lines.
  type(key_t), parameter, public :: OUTPUT_KEYS(6) = [ &
      key_t("directory", "c", "'.'", "", &
      "where dumps and history go"), &
      key_t("prefix", "c", "'dump'", "", &
      "dump file prefix"), &
      key_t("dump_interval", "r", "0", "time", &
      "simulated time between dumps (0 = none)"), &
      key_t("dump_cycles", "i", "0", "cycles", &
      "cycles between dumps (0 = none)"), &
      key_t("status_every", "i", "10", "cycles", &
      "cycles between status lines"), &
      key_t("history_every", "i", "1", "cycles", &
      "cycles between history lines")]

  !> &probe: a time history at one node / zone.
  type(key_t), parameter, public :: PROBE_KEYS(6) = [ &
      key_t("name", "c", "required", "", &
      "names the file probe_<name>.csv (letters, digits, _, -, .; unique)"), &
      key_t("node", "i", "-", "", &
      "global node id (1-based); give node or point"), &
      key_t("point", "r", "-", "length", &
      "x, y, z of a point inside the mesh at t = 0"), &
      key_t("fields", "c", "required", "", &
      "names separated by blanks or commas (velocity, position, pressure, ...)"), &
      key_t("every", "i", "1", "cycles", &
      "cycles between rows (rows at multiples of it)"), &
      key_t("interval", "r", "-", "time", &
      "simulated time between rows; give every or interval")]

contains

  !> &control into config (run limits, stops, units) and config%hydro (time step).
  subroutine read_control(sect, config, status)
    character(len=*), intent(in) :: sect(:) !< the group's text (io_deck: unknown keys blanked)
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
    logical :: allow_high_speed
    character(len=8) :: partitioner
    character(len=NAME_LEN) :: stop_block
    real(rk) :: stop_kinetic_fraction
    namelist /control/ title, t_end, max_cycles, deck_version, restart, cfl, dt_initial, &
        dt_max, dt_min, dt_growth, dvol_max, fault_cycle, fault_kind, wall_limit, stop_file, &
        stop_check_every, units, allow_high_speed, partitioner, stop_block, stop_kinetic_fraction

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
    allow_high_speed = config%allow_high_speed
    partitioner = config%partitioner
    stop_block = ''
    stop_kinetic_fraction = UNSET
    cfl = config%hydro%cfl
    dt_initial = config%hydro%dt_initial
    dt_max = config%hydro%dt_max
    dt_min = config%hydro%dt_min
    dt_growth = config%hydro%dt_growth
    dvol_max = config%hydro%dvol_max
    read(sect, nml=control, iostat=ios, iomsg=msg)
    if (ios /= 0) call status%add('&control: cannot read the group: '//trim(msg))
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
    config%allow_high_speed = allow_high_speed
    partitioner = to_lower(partitioner)
    if (partitioner /= 'scotch' .and. partitioner /= 'metis') call status%add('&control: '// &
        'partitioner: '''//trim(partitioner)//''' is not a partitioner (valid: scotch, metis)')
    config%partitioner = partitioner
    if (len_trim(stop_block) > 0) then
      if (stop_kinetic_fraction == UNSET) then
        call status%add('&control: stop_kinetic_fraction: required with stop_block')
      else if (.not. (stop_kinetic_fraction > 0.0_rk .and. stop_kinetic_fraction < 1.0_rk)) then
        call status%add('&control: stop_kinetic_fraction: must be in (0, 1)')
      end if
    else if (stop_kinetic_fraction /= UNSET) then
      call status%add('&control: stop_kinetic_fraction: only with stop_block (the block '// &
          'whose kinetic energy ends the run)')
    end if
    config%stop_block = stop_block
    config%stop_kinetic_fraction = max(stop_kinetic_fraction, 0.0_rk)
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

  !> &output into out (its defaults are out's on entry).
  subroutine read_output(sect, out, status)
    character(len=*), intent(in) :: sect(:) !< the group's text (io_deck: unknown keys blanked)
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
    if (ios /= 0) call status%add('&output: cannot read the group: '//trim(msg))
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

  !> One &probe group. The node range and whether the point lies in the mesh
  !> are checked when the mesh is built (io_probe).
  subroutine read_probe(sect, index, config, status)
    character(len=*), intent(in) :: sect(:) !< the group's text (io_deck: unknown keys blanked)
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

end module io_config
