!> The mesh package's deck group &mesh (one generated or imported part per
!> group), its keys declared once in MESH_KEYS (core_keys) next to its reader.
!> io_deck has checked the key names and value types and hands the reader the
!> group's text; the reader does the namelist read and the checks of the values.
module mesh_deck
  use core_kinds, only: rk
  use core_status, only: status_t
  use core_text, only: to_lower
  use core_keys, only: UNSET, key_t
  use core_path, only: path_from_deck, path_directory, path_absolute, PATH_LEN
  use parallel_env, only: par_rank, par_bcast
  use mesh_global, only: box_spec_t, MAX_INTERVALS, NAME_LEN
  use mesh_curved, only: rod_spec_t, tube_spec_t, shell_spec_t, ball_spec_t, &
      box_minus_ball_spec_t, sector_known
  implicit none
  private
  public :: read_mesh

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

  !> &mesh: one part.
  type(key_t), parameter, public :: MESH_KEYS(35) = [ &
      key_t("type", "c", "'box'", "", &
      "'box', 'rod', 'tube', 'shell', 'ball', 'box_minus_ball', 'gmsh' or 'exodus'"), &
      key_t("x", "r", "required", "length", &
      "interval end points along x (increasing; one more than intervals)"), &
      key_t("y", "r", "required", "length", &
      "interval end points along y (increasing; one more than intervals)"), &
      key_t("z", "r", "required", "length", &
      "interval end points along z (increasing; one more than intervals)"), &
      key_t("nx", "i", "required", "", &
      "zones in each interval along x (>= 1)"), &
      key_t("ny", "i", "required", "", &
      "zones in each interval along y (>= 1)"), &
      key_t("nz", "i", "required", "", &
      "zones in each interval along z (>= 1)"), &
      key_t("ratio_x", "r", "1", "", &
      "grading along x: last/first zone size in each interval (> 0)"), &
      key_t("ratio_y", "r", "1", "", &
      "grading along y: last/first zone size in each interval (> 0)"), &
      key_t("ratio_z", "r", "1", "", &
      "grading along z: last/first zone size in each interval (> 0)"), &
      key_t("skew_amplitude", "r", "0", "length", &
      "Saltzman skew amplitude A: x += A (ymax - y)/(ymax - ymin) sin(...)"), &
      key_t("perturb", "r", "0", "", &
      "random displacement of interior nodes, fraction of the local zone size, [0, 0.5)"), &
      key_t("radius", "r", "1 (rod), 0.5 (ball, box_minus_ball)", "length", &
      "rod: radius; ball, box_minus_ball: radius R of the sphere"), &
      key_t("length", "r", "4 (rod), 1.2 (box_minus_ball)", "length", &
      "rod: length; box_minus_ball: box edge L (> R)"), &
      key_t("z0", "r", "0", "length", &
      "rod: z of the bottom face"), &
      key_t("sector", "c", "'quarter' (rod), 'full' (tube), 'octant' (ball, shell)", "", &
      "rod: quarter, full; tube: full, half, quarter; ball, shell: octant, quarter, half, full"), &
      key_t("n_core", "i", "6 (rod), 8 (ball)", "", &
      "rod: zones along each edge of the square core; ball: of the cube core"), &
      key_t("n_radial", "i", "4 (rod), 3 (tube), 8 (shell), 6 (ball), 16 (box_minus_ball)", "", &
      "zones across the ring / wall / shell, or from core or sphere outward"), &
      key_t("n_axial", "i", "40 (rod), 80 (tube)", "", &
      "zones along the axis"), &
      key_t("axial_ratio", "r", "1", "", &
      "rod, tube: last/first zone length along the axis"), &
      key_t("core_fraction", "r", "0.55 (rod), 0.45 (ball)", "", &
      "rod: core corner at (f R, f R), [0.3, 0.65]; ball: core [0, f R]^3, [0.2, 0.5]"), &
      key_t("ri", "r", "0.8 (tube), 8 (shell)", "length", &
      "inner radius (tube, shell)"), &
      key_t("ro", "r", "1 (tube), 10 (shell)", "length", &
      "outer radius (tube, shell)"), &
      key_t("n_theta", "i", "64", "", &
      "tube: zones around the sector"), &
      key_t("axis", "r", "(0,0,1)", "", &
      "tube: axis direction"), &
      key_t("origin", "r", "(0,0,0)", "length", &
      "tube: centre of its bottom face"), &
      key_t("radial_reference", "r", "automatic", "", &
      "tube: the direction of theta = 0 (projected normal to the axis)"), &
      key_t("n_patch", "i", "10 (shell), 12 (box_minus_ball)", "", &
      "shell, box_minus_ball: zones along each edge of the cubed-sphere patches"), &
      key_t("radial_ratio", "r", "1", "", &
      "shell, ball, box_minus_ball: last/first zone thickness, outward (> 0)"), &
      key_t("file", "c", "''", "", &
      "gmsh, exodus: the mesh file, relative to the deck's directory (or absolute)"), &
      key_t("name", "c", "''", "", &
      "part name, prefix of its own face sets (required when there are several parts)"), &
      key_t("offset", "r", "0, 0, 0", "length", &
      "translation applied to the part"), &
      key_t("block", "c", "''", "", &
      "every zone of the part belongs to this &block"), &
      key_t("rotation_axis", "r", "0, 0, 0", "", &
      "axis of a rotation of the part about the origin, before offset"), &
      key_t("rotation_angle", "r", "0", "degrees", &
      "angle of that rotation in degrees, right-handed about rotation_axis")]

contains

  !> The index-th of nparts &mesh groups into part; a mesh file is looked for
  !> relative to the deck's directory (rank 0 looks, every rank is told).
  subroutine read_mesh(sect, index, nparts, part, status, deck_path)
    character(len=*), intent(in) :: sect(:) !< the group's text (io_deck: unknown keys blanked)
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
    if (ios /= 0) call status%add(trim(where)//': cannot read the group: '//trim(msg))
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
      if (len_trim(sector) > 0) part%shell%sector = to_lower(sector)
      if (.not. sector_known(part%shell%sector)) call status%add(trim(where)//': sector: '''// &
          trim(sector)//''' is not a shell sector (valid: octant, quarter, half, full)')
    case ('ball')
      if (box_keys) call status%add(trim(where)//': type: ''ball'' does not take box keys '// &
          '(x, nx, ...)')
      if (length /= UNSET .or. ri /= UNSET .or. ro /= UNSET .or. n_axial /= -1 .or. &
          n_theta /= -1 .or. n_patch /= -1) call status%add(trim(where)//': type: ''ball'' '// &
          'takes radius, n_core, n_radial, radial_ratio, core_fraction, sector')
      if (radius /= UNSET) part%ball%radius = radius
      if (n_core /= -1) part%ball%n_core = n_core
      if (n_radial /= -1) part%ball%n_radial = n_radial
      if (radial_ratio /= UNSET) part%ball%radial_ratio = radial_ratio
      if (core_fraction /= UNSET) part%ball%core_fraction = core_fraction
      if (len_trim(sector) > 0) part%ball%sector = to_lower(sector)
      if (.not. sector_known(part%ball%sector)) call status%add(trim(where)//': sector: '''// &
          trim(sector)//''' is not a ball sector (valid: octant, quarter, half, full)')
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

end module mesh_deck
