!> The input deck: namelist groups &control, &hydro, &mesh, &material,
!> &block, &region, &boundary, &contact, &output and &probe. Rank 0 reads the file and
!> broadcasts its text; every rank then scans the same text (io_deck_scan),
!> checks every key's name and value type against its group's key table, and
!> hands each group's text to the reader of the package that owns the group
!> (io_config, mesh_deck, material_deck, hydro_deck, contact_deck), which
!> reads and checks its values. Rank 0 reports every problem found (group,
!> key, reason) before any work starts.
module io_deck
  use core_status, only: status_t
  use core_keys, only: key_t, key_names
  use core_text, only: join
  use core_names, only: name_hint
  use core_units, only: UNITS_CGSUS
  use io_deck_scan, only: deck_scan, group_instance_t, to_lower, group_text, value_problem, &
      closest_name, LINE_LEN, KEY_LEN
  use parallel_env, only: par_rank, par_bcast
  use mesh_deck, only: read_mesh, MESH_KEYS
  use material_deck, only: read_material, check_material_names, read_block, MATERIAL_KEYS, &
      BLOCK_KEYS, read_erosion, EROSION_KEYS
  use hydro_deck, only: read_hydro, read_region, read_boundary, HYDRO_KEYS, REGION_KEYS, &
      BOUNDARY_KEYS
  use contact_deck, only: read_contact, CONTACT_KEYS
  use io_deck_checks, only: deck_cross_checks
  use material_table, only: STRENGTH_NONE
  use hydro_boundary, only: BC_WALL
  use io_config, only: config_t, read_control, read_output, read_probe, CONTROL_KEYS, &
      OUTPUT_KEYS, PROBE_KEYS
  implicit none
  private
  public :: deck_read, deck_group_keys, deck_known_keys, deck_restart_check
  public :: output_directory_create
  public :: config_t

  integer, parameter :: NGROUP_KNOWN = 11
  !> Every group, in the order `impact3d --keys` lists them.
  character(len=*), parameter, public :: DECK_GROUPS(NGROUP_KNOWN) = [character(len=8) :: &
      'control', 'hydro', 'mesh', 'material', 'block', 'region', 'boundary', 'output', 'contact', &
      'probe', 'erosion']

  !> A group's text as read (unknown keys blanked).
  type :: section_t
    character(len=LINE_LEN), allocatable :: text(:)
  end type section_t

  !> Keys of a group instance left out of its namelist read (bad values).
  type :: skip_t
    logical, allocatable :: key(:)
  end type skip_t

contains

  !> The key registry: a group's key table, that of the package reading the
  !> group (none for an unknown group).
  function deck_group_keys(group) result(keys)
    character(len=*), intent(in) :: group
    type(key_t), allocatable :: keys(:)
    select case (group)
    case ('control')
      keys = CONTROL_KEYS
    case ('hydro')
      keys = HYDRO_KEYS
    case ('mesh')
      keys = MESH_KEYS
    case ('material')
      keys = MATERIAL_KEYS
    case ('block')
      keys = BLOCK_KEYS
    case ('region')
      keys = REGION_KEYS
    case ('boundary')
      keys = BOUNDARY_KEYS
    case ('output')
      keys = OUTPUT_KEYS
    case ('contact')
      keys = CONTACT_KEYS
    case ('probe')
      keys = PROBE_KEYS
    case ('erosion')
      keys = EROSION_KEYS
    case default
      allocate(keys(0))
    end select
  end function deck_group_keys

  !> Known keys of a group, in its table's order.
  function deck_known_keys(group) result(keys)
    character(len=*), intent(in) :: group
    character(len=KEY_LEN), allocatable :: keys(:)
    keys = key_names(deck_group_keys(group))
  end function deck_known_keys

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
    type(key_t), allocatable :: keys(:)
    character(len=:), allocatable :: problem, guess
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
        if (trim(groups(ig)%name) == trim(DECK_GROUPS(k))) then
          found = .true.
          counts(k) = counts(k) + 1
        end if
      end do
      if (.not. found) then
        write(lnum, '(i0)') groups(ig)%first_line
        call status%add('&'//trim(groups(ig)%name)//': unknown group on deck line '// &
            trim(lnum)//did_you_mean(closest_name(groups(ig)%name, DECK_GROUPS), '&')// &
            ' (valid groups: '//join(DECK_GROUPS)//')')
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
      keys = deck_group_keys(trim(groups(ig)%name))
      do ik = 1, groups(ig)%nkey
        do k = 1, size(keys)
          if (keys(k)%name /= groups(ig)%key(ik)) cycle
          problem = value_problem(groups(ig)%value(ik), keys(k)%type)
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
      select case (DECK_GROUPS(k))
      case ('control')
        if (counts(k) == 0) call status%add('&'//trim(DECK_GROUPS(k))// &
            ': required group is missing')
        if (counts(k) > 1) call status%add('&'//trim(DECK_GROUPS(k))// &
            ': group given more than once')
      case ('mesh')
        if (counts(k) == 0) call status%add('&mesh: required group is missing')
      case ('hydro', 'output', 'erosion')
        if (counts(k) > 1) call status%add('&'//trim(DECK_GROUPS(k))// &
            ': group given more than once')
      case ('material', 'block', 'region')
        if (counts(k) == 0) call status%add('&'//trim(DECK_GROUPS(k))// &
            ': at least one is required')
      end select
    end do
    ! Read every known group, unknown keys blanked out, so that every problem
    ! of the deck is reported in this one run.

    allocate(config%materials(counts(4)), config%failures(counts(4)), config%blocks(counts(5)), config%regions(counts(6)))
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
              config%materials_read, config%units, config%failures(counts(4)))
        case ('output')
          call read_output(sect, config%output, status)
        end select
      end associate
    end do
    ! Groups that refer to others by name come after those are known.
    call check_material_names(config%materials, status)
    do ig = 1, ngroup
      associate(sect => sections(ig)%text)
        select case (trim(groups(ig)%name))
        case ('block')
          counts(5) = counts(5) + 1
          call read_block(sect, counts(5), config%blocks, config%materials, &
              config%materials_read, status)
        case ('region')
          counts(6) = counts(6) + 1
          call read_region(sect, counts(6), config%blocks, config%materials, &
              config%materials_read, config%regions(counts(6)), status, config%units)
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
    ! &erosion names blocks, which may come after it in the deck.
    do ig = 1, ngroup
      if (trim(groups(ig)%name) /= 'erosion') cycle
      if (counts(11) == 0) call read_erosion(sections(ig)%text, config%blocks, config%erosion, &
          status)
      counts(11) = counts(11) + 1
    end do
    if (len_trim(config%stop_block) > 0) then
      config%stop_block_index = findloc(config%blocks%name, config%stop_block, dim=1)
      if (config%stop_block_index == 0) call status%add('&control: stop_block: '''// &
          trim(config%stop_block)//''' is not a block of this deck'// &
          name_hint(config%stop_block, config%blocks%name))
    end if
    ! The single-stage scheme is for gas dynamics: its position update is not
    ! the one the contact, the wall and the strength update assume.
    if (config%hydro%single_stage) then
      if (counts(9) > 0) call status%add("&hydro: scheme: 'single' is for gas dynamics: "// &
          "not with &contact (use 'predictor_corrector')")
      if (allocated(config%materials)) then
        if (any(config%materials(:counts(4))%strength /= STRENGTH_NONE)) call status%add( &
            "&hydro: scheme: 'single' is for gas dynamics: not with a &material with "// &
            "strength (use 'predictor_corrector')")
      end if
      if (allocated(config%boundaries)) then
        if (any(config%boundaries(:counts(7))%kind == BC_WALL)) call status%add( &
            "&hydro: scheme: 'single' is for gas dynamics: not with a 'wall' &boundary "// &
            "(use 'predictor_corrector')")
      end if
    end if
    ! Across groups: the &block of a &mesh part, the speeds against the
    ! unit-mistake limit.
    call deck_cross_checks(config, status)
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
    character(len=8), parameter :: FIXED(8) = [character(len=8) :: 'mesh', 'material', &
        'block', 'region', 'boundary', 'contact', 'hydro', 'erosion']
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
