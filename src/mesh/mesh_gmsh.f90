!> Reader of Gmsh ASCII meshes, format 2.2 and 4.1, into a global_mesh_t.
!>
!> Zones are the 8-node hexahedra (Gmsh element type 5); each must lie in one
!> 3D physical group, and the 3D groups, in order of their physical tags, are
!> the blocks. Quadrilaterals (type 3) in 2D physical groups become face sets
!> named after their groups, each quad matched to the hexahedron face with the
!> same four nodes. Nodes used by the hexahedra are renumbered 1..nnode in
!> increasing order of their Gmsh tags; zones keep the order of the file.
!> Gmsh's hexahedron node order is the VTK order used by mesh_geometry.
!> Points, lines, triangles, other volume elements and second-order elements
!> are ignored when they are in no physical group or in a 0D/1D group.
!> Names of physical groups are required in 4.1 files; in 2.2 files an
!> unnamed group N is called 'physical_N'.
module mesh_gmsh
  use, intrinsic :: ieee_arithmetic, only: ieee_is_finite
  use core_kinds, only: rk, ik, i8
  use core_status, only: status_t
  use core_sort, only: sort_order, sort_values
  use core_text, only: itoa => to_text, i8toa => to_text
  use core_sort, only: sort_unique, sorted_find
  use mesh_geometry, only: hex_volume, HEX_FACE_NODES, quad_vector_area
  use mesh_global, only: global_mesh_t, NAME_LEN
  use mesh_range, only: mesh_range_t, range_grow_faces
  use mesh_report, only: merge_capped, keyed_report_t, LINE_LEN
  use parallel_env, only: par_rank, par_size, par_sum, par_max, par_bcast
  use parallel_route, only: par_block_range, par_block_owner, par_route_free, par_exscan_i8, &
      par_ordered_sum, par_allgather_text
  implicit none
  private
  public :: mesh_read_gmsh, gmsh_scan, range_add_gmsh

  integer, parameter :: TYPE_QUAD = 3 !< Gmsh 4-node quadrilateral
  integer, parameter :: TYPE_HEX = 5 !< Gmsh 8-node hexahedron
  integer, parameter :: VERSION_22 = 22, VERSION_41 = 41
  !> Per-element problems of one kind reported one by one before a summary line.
  integer, parameter :: MAX_REPORT = 10
  !> Packs two non-negative 32-bit integers into one 64-bit sort key.
  integer(i8), parameter :: SHIFT = 4294967296_i8
  !> Bytes of the file read at a time.
  integer, parameter :: BLOCK_LEN = 65536
  !> Words (64-bit) of a chunk rank 0 sends while it streams a file (1 MB:
  !> rank 0's buffers for a chunk, packed and received, stay near 3 MB).
  integer, parameter :: CHUNK_WORDS = 131072
  !> What rank 0 is doing with the file: reading it whole (mesh_read_gmsh),
  !> streaming its nodes and the hexahedra's node tags (gmsh_scan), or its
  !> hexahedra and quadrilaterals (range_add_gmsh).
  integer, parameter :: MODE_WHOLE = 0, MODE_SCAN = 1, MODE_ZONES = 2
  !> Chunks rank 0 sends while it streams (the other ranks serve them).
  integer, parameter :: CMD_END = 0, CMD_LAYOUT = 1, CMD_NODES = 2, CMD_NODES_DONE = 3, &
      CMD_USED = 4, CMD_HEX = 5, CMD_QUAD = 6
  !> Words of a record of each chunk kind.
  integer, parameter :: WIDTH(CMD_NODES:CMD_QUAD) = [5, 0, 1, 11, 7]

  !> A Gmsh file read in chunks (gmsh_scan, then range_add_gmsh): rank 0
  !> streams it; every rank holds the nodes whose tags fall in its block of
  !> the tag range, and later the hexahedra of its zone range and its block
  !> of the quadrilaterals. Sizes and names are the same on every rank.
  type, public :: gmsh_part_t
    character(len=:), allocatable :: path
    integer(i8) :: nhex = 0 !< hexahedra (= zones)
    integer(i8) :: nquad = 0 !< quadrilaterals in 2D groups (one per group)
    integer(i8) :: nnode = 0 !< nodes used by the hexahedra
    integer, allocatable :: block_tags(:), set_tags(:) !< sorted 3D and 2D physical tags
    character(len=NAME_LEN), allocatable :: block_names(:), set_names(:)
    logical, allocatable :: block_used(:) !< the 3D group holds hexahedra
    integer(i8), allocatable :: set_count(:) !< faces of each set (range_add_gmsh)
    !> Node tags tag_lo .. tag_lo + ntag - 1 are spread over the ranks in
    !> blocks (smaller tags go to rank 0, larger to the last rank).
    integer(i8) :: tag_lo = 1, ntag = 1
    integer :: nstore = 0
    !> (6, nstore) this rank's nodes sorted by tag: tag, index in $Nodes,
    !> x, y, z (bits), id (1.. in tag order over the used nodes, 0 unused)
    integer(i8), allocatable :: store(:, :)
    integer(i8), allocatable :: hex_tag(:) !< (range%nzone) Gmsh tags of the range's hexahedra
    integer :: nq = 0
    integer(i8), allocatable :: quads(:, :) !< (7, nq) [index, tag, group, 4 node tags]
  end type gmsh_part_t

  !> Line-oriented token reader; the first syntax error is fatal and kept in message.
  type :: reader_t
    integer :: unit = -1 !< open file
    character(len=:), allocatable :: line !< current line
    integer :: pos = 1 !< next character of line to look at
    integer :: line_number = 0 !< of line, for messages
    logical :: eof = .false. !< the file is exhausted
    logical :: failed = .false. !< a fatal problem was found
    character(len=:), allocatable :: message !< what it was
    character(len=:), allocatable :: section !< current $Section, for messages
    integer(i8) :: fsize = 0 !< bytes in the file
    integer(i8) :: fpos = 1 !< next byte of the file to read into block
    integer :: bpos = 1, blen = 0 !< next byte of block to look at, bytes in block
    character(len=:), allocatable :: block !< (BLOCK_LEN) the bytes read last
  end type reader_t

  !> Everything kept from the file, before checking and renumbering.
  type :: gmsh_data_t
    integer :: version = 0 !< VERSION_22 or VERSION_41
    logical :: has_names = .false. !< a $PhysicalNames section was read
    integer :: nname = 0 !< entries of $PhysicalNames
    integer, allocatable :: name_dim(:), name_tag(:)
    character(len=256), allocatable :: name_text(:)
    logical :: has_entities = .false. !< a $Entities section was read (4.1)
    integer :: nentity = 0
    integer(i8), allocatable :: entity_key(:, :) !< (1, n): dim * SHIFT + tag
    integer, allocatable :: entity_order(:) !< sorting permutation of entity_key
    integer, allocatable :: entity_start(:) !< CSR into entity_phys, size nentity + 1
    integer, allocatable :: entity_phys(:) !< physical tags of each entity
    logical :: has_nodes = .false.
    integer :: nnode = 0 !< nodes in the file
    integer(i8), allocatable :: node_tag(:)
    real(rk), allocatable :: node_xyz(:, :) !< (3, nnode)
    logical :: has_elements = .false.
    integer :: nhex = 0
    integer(i8), allocatable :: hex_tag(:), hex_node(:, :) !< node tags (8, nhex)
    integer, allocatable :: hex_group(:) !< 3D physical tag, 0 = none
    integer :: nquad = 0 !< quads in 2D physical groups (one entry per group)
    integer(i8), allocatable :: quad_tag(:), quad_node(:, :) !< node tags (4, nquad)
    integer, allocatable :: quad_group(:) !< 2D physical tag
    integer :: nbad = 0 !< other elements in 2D or 3D physical groups
    ! Streaming (rank 0 of a read in chunks):
    integer :: mode = MODE_WHOLE
    type(gmsh_part_t), pointer :: part => null()
    type(mesh_range_t), pointer :: range => null()
    integer(i8) :: zone0 = 0 !< zones of the parts before this one
    character(len=:), allocatable :: prefix
    integer :: buf_cmd = -1, nbuf = 0
    integer(i8), allocatable :: buf(:, :)
    integer, allocatable :: buf_dest(:)
    integer(i8) :: nstream_node = 0, nstream_hex = 0, nstream_quad = 0
    integer, allocatable :: hex_groups(:), quad_groups(:) !< distinct physical tags seen
    integer :: nnogroup = 0 !< hexahedra in no 3D group
    character(len=LINE_LEN) :: nogroup(10) = ''
  end type gmsh_data_t

contains

  !> Read an ASCII Gmsh mesh (.msh 2.2 or 4.1). Every problem goes to status with a
  !> message starting "mesh file '<path>': "; on any problem the mesh is left empty.
  subroutine mesh_read_gmsh(path, mesh, block_names, status)
    character(len=*), intent(in) :: path !< the .msh file
    type(global_mesh_t), intent(inout) :: mesh !< the mesh read; zone_block indexes block_names
    !> Names of the 3D physical groups in order of their physical tags.
    character(len=NAME_LEN), allocatable, intent(out) :: block_names(:)
    type(status_t), intent(inout) :: status !< problems are added here
    type(reader_t) :: r
    type(gmsh_data_t) :: data
    character(len=:), allocatable :: prefix
    character(len=256) :: msg
    logical :: exists
    integer :: ios, count0

    prefix = "mesh file '"//trim(path)//"': "
    count0 = status%count
    call mesh%free()
    allocate(block_names(0))
    inquire(file=path, exist=exists)
    if (.not. exists) then
      call status%add(prefix//'no such file')
      return
    end if
    open(newunit=r%unit, file=path, status='old', action='read', form='unformatted', &
        access='stream', iostat=ios, iomsg=msg)
    if (ios /= 0) then
      call status%add(prefix//'cannot open it: '//trim(msg))
      return
    end if
    r%line = ''
    r%section = ''
    r%message = ''
    inquire(unit=r%unit, size=r%fsize)
    allocate(character(len=BLOCK_LEN) :: r%block)
    call parse_file(r, data, prefix, status)
    close(r%unit)
    if (r%failed) then
      call status%add(prefix//r%message)
    else
      call build_mesh(data, prefix, mesh, block_names, status)
    end if
    if (status%count > count0) then
      call mesh%free()
      if (allocated(block_names)) deallocate(block_names)
      allocate(block_names(0))
    end if
  end subroutine mesh_read_gmsh

  ! ---------------------------------------------------------------------------
  ! Parsing
  ! ---------------------------------------------------------------------------

  !> Read the sections of the file into data; unknown sections are skipped.
  subroutine parse_file(r, data, prefix, status)
    type(reader_t), intent(inout) :: r
    type(gmsh_data_t), intent(inout) :: data
    character(len=*), intent(in) :: prefix
    type(status_t), intent(inout) :: status
    integer :: i1, i2
    logical :: at_end
    character(len=:), allocatable :: name

    call reader_token(r, i1, i2, at_end)
    if (at_end) then
      call reader_fail(r, 'the file is empty; expected a Gmsh mesh starting with $MeshFormat')
      return
    end if
    if (r%line(i1:i2) /= '$MeshFormat') then
      call reader_fail(r, 'not a Gmsh mesh: expected $MeshFormat, found '''// &
          clip(r%line(i1:i2))//'''')
      return
    end if
    call parse_format(r, data)
    do while (.not. r%failed)
      call reader_token(r, i1, i2, at_end)
      if (at_end .or. r%failed) exit
      name = r%line(i1:i2)
      r%section = name
      select case (name)
      case ('$MeshFormat')
        call reader_fail(r, 'a second $MeshFormat section')
      case ('$PhysicalNames')
        call parse_physical_names(r, data, prefix, status)
      case ('$Entities')
        if (data%version == VERSION_41) then
          call parse_entities(r, data)
        else
          call reader_skip_section(r, name(2:))
        end if
      case ('$PartitionedEntities')
        call reader_fail(r, 'partitioned meshes are not supported; save the mesh '// &
            'unpartitioned (impact3d partitions it itself)')
      case ('$Nodes')
        if (data%has_nodes) then
          call reader_fail(r, 'a second $Nodes section')
        else if (data%mode == MODE_ZONES) then
          call reader_skip_section(r, 'Nodes')
          data%has_nodes = .true.
        else if (data%version == VERSION_22) then
          call parse_nodes_22(r, data)
        else
          call parse_nodes_41(r, data)
        end if
      case ('$Elements')
        if (data%has_elements) then
          call reader_fail(r, 'a second $Elements section')
        else if (data%mode == MODE_SCAN .and. .not. data%has_nodes) then
          call reader_fail(r, 'the $Elements section comes before $Nodes (a file read in '// &
              'chunks needs the nodes first, as Gmsh writes them)')
        else if (data%version == VERSION_22) then
          call parse_elements_22(r, data, prefix, status)
        else
          call parse_elements_41(r, data, prefix, status)
        end if
      case default
        if (name(1:1) == '$' .and. len(name) > 1) then
          call reader_skip_section(r, name(2:))
        else
          call reader_fail(r, 'unexpected text '''//clip(name)//''' outside any section')
        end if
      end select
      r%section = ''
    end do
    if (r%failed) return
    if (.not. data%has_nodes) then
      call reader_fail(r, 'the file has no $Nodes section')
    else if (.not. data%has_elements) then
      call reader_fail(r, 'the file has no $Elements section')
    end if
  end subroutine parse_file

  !> $MeshFormat: accept ASCII 2.2 and 4.1 only.
  subroutine parse_format(r, data)
    type(reader_t), intent(inout) :: r
    type(gmsh_data_t), intent(inout) :: data
    integer :: i1, i2, file_type, data_size, ios
    real(rk) :: number
    character(len=:), allocatable :: version

    r%section = '$MeshFormat'
    call reader_required_token(r, 'the format version', i1, i2)
    if (r%failed) return
    version = r%line(i1:i2)
    call read_int(r, 'the file type', file_type)
    call read_int(r, 'the data size', data_size)
    if (r%failed) return
    call reader_end_line(r)
    read(version, *, iostat=ios) number
    if (ios /= 0) number = -1.0_rk
    if (abs(number - 2.2_rk) < 1.0e-9_rk) then
      data%version = VERSION_22
    else if (abs(number - 4.1_rk) < 1.0e-9_rk) then
      data%version = VERSION_41
    else
      call reader_fail(r, 'Gmsh format version '//clip(version)//' is not supported; '// &
          'impact3d reads ASCII .msh 2.2 and 4.1 (gmsh -format msh22 or msh41)')
      return
    end if
    if (file_type /= 0) then
      call reader_fail(r, 'the file is binary (format '//clip(version)//', file type '// &
          itoa(file_type)//'); impact3d reads ASCII .msh only (set Mesh.Binary = 0)')
      return
    end if
    call reader_expect(r, '$EndMeshFormat')
  end subroutine parse_format

  !> $PhysicalNames: lines "dim tag "name"".
  subroutine parse_physical_names(r, data, prefix, status)
    type(reader_t), intent(inout) :: r
    type(gmsh_data_t), intent(inout) :: data
    character(len=*), intent(in) :: prefix
    type(status_t), intent(inout) :: status
    integer :: n, i, j, dim, tag, q1, q2

    if (data%has_names) then
      call reader_fail(r, 'a second $PhysicalNames section')
      return
    end if
    call read_count(r, 'the number of physical names', n)
    if (r%failed) return
    call reader_end_line(r)
    allocate(data%name_dim(n), data%name_tag(n), data%name_text(n))
    do i = 1, n
      call read_int(r, 'a physical dimension', dim)
      call read_int(r, 'a physical tag', tag)
      if (r%failed) return
      q1 = index(r%line(r%pos:), '"')
      q2 = index(r%line(r%pos:), '"', back=.true.)
      if (q1 == 0 .or. q2 <= q1) then
        call reader_fail(r, 'expected a physical name in double quotes')
        return
      end if
      data%name_dim(i) = dim
      data%name_tag(i) = tag
      ! A name longer than the buffer stays longer than NAME_LEN: build_mesh reports it.
      data%name_text(i) = r%line(r%pos + q1:r%pos + q2 - 2)
      do j = 1, i - 1
        if (data%name_dim(j) == dim .and. data%name_tag(j) == tag) then
          call status%add(prefix//'$PhysicalNames names the '//itoa(dim)// &
              'D physical group '//itoa(tag)//' twice')
        end if
      end do
      call reader_end_line(r)
    end do
    data%nname = n
    data%has_names = .true.
    call reader_expect(r, '$EndPhysicalNames')
  end subroutine parse_physical_names

  !> $Entities (4.1): the physical tags of every point, curve, surface and volume.
  subroutine parse_entities(r, data)
    type(reader_t), intent(inout) :: r
    type(gmsh_data_t), intent(inout) :: data
    integer :: counts(0:3), dim, i, k, n, tag, nphys, phys, nskip
    real(rk) :: value

    if (data%has_entities) then
      call reader_fail(r, 'a second $Entities section')
      return
    end if
    do dim = 0, 3
      call read_count(r, 'the number of entities', counts(dim))
    end do
    if (r%failed) return
    call reader_end_line(r)
    data%nentity = sum(counts)
    allocate(data%entity_key(1, data%nentity), data%entity_start(data%nentity + 1))
    allocate(data%entity_phys(16))
    data%entity_start(1) = 1
    n = 0
    do dim = 0, 3
      nskip = 6
      if (dim == 0) nskip = 3
      do i = 1, counts(dim)
        call read_int(r, 'an entity tag', tag)
        do k = 1, nskip
          call read_real(r, 'a coordinate', value)
        end do
        call read_count(r, 'the number of physical tags', nphys)
        if (r%failed) return
        n = n + 1
        data%entity_key(1, n) = int(dim, i8) * SHIFT + int(tag, i8)
        call grow_int(data%entity_phys, data%entity_start(n) - 1 + nphys)
        do k = 1, nphys
          call read_int(r, 'a physical tag', phys)
          data%entity_phys(data%entity_start(n) + k - 1) = phys
        end do
        data%entity_start(n + 1) = data%entity_start(n) + nphys
        call reader_end_line(r)
        if (r%failed) return
      end do
    end do
    call sort_order(data%entity_key, data%entity_order)
    data%has_entities = .true.
    call reader_expect(r, '$EndEntities')
  end subroutine parse_entities

  !> $Nodes in format 2.2: a count, then "tag x y z" lines.
  subroutine parse_nodes_22(r, data)
    type(reader_t), intent(inout) :: r
    type(gmsh_data_t), intent(inout) :: data
    integer :: n, i, k

    call read_count(r, 'the number of nodes', n)
    if (r%failed) return
    call reader_end_line(r)
    if (data%mode == MODE_SCAN) then
      call stream_layout(data, 1_i8, int(n, i8))
      allocate(data%node_tag(1), data%node_xyz(3, 1))
    else
      call allocate_nodes(r, data, n)
    end if
    if (r%failed) return
    do i = 1, n
      if (data%mode == MODE_SCAN) then
        call read_i8(r, 'a node tag', data%node_tag(1))
        do k = 1, 3
          call read_real(r, 'a node coordinate', data%node_xyz(k, 1))
        end do
        if (.not. r%failed) call stream_node(data, data%node_tag(1), data%node_xyz(:, 1))
      else
        call read_i8(r, 'a node tag', data%node_tag(i))
        do k = 1, 3
          call read_real(r, 'a node coordinate', data%node_xyz(k, i))
        end do
      end if
      call reader_end_line(r)
      if (r%failed) return
    end do
    if (data%mode == MODE_SCAN) call stream_nodes_done(data)
    data%has_nodes = .true.
    call reader_expect(r, '$EndNodes')
  end subroutine parse_nodes_22

  !> $Nodes in format 4.1: entity blocks of tags followed by coordinates.
  subroutine parse_nodes_41(r, data)
    type(reader_t), intent(inout) :: r
    type(gmsh_data_t), intent(inout) :: data
    integer :: nblock, n, b, i, k, dim, tag, parametric, count, first
    integer(i8) :: min_tag, max_tag

    call read_count(r, 'the number of node blocks', nblock)
    call read_count(r, 'the number of nodes', n)
    call read_i8(r, 'the smallest node tag', min_tag)
    call read_i8(r, 'the largest node tag', max_tag)
    if (r%failed) return
    call reader_end_line(r)
    if (data%mode == MODE_SCAN) then
      call parse_nodes_41_stream(r, data, nblock, n, min_tag, max_tag)
      return
    end if
    call allocate_nodes(r, data, n)
    if (r%failed) return
    first = 0
    do b = 1, nblock
      call read_int(r, 'an entity dimension', dim)
      call read_int(r, 'an entity tag', tag)
      call read_int(r, 'the parametric flag', parametric)
      call read_count(r, 'the number of nodes in the block', count)
      if (r%failed) return
      call reader_end_line(r)
      if (first + count > n) then
        call reader_fail(r, 'bad counts: the node blocks hold more than the '//itoa(n)// &
            ' nodes announced in the $Nodes header')
        return
      end if
      do i = first + 1, first + count
        call read_i8(r, 'a node tag', data%node_tag(i))
        call reader_end_line(r)
        if (r%failed) return
        if (data%node_tag(i) < min_tag .or. data%node_tag(i) > max_tag) then
          call reader_fail(r, 'bad counts: node tag '//i8toa(data%node_tag(i))// &
              ' is outside the range '//i8toa(min_tag)//'..'//i8toa(max_tag)// &
              ' given in the $Nodes header')
          return
        end if
      end do
      do i = first + 1, first + count
        do k = 1, 3
          call read_real(r, 'a node coordinate', data%node_xyz(k, i))
        end do
        ! Parametric coordinates, if any, follow on the same line.
        call reader_end_line(r)
        if (r%failed) return
      end do
      first = first + count
    end do
    if (first /= n) then
      call reader_fail(r, 'bad counts: the node blocks hold '//itoa(first)// &
          ' nodes but the $Nodes header announces '//itoa(n))
      return
    end if
    data%has_nodes = .true.
    call reader_expect(r, '$EndNodes')
  end subroutine parse_nodes_41

  !> $Nodes in format 4.1 streamed (MODE_SCAN): the tags of an entity block
  !> are kept until its coordinates are read (8 bytes a node of the largest
  !> block on rank 0), each node then sent on.
  subroutine parse_nodes_41_stream(r, data, nblock, n, min_tag, max_tag)
    type(reader_t), intent(inout) :: r
    type(gmsh_data_t), intent(inout) :: data
    integer, intent(in) :: nblock, n
    integer(i8), intent(in) :: min_tag, max_tag
    integer :: b, i, k, dim, tag, parametric, count, first
    integer(i8), allocatable :: tags(:)
    real(rk) :: xyz(3)
    call stream_layout(data, min_tag, int(n, i8))
    first = 0
    do b = 1, nblock
      call read_int(r, 'an entity dimension', dim)
      call read_int(r, 'an entity tag', tag)
      call read_int(r, 'the parametric flag', parametric)
      call read_count(r, 'the number of nodes in the block', count)
      if (r%failed) return
      call reader_end_line(r)
      if (first + count > n) then
        call reader_fail(r, 'bad counts: the node blocks hold more than the '//itoa(n)// &
            ' nodes announced in the $Nodes header')
        return
      end if
      allocate(tags(count))
      do i = 1, count
        call read_i8(r, 'a node tag', tags(i))
        call reader_end_line(r)
        if (r%failed) return
        if (tags(i) < min_tag .or. tags(i) > max_tag) then
          call reader_fail(r, 'bad counts: node tag '//i8toa(tags(i))// &
              ' is outside the range '//i8toa(min_tag)//'..'//i8toa(max_tag)// &
              ' given in the $Nodes header')
          return
        end if
      end do
      do i = 1, count
        do k = 1, 3
          call read_real(r, 'a node coordinate', xyz(k))
        end do
        call reader_end_line(r)
        if (r%failed) return
        call stream_node(data, tags(i), xyz)
      end do
      deallocate(tags)
      first = first + count
    end do
    if (first /= n) then
      call reader_fail(r, 'bad counts: the node blocks hold '//itoa(first)// &
          ' nodes but the $Nodes header announces '//itoa(n))
      return
    end if
    data%has_nodes = .true.
    call stream_nodes_done(data)
    call reader_expect(r, '$EndNodes')
  end subroutine parse_nodes_41_stream

  !> $Elements in format 2.2: "tag type ntags tags... nodes..." lines.
  subroutine parse_elements_22(r, data, prefix, status)
    type(reader_t), intent(inout) :: r
    type(gmsh_data_t), intent(inout) :: data
    character(len=*), intent(in) :: prefix
    type(status_t), intent(inout) :: status
    integer :: n, i, k, element_type, ntags, phys, value
    integer(i8) :: tag, nodes(8)

    call read_count(r, 'the number of elements', n)
    if (r%failed) return
    call reader_end_line(r)
    do i = 1, n
      call read_i8(r, 'an element tag', tag)
      call read_int(r, 'an element type', element_type)
      call read_count(r, 'the number of element tags', ntags)
      if (r%failed) return
      phys = 0
      do k = 1, ntags
        call read_int(r, 'an element tag', value)
        if (k == 1) phys = value
      end do
      select case (element_type)
      case (TYPE_HEX)
        do k = 1, 8
          call read_i8(r, 'a node tag', nodes(k))
        end do
        if (r%failed) return
        call add_hex(data, tag, nodes, phys)
      case (TYPE_QUAD)
        do k = 1, 4
          call read_i8(r, 'a node tag', nodes(k))
        end do
        if (r%failed) return
        if (phys /= 0) call add_quad(data, tag, nodes(1:4), phys)
      case default
        if (phys /= 0) then
          if (element_dimension(element_type) < 0) then
            call status%add(prefix//'element '//i8toa(tag)//' has the unknown type '// &
                itoa(element_type)//' and is in physical group '//itoa(phys))
          else if (element_dimension(element_type) >= 2) then
            call report_bad_element(data, prefix, status, tag, element_type, &
                element_dimension(element_type), phys)
          end if
        end if
      end select
      call reader_end_line(r)
      if (r%failed) return
    end do
    data%has_elements = .true.
    call reader_expect(r, '$EndElements')
    call report_bad_summary(data, prefix, status)
  end subroutine parse_elements_22

  !> $Elements in format 4.1: entity blocks of "tag nodes..." lines.
  subroutine parse_elements_41(r, data, prefix, status)
    type(reader_t), intent(inout) :: r
    type(gmsh_data_t), intent(inout) :: data
    character(len=*), intent(in) :: prefix
    type(status_t), intent(inout) :: status
    integer :: nblock, n, b, i, k, p, dim, entity, element_type, count, total
    integer :: first_phys, last_phys, phys
    integer(i8) :: min_tag, max_tag, tag, nodes(8)

    call read_count(r, 'the number of element blocks', nblock)
    call read_count(r, 'the number of elements', n)
    call read_i8(r, 'the smallest element tag', min_tag)
    call read_i8(r, 'the largest element tag', max_tag)
    if (r%failed) return
    call reader_end_line(r)
    total = 0
    do b = 1, nblock
      call read_int(r, 'an entity dimension', dim)
      call read_int(r, 'an entity tag', entity)
      call read_int(r, 'an element type', element_type)
      call read_count(r, 'the number of elements in the block', count)
      if (r%failed) return
      call reader_end_line(r)
      if (count > n - total) then
        call reader_fail(r, 'bad counts: the element blocks hold more than the '// &
            itoa(n)//' elements announced in the $Elements header')
        return
      end if
      total = total + count
      first_phys = 1
      last_phys = 0
      if (dim >= 2) then
        call entity_physicals(r, data, dim, entity, first_phys, last_phys)
        if (r%failed) return
      end if
      if ((element_type == TYPE_HEX .and. dim /= 3) .or. &
          (element_type == TYPE_QUAD .and. dim /= 2)) then
        call reader_fail(r, 'element type '//itoa(element_type)//' in an entity of dimension '// &
            itoa(dim))
        return
      end if
      if (element_type == TYPE_HEX .and. last_phys > first_phys) then
        call status%add(prefix//'volume '//itoa(entity)//' is in several 3D physical '// &
            'groups; a hexahedron can belong to one block only')
      end if
      if (element_type == TYPE_HEX) call reserve_hex(data, data%nhex + count)
      if (element_type == TYPE_QUAD) then
        call reserve_quad(data, data%nquad + count * (last_phys - first_phys + 1))
      end if
      do i = 1, count
        call read_i8(r, 'an element tag', tag)
        if (r%failed) return
        if (tag < min_tag .or. tag > max_tag) then
          call reader_fail(r, 'bad counts: element tag '//i8toa(tag)// &
              ' is outside the range '//i8toa(min_tag)//'..'//i8toa(max_tag)// &
              ' given in the $Elements header')
          return
        end if
        if (element_type == TYPE_HEX) then
          do k = 1, 8
            call read_i8(r, 'a node tag', nodes(k))
          end do
          if (r%failed) return
          phys = 0
          if (last_phys >= first_phys) phys = data%entity_phys(first_phys)
          call add_hex(data, tag, nodes, phys)
        else if (element_type == TYPE_QUAD) then
          do k = 1, 4
            call read_i8(r, 'a node tag', nodes(k))
          end do
          if (r%failed) return
          do p = first_phys, last_phys
            call add_quad(data, tag, nodes(1:4), data%entity_phys(p))
          end do
        else if (last_phys >= first_phys) then
          call report_bad_element(data, prefix, status, tag, element_type, dim, &
              data%entity_phys(first_phys))
        end if
        call reader_end_line(r)
        if (r%failed) return
      end do
    end do
    if (total /= n) then
      call reader_fail(r, 'bad counts: the element blocks hold '//itoa(total)// &
          ' elements but the $Elements header announces '//itoa(n))
      return
    end if
    data%has_elements = .true.
    call reader_expect(r, '$EndElements')
    call report_bad_summary(data, prefix, status)
  end subroutine parse_elements_41

  !> Range of data%entity_phys holding the physical tags of entity (dim, tag).
  subroutine entity_physicals(r, data, dim, tag, first, last)
    type(reader_t), intent(inout) :: r
    type(gmsh_data_t), intent(in) :: data
    integer, intent(in) :: dim, tag
    integer, intent(out) :: first, last
    integer :: p, e

    first = 1
    last = 0
    if (.not. data%has_entities) then
      call reader_fail(r, 'elements refer to entities but the file has no $Entities section')
      return
    end if
    p = lower_bound(data%entity_key, data%entity_order, [int(dim, i8) * SHIFT + int(tag, i8)])
    if (p > data%nentity) then
      e = 0
    else
      e = data%entity_order(p)
      if (data%entity_key(1, e) /= int(dim, i8) * SHIFT + int(tag, i8)) e = 0
    end if
    if (e == 0) then
      call reader_fail(r, 'elements refer to the '//itoa(dim)//'D entity '//itoa(tag)// &
          ', which is not in $Entities')
      return
    end if
    first = data%entity_start(e)
    last = data%entity_start(e + 1) - 1
  end subroutine entity_physicals

  !> A non-hexahedron in a 3D group, or a non-quadrilateral in a 2D group.
  subroutine report_bad_element(data, prefix, status, tag, element_type, dim, phys)
    type(gmsh_data_t), intent(inout) :: data
    character(len=*), intent(in) :: prefix
    type(status_t), intent(inout) :: status
    integer(i8), intent(in) :: tag
    integer, intent(in) :: element_type, dim, phys

    data%nbad = data%nbad + 1
    if (data%nbad > MAX_REPORT) return
    if (dim == 3) then
      call status%add(prefix//'element '//i8toa(tag)//' of type '//itoa(element_type)// &
          ' is in the 3D physical group '//group_label(data, 3, phys)// &
          ', but impact3d needs hexahedra (8-node, Gmsh type 5): use Recombine'// &
          ' and Transfinite or Extrude with Layers')
    else
      call status%add(prefix//'element '//i8toa(tag)//' of type '//itoa(element_type)// &
          ' is in the 2D physical group '//group_label(data, 2, phys)// &
          ', but face sets need 4-node quadrilaterals (Gmsh type 3)')
    end if
  end subroutine report_bad_element

  !> The count of bad elements beyond those reported one by one.
  subroutine report_bad_summary(data, prefix, status)
    type(gmsh_data_t), intent(in) :: data
    character(len=*), intent(in) :: prefix
    type(status_t), intent(inout) :: status
    if (data%nbad > MAX_REPORT) then
      call status%add(prefix//itoa(data%nbad - MAX_REPORT)//' more elements of the wrong'// &
          ' type in 2D or 3D physical groups')
    end if
  end subroutine report_bad_summary

  !> 'name' (tag N) of a physical group if it is named, else "tag N".
  function group_label(data, dim, tag) result(label)
    type(gmsh_data_t), intent(in) :: data
    integer, intent(in) :: dim, tag
    character(len=:), allocatable :: label
    integer :: i
    label = itoa(tag)
    do i = 1, data%nname
      if (data%name_dim(i) == dim .and. data%name_tag(i) == tag) then
        label = ''''//trim(data%name_text(i))//''' (tag '//itoa(tag)//')'
        return
      end if
    end do
  end function group_label

  !> Room for n nodes.
  subroutine allocate_nodes(r, data, n)
    type(reader_t), intent(inout) :: r
    type(gmsh_data_t), intent(inout) :: data
    integer, intent(in) :: n
    integer :: stat
    allocate(data%node_tag(n), data%node_xyz(3, n), stat=stat)
    if (stat /= 0) call reader_fail(r, 'bad counts: cannot allocate '//itoa(n)//' nodes')
    data%nnode = n
  end subroutine allocate_nodes

  !> Room for at least n hexahedra.
  subroutine reserve_hex(data, n)
    type(gmsh_data_t), intent(inout) :: data
    integer, intent(in) :: n
    integer(i8), allocatable :: tag(:), node(:, :)
    integer, allocatable :: group(:)
    integer :: capacity
    if (data%mode /= MODE_WHOLE) return
    if (allocated(data%hex_tag)) then
      if (size(data%hex_tag) >= n) return
    end if
    capacity = max(n, 2 * data%nhex, 64)
    allocate(tag(capacity), node(8, capacity), group(capacity))
    if (data%nhex > 0) then
      tag(1:data%nhex) = data%hex_tag(1:data%nhex)
      node(:, 1:data%nhex) = data%hex_node(:, 1:data%nhex)
      group(1:data%nhex) = data%hex_group(1:data%nhex)
    end if
    call move_alloc(tag, data%hex_tag)
    call move_alloc(node, data%hex_node)
    call move_alloc(group, data%hex_group)
  end subroutine reserve_hex

  !> Room for at least n quadrilaterals.
  subroutine reserve_quad(data, n)
    type(gmsh_data_t), intent(inout) :: data
    integer, intent(in) :: n
    integer(i8), allocatable :: tag(:), node(:, :)
    integer, allocatable :: group(:)
    integer :: capacity
    if (data%mode /= MODE_WHOLE) return
    if (allocated(data%quad_tag)) then
      if (size(data%quad_tag) >= n) return
    end if
    capacity = max(n, 2 * data%nquad, 64)
    allocate(tag(capacity), node(4, capacity), group(capacity))
    if (data%nquad > 0) then
      tag(1:data%nquad) = data%quad_tag(1:data%nquad)
      node(:, 1:data%nquad) = data%quad_node(:, 1:data%nquad)
      group(1:data%nquad) = data%quad_group(1:data%nquad)
    end if
    call move_alloc(tag, data%quad_tag)
    call move_alloc(node, data%quad_node)
    call move_alloc(group, data%quad_group)
  end subroutine reserve_quad

  !> Append one hexahedron.
  subroutine add_hex(data, tag, nodes, phys)
    type(gmsh_data_t), intent(inout) :: data
    integer(i8), intent(in) :: tag, nodes(8)
    integer, intent(in) :: phys
    if (data%mode /= MODE_WHOLE) then
      call stream_hex(data, tag, nodes, phys)
      return
    end if
    call reserve_hex(data, data%nhex + 1)
    data%nhex = data%nhex + 1
    data%hex_tag(data%nhex) = tag
    data%hex_node(:, data%nhex) = nodes
    data%hex_group(data%nhex) = phys
  end subroutine add_hex

  !> Append one quadrilateral of the 2D group phys.
  subroutine add_quad(data, tag, nodes, phys)
    type(gmsh_data_t), intent(inout) :: data
    integer(i8), intent(in) :: tag, nodes(4)
    integer, intent(in) :: phys
    if (data%mode /= MODE_WHOLE) then
      call stream_quad(data, tag, nodes, phys)
      return
    end if
    call reserve_quad(data, data%nquad + 1)
    data%nquad = data%nquad + 1
    data%quad_tag(data%nquad) = tag
    data%quad_node(:, data%nquad) = nodes
    data%quad_group(data%nquad) = phys
  end subroutine add_quad

  !> Make a(:) hold at least n entries, keeping its contents.
  subroutine grow_int(a, n)
    integer, allocatable, intent(inout) :: a(:)
    integer, intent(in) :: n
    integer, allocatable :: b(:)
    if (size(a) >= n) return
    allocate(b(max(n, 2 * size(a))))
    b(1:size(a)) = a
    call move_alloc(b, a)
  end subroutine grow_int

  !> Dimension of a Gmsh element type, -1 if unknown.
  pure integer function element_dimension(element_type) result(dim)
    integer, intent(in) :: element_type
    select case (element_type)
    case (15)
      dim = 0
    case (1, 8, 26:28, 62:67, 70, 84)
      dim = 1
    case (2, 3, 9, 10, 16, 20:25, 34, 36:61, 68, 69, 85, 86)
      dim = 2
    case (4:7, 11:14, 17:19, 29:33, 35, 71:75, 79:83, 87:93)
      dim = 3
    case default
      dim = -1
    end select
  end function element_dimension

  ! ---------------------------------------------------------------------------
  ! Building the mesh
  ! ---------------------------------------------------------------------------

  !> Check what was read, renumber the nodes, match quads to hex faces, fill mesh.
  subroutine build_mesh(data, prefix, mesh, block_names, status)
    type(gmsh_data_t), intent(inout) :: data
    character(len=*), intent(in) :: prefix
    type(global_mesh_t), intent(inout) :: mesh
    character(len=NAME_LEN), allocatable, intent(inout) :: block_names(:)
    type(status_t), intent(inout) :: status
    integer, allocatable :: block_tags(:), set_tags(:), node_order(:), new_id(:)
    character(len=NAME_LEN), allocatable :: set_names(:)
    integer(i8), allocatable :: keys(:, :), node_keys(:, :)
    integer, allocatable :: order(:)
    integer :: z, k, i, nbad, nused, p
    logical, allocatable :: used(:)
    real(rk) :: volume
    character(len=24) :: text

    call reserve_hex(data, 1)
    call reserve_quad(data, 1)
    if (data%nhex == 0) then
      call status%add(prefix//'no 8-node hexahedra (Gmsh type 5) found; impact3d needs '// &
          'a hexahedral mesh (Recombine with Transfinite, or Extrude with Layers)')
      return
    end if

    ! Blocks and face sets.
    call group_tags(data, 3, data%hex_group(1:data%nhex), block_tags)
    call group_tags(data, 2, data%quad_group(1:data%nquad), set_tags)
    if (data%version == VERSION_41 .and. .not. data%has_names .and. &
        size(block_tags) + size(set_tags) > 0) then
      call status%add(prefix//'physical groups are used but the file has no '// &
          '$PhysicalNames section: name every 2D and 3D physical group '// &
          '(e.g. Physical Volume("steel") = {...};)')
    end if
    call group_names(data, prefix, 3, block_tags, block_names, status)
    call group_names(data, prefix, 2, set_tags, set_names, status)

    nbad = 0
    do z = 1, data%nhex
      if (data%hex_group(z) == 0) then
        call status%add_capped(nbad, MAX_REPORT, prefix//'hexahedron '//i8toa(data%hex_tag(z))// &
            ' is in no 3D physical group (every zone needs a block: define Physical Volumes)')
      end if
    end do
    call status%add_more(prefix, nbad, MAX_REPORT, 'hexahedra in no 3D physical group')

    ! Nodes: file index of every tag, then compact ids of those used by hexahedra.
    allocate(node_keys(1, data%nnode))
    node_keys(1, :) = data%node_tag(1:data%nnode)
    call sort_order(node_keys, node_order)
    nbad = 0
    do i = 2, data%nnode
      if (node_keys(1, node_order(i)) == node_keys(1, node_order(i - 1))) then
        call status%add_capped(nbad, MAX_REPORT, prefix//'node tag '//i8toa(node_keys(1, node_order(i)))// &
            ' appears more than once in $Nodes')
      end if
    end do
    call status%add_more(prefix, nbad, MAX_REPORT, 'repeated node tags')
    allocate(used(data%nnode), new_id(data%nnode))
    used = .false.
    nbad = 0
    do z = 1, data%nhex
      do k = 1, 8
        p = find_tag(node_keys, node_order, data%hex_node(k, z))
        if (p == 0) then
          call status%add_capped(nbad, MAX_REPORT, prefix//'hexahedron '//i8toa(data%hex_tag(z))// &
              ' refers to node '//i8toa(data%hex_node(k, z))//', which is not in $Nodes')
        else
          used(p) = .true.
        end if
      end do
    end do
    call status%add_more(prefix, nbad, MAX_REPORT, 'unknown node tags in hexahedra')
    if (nbad > 0) return

    new_id = 0
    nused = 0
    do i = 1, data%nnode
      if (used(node_order(i))) then
        nused = nused + 1
        new_id(node_order(i)) = nused
      end if
    end do
    mesh%nnode = nused
    mesh%nzone = data%nhex
    allocate(mesh%coordinates(3, nused), mesh%connectivity(8, data%nhex))
    allocate(mesh%zone_block(data%nhex))
    do i = 1, data%nnode
      if (new_id(i) > 0) mesh%coordinates(:, new_id(i)) = data%node_xyz(:, i)
    end do
    nbad = 0
    do i = 1, data%nnode
      if (new_id(i) > 0) then
        if (.not. all(ieee_is_finite(data%node_xyz(:, i)))) then
          call status%add_capped(nbad, MAX_REPORT, prefix//'node '//i8toa(data%node_tag(i))// &
              ' has a coordinate that is not a finite number')
        end if
      end if
    end do
    call status%add_more(prefix, nbad, MAX_REPORT, 'nodes with non-finite coordinates')
    if (nbad > 0) return
    do z = 1, data%nhex
      do k = 1, 8
        p = find_tag(node_keys, node_order, data%hex_node(k, z))
        mesh%connectivity(k, z) = int(new_id(p), ik)
      end do
      mesh%zone_block(z) = int(find_sorted(block_tags, data%hex_group(z)), ik)
    end do

    ! The same hexahedron twice: 2.2 files repeat the elements of a volume that is in
    ! several physical groups.
    allocate(keys(4, mesh%nzone))
    do z = 1, mesh%nzone
      keys(:, z) = sorted_key(int(mesh%connectivity(:, z)))
    end do
    call sort_order(keys, order)
    nbad = 0
    do i = 2, mesh%nzone
      if (all(keys(:, order(i)) == keys(:, order(i - 1)))) then
        call status%add_capped(nbad, MAX_REPORT, prefix//'hexahedra '//i8toa(data%hex_tag(order(i - 1)))// &
            ' and '//i8toa(data%hex_tag(order(i)))//' have the same nodes (is a volume in '// &
            'several 3D physical groups?)')
      end if
    end do
    call status%add_more(prefix, nbad, MAX_REPORT, 'repeated hexahedra')
    deallocate(keys, order)

    ! Orientation: Gmsh and impact3d share the node order, so a volume <= 0 is an error.
    nbad = 0
    do z = 1, mesh%nzone
      volume = hex_volume(mesh%coordinates(:, mesh%connectivity(:, z)))
      if (volume <= 0.0_rk) then
        write(text, '(es12.4)') volume
        call status%add_capped(nbad, MAX_REPORT, prefix//'hexahedron '//i8toa(data%hex_tag(z))// &
            ' has volume '//trim(adjustl(text))//' <= 0: its nodes are inverted or '// &
            'degenerate (impact3d does not reorder them)')
      end if
    end do
    call status%add_more(prefix, nbad, MAX_REPORT, 'hexahedra with volume <= 0')

    call build_sets(data, prefix, node_keys, node_order, new_id, set_tags, set_names, mesh, &
        status)
  end subroutine build_mesh

  !> Match every quadrilateral to a hexahedron face and fill the face sets of mesh.
  subroutine build_sets(data, prefix, node_keys, node_order, new_id, set_tags, set_names, &
      mesh, status)
    type(gmsh_data_t), intent(in) :: data
    character(len=*), intent(in) :: prefix
    integer(i8), intent(in) :: node_keys(:, :) !< (1, nnode in file): the node tags
    integer, intent(in) :: node_order(:) !< sorting permutation of node_keys
    integer, intent(in) :: new_id(:) !< compact id of each file node, 0 if unused
    integer, intent(in) :: set_tags(:) !< 2D physical tags of the sets, sorted
    character(len=NAME_LEN), intent(in) :: set_names(:)
    type(global_mesh_t), intent(inout) :: mesh
    type(status_t), intent(inout) :: status
    integer(i8), allocatable :: face_keys(:, :), entry_keys(:, :)
    integer, allocatable :: face_order(:), quad_set(:), quad_face(:), entry_order(:)
    integer :: z, f, q, k, p, nbad_node, nbad_face, nset, s, n, best, candidate, m, last
    integer :: nodes(4), file_index
    logical :: unknown

    nset = size(set_tags)
    ! Every hexahedron face, keyed by its sorted node ids.
    allocate(face_keys(2, 6 * mesh%nzone))
    do z = 1, mesh%nzone
      do f = 1, 6
        face_keys(:, 6 * (z - 1) + f) = &
            sorted_key(int(mesh%connectivity(HEX_FACE_NODES(:, f), z)))
      end do
    end do
    call sort_order(face_keys, face_order)

    allocate(quad_set(data%nquad), quad_face(data%nquad))
    quad_face = 0
    nbad_node = 0
    nbad_face = 0
    do q = 1, data%nquad
      quad_set(q) = find_sorted(set_tags, data%quad_group(q))
      unknown = .false.
      do k = 1, 4
        file_index = find_tag(node_keys, node_order, data%quad_node(k, q))
        if (file_index == 0) then
          unknown = .true.
          call status%add_capped(nbad_node, MAX_REPORT, prefix//'quadrilateral '//i8toa(data%quad_tag(q))// &
              ' refers to node '//i8toa(data%quad_node(k, q))//', which is not in $Nodes')
          nodes(k) = 0
        else
          nodes(k) = new_id(file_index)
        end if
      end do
      if (unknown) cycle
      best = 0
      if (all(nodes > 0)) then
        p = lower_bound(face_keys, face_order, sorted_key(nodes))
        do while (p <= size(face_order))
          candidate = face_order(p)
          if (any(face_keys(:, candidate) /= sorted_key(nodes))) exit
          ! Prefer the face whose outward normal agrees with the quad's orientation.
          if (best == 0) best = candidate
          z = (candidate - 1) / 6 + 1
          f = candidate - 6 * (z - 1)
          if (same_cycle(int(mesh%connectivity(HEX_FACE_NODES(:, f), z)), nodes)) then
            best = candidate
            exit
          end if
          p = p + 1
        end do
      end if
      if (best == 0) then
        call status%add_capped(nbad_face, MAX_REPORT, prefix//'quadrilateral '//i8toa(data%quad_tag(q))// &
            ' of face set '''//trim(set_names(quad_set(q)))//''' matches no hexahedron face')
      else
        quad_face(q) = best
      end if
    end do
    call status%add_more(prefix, nbad_node, MAX_REPORT, 'unknown node tags in quadrilaterals')
    call status%add_more(prefix, nbad_face, MAX_REPORT, 'quadrilaterals matching no hexahedron face')

    ! CSR by set, sorted by (zone, face) within each set, repeats removed.
    mesh%nset = nset
    allocate(mesh%set_name(nset), mesh%set_start(nset + 1))
    mesh%set_name = set_names
    allocate(entry_keys(2, data%nquad))
    do q = 1, data%nquad
      entry_keys(:, q) = [int(quad_set(q), i8), int(quad_face(q), i8)]
    end do
    call sort_order(entry_keys, entry_order)
    allocate(mesh%set_zone(data%nquad), mesh%set_face(data%nquad))
    n = 0
    m = 1
    do s = 1, nset
      mesh%set_start(s) = n + 1
      last = 0
      do while (m <= data%nquad)
        q = entry_order(m)
        if (quad_set(q) /= s) exit
        m = m + 1
        if (quad_face(q) == 0 .or. quad_face(q) == last) cycle
        last = quad_face(q)
        n = n + 1
        mesh%set_zone(n) = int((last - 1) / 6 + 1, ik)
        mesh%set_face(n) = int(last - 6 * (mesh%set_zone(n) - 1), ik)
      end do
    end do
    mesh%set_start(nset + 1) = n + 1
    call shrink(mesh%set_zone, n)
    call shrink(mesh%set_face, n)
  end subroutine build_sets

  !> Keep the first n entries of a.
  subroutine shrink(a, n)
    integer(ik), allocatable, intent(inout) :: a(:)
    integer, intent(in) :: n
    integer(ik), allocatable :: b(:)
    allocate(b(n))
    b = a(1:n)
    call move_alloc(b, a)
  end subroutine shrink

  !> Sorted distinct physical tags of dimension dim: named ones and those used.
  subroutine group_tags(data, dim, used, tags)
    type(gmsh_data_t), intent(in) :: data
    integer, intent(in) :: dim
    integer, intent(in) :: used(:) !< tags of elements, 0 = none
    integer, allocatable, intent(out) :: tags(:)
    integer(i8), allocatable :: keys(:, :)
    integer, allocatable :: order(:)
    integer :: n, i, m

    n = 0
    allocate(keys(1, size(used) + data%nname))
    do i = 1, size(used)
      if (used(i) /= 0) then
        n = n + 1
        keys(1, n) = used(i)
      end if
    end do
    do i = 1, data%nname
      if (data%name_dim(i) == dim) then
        n = n + 1
        keys(1, n) = data%name_tag(i)
      end if
    end do
    call sort_order(keys(:, 1:n), order)
    allocate(tags(n))
    m = 0
    do i = 1, n
      if (m > 0) then
        if (tags(m) == keys(1, order(i))) cycle
      end if
      m = m + 1
      tags(m) = int(keys(1, order(i)))
    end do
    tags = tags(1:m)
  end subroutine group_tags

  !> Names of the groups (dim, tags(:)); unnamed 2.2 groups become 'physical_N'.
  subroutine group_names(data, prefix, dim, tags, names, status)
    type(gmsh_data_t), intent(in) :: data
    character(len=*), intent(in) :: prefix
    integer, intent(in) :: dim, tags(:)
    character(len=NAME_LEN), allocatable, intent(inout) :: names(:)
    type(status_t), intent(inout) :: status
    character(len=256) :: name
    integer :: i, j, k
    logical :: found

    if (allocated(names)) deallocate(names)
    allocate(names(size(tags)))
    do i = 1, size(tags)
      found = .false.
      do j = 1, data%nname
        if (data%name_dim(j) == dim .and. data%name_tag(j) == tags(i)) then
          found = .true.
          name = data%name_text(j)
          exit
        end if
      end do
      if (.not. found) then
        name = 'physical_'//itoa(tags(i))
        ! Without any $PhysicalNames, build_mesh has said so once.
        if (data%version == VERSION_41 .and. data%has_names) then
          call status%add(prefix//'the '//itoa(dim)//'D physical group '//itoa(tags(i))// &
              ' has no name in $PhysicalNames')
        end if
      end if
      if (len_trim(name) == 0) then
        call status%add(prefix//'the '//itoa(dim)//'D physical group '//itoa(tags(i))// &
            ' has an empty name')
      else if (len_trim(name) > NAME_LEN) then
        call status%add(prefix//'the name '''//trim(name)//''' of the '//itoa(dim)// &
            'D physical group '//itoa(tags(i))//' is longer than '//itoa(NAME_LEN)// &
            ' characters')
      end if
      names(i) = name(1:NAME_LEN)
      do k = 1, i - 1
        if (names(k) == names(i) .and. len_trim(name) > 0) then
          call status%add(prefix//'the '//itoa(dim)//'D physical groups '//itoa(tags(k))// &
              ' and '//itoa(tags(i))//' have the same name '''//trim(names(i))//'''')
        end if
      end do
    end do
  end subroutine group_names

  !> Sort key of a face or element: its node ids (an even number of them, each
  !> in 0..2**31-1) in increasing order, packed two by two.
  pure function sorted_key(nodes) result(key)
    integer, intent(in) :: nodes(:)
    integer(i8) :: key(size(nodes) / 2)
    integer :: s(size(nodes)), i
    s = nodes
    call sort_values(s)
    do i = 1, size(key)
      key(i) = int(s(2 * i - 1), i8) * SHIFT + int(s(2 * i), i8)
    end do
  end function sorted_key

  !> True if b lists the nodes of a in the same cyclic order (same orientation).
  pure logical function same_cycle(a, b)
    integer, intent(in) :: a(4), b(4)
    integer :: shift_by, k
    same_cycle = .false.
    do shift_by = 0, 3
      if (a(1 + shift_by) /= b(1)) cycle
      same_cycle = .true.
      do k = 1, 3
        if (a(1 + modulo(shift_by + k, 4)) /= b(1 + k)) same_cycle = .false.
      end do
      return
    end do
  end function same_cycle

  ! ---------------------------------------------------------------------------
  ! Sorting and searching
  ! ---------------------------------------------------------------------------

  !> First position p in order with keys(:, order(p)) >= key; size(order) + 1 if none.
  pure integer function lower_bound(keys, order, key) result(lo)
    integer(i8), intent(in) :: keys(:, :)
    integer, intent(in) :: order(:)
    integer(i8), intent(in) :: key(:)
    integer :: hi, mid, i
    logical :: less
    lo = 1
    hi = size(order) + 1
    do while (lo < hi)
      mid = (lo + hi) / 2
      less = .false.
      do i = 1, size(key)
        if (keys(i, order(mid)) /= key(i)) then
          less = keys(i, order(mid)) < key(i)
          exit
        end if
      end do
      if (less) then
        lo = mid + 1
      else
        hi = mid
      end if
    end do
  end function lower_bound

  !> Column of the one-row keys equal to tag, 0 if none.
  pure integer function find_tag(keys, order, tag) result(column)
    integer(i8), intent(in) :: keys(:, :)
    integer, intent(in) :: order(:)
    integer(i8), intent(in) :: tag
    integer :: p
    column = 0
    p = lower_bound(keys, order, [tag])
    if (p <= size(order)) then
      if (keys(1, order(p)) == tag) column = order(p)
    end if
  end function find_tag

  !> Position of value in the sorted list, 0 if absent.
  pure integer function find_sorted(list, value) result(position)
    integer, intent(in) :: list(:), value
    integer :: lo, hi, mid
    position = 0
    lo = 1
    hi = size(list)
    do while (lo <= hi)
      mid = (lo + hi) / 2
      if (list(mid) == value) then
        position = mid
        return
      else if (list(mid) < value) then
        lo = mid + 1
      else
        hi = mid - 1
      end if
    end do
  end function find_sorted

  ! ---------------------------------------------------------------------------
  ! Token reader
  ! ---------------------------------------------------------------------------

  !> Record the first fatal problem, with the line number and section.
  subroutine reader_fail(r, text)
    type(reader_t), intent(inout) :: r
    character(len=*), intent(in) :: text
    if (r%failed) return
    r%failed = .true.
    if (len(r%section) > 0) then
      r%message = 'line '//itoa(r%line_number)//' (in '//r%section//'): '//text
    else
      r%message = 'line '//itoa(r%line_number)//': '//text
    end if
  end subroutine reader_fail

  !> Read the next line, of any length, without its line terminator (LF,
  !> with a CR before it dropped). The file is read as a byte stream in
  !> blocks of BLOCK_LEN: gfortran's formatted non-advancing reads keep a
  !> buffer that grew with the file (16 MB for a 12 MB mesh).
  subroutine reader_next_line(r)
    type(reader_t), intent(inout) :: r
    character(len=256) :: msg
    integer :: ios, n, k
    logical :: got
    r%line = ''
    r%pos = 1
    if (r%eof) return
    got = .false.
    do
      if (r%bpos > r%blen) then
        if (r%fpos > r%fsize) then
          if (.not. got) then
            r%eof = .true.
            return
          end if
          exit
        end if
        n = int(min(int(BLOCK_LEN, i8), r%fsize - r%fpos + 1))
        read(r%unit, pos=r%fpos, iostat=ios, iomsg=msg) r%block(1:n)
        if (ios /= 0) then
          r%line_number = r%line_number + 1
          call reader_fail(r, 'cannot read: '//trim(msg))
          r%eof = .true.
          return
        end if
        r%fpos = r%fpos + n
        r%blen = n
        r%bpos = 1
      end if
      got = .true.
      k = index(r%block(r%bpos:r%blen), achar(10))
      if (k == 0) then
        r%line = r%line//r%block(r%bpos:r%blen)
        r%bpos = r%blen + 1
      else
        r%line = r%line//r%block(r%bpos:r%bpos + k - 2)
        r%bpos = r%bpos + k
        exit
      end if
    end do
    r%line_number = r%line_number + 1
    if (len(r%line) > 0) then
      if (r%line(len(r%line):) == achar(13)) r%line = r%line(1:len(r%line) - 1)
    end if
  end subroutine reader_next_line

  !> Next whitespace-separated token as r%line(first:last); at_end at the end of the file.
  subroutine reader_token(r, first, last, at_end)
    type(reader_t), intent(inout) :: r
    integer, intent(out) :: first, last
    logical, intent(out) :: at_end
    first = 1
    last = 0
    at_end = .false.
    do
      if (r%failed) return
      do while (r%pos <= len(r%line))
        if (.not. is_blank(r%line(r%pos:r%pos))) exit
        r%pos = r%pos + 1
      end do
      if (r%pos <= len(r%line)) exit
      call reader_next_line(r)
      if (r%eof) then
        at_end = .true.
        return
      end if
    end do
    first = r%pos
    do while (r%pos <= len(r%line))
      if (is_blank(r%line(r%pos:r%pos))) exit
      r%pos = r%pos + 1
    end do
    last = r%pos - 1
  end subroutine reader_token

  !> Next token, which must exist: the end of the file here means truncation.
  subroutine reader_required_token(r, what, first, last)
    type(reader_t), intent(inout) :: r
    character(len=*), intent(in) :: what
    integer, intent(out) :: first, last
    logical :: at_end
    call reader_token(r, first, last, at_end)
    if (at_end) call reader_fail(r, 'unexpected end of file while reading '//what// &
        ': the file is truncated or a count is too large')
  end subroutine reader_required_token

  !> Drop the rest of the current line.
  subroutine reader_end_line(r)
    type(reader_t), intent(inout) :: r
    r%pos = len(r%line) + 1
  end subroutine reader_end_line

  !> The next token must be text (a section end).
  subroutine reader_expect(r, text)
    type(reader_t), intent(inout) :: r
    character(len=*), intent(in) :: text
    integer :: i1, i2
    call reader_required_token(r, text, i1, i2)
    if (r%failed) return
    if (r%line(i1:i2) /= text) then
      call reader_fail(r, 'bad counts: expected '//text//' but found '''// &
          clip(r%line(i1:i2))//''' (the section holds more entries than its header says)')
    end if
  end subroutine reader_expect

  !> Skip an unknown section up to its $End line.
  subroutine reader_skip_section(r, name)
    type(reader_t), intent(inout) :: r
    character(len=*), intent(in) :: name !< without the $
    do
      call reader_next_line(r)
      if (r%failed) return
      if (r%eof) then
        call reader_fail(r, 'unexpected end of file: section $'//name//' is not closed')
        return
      end if
      if (trim(adjustl(r%line)) == '$End'//name) exit
    end do
    call reader_end_line(r)
  end subroutine reader_skip_section

  !> Next token as a 64-bit integer.
  subroutine read_i8(r, what, value)
    type(reader_t), intent(inout) :: r
    character(len=*), intent(in) :: what
    integer(i8), intent(out) :: value
    integer :: i1, i2
    logical :: ok
    value = 0
    call reader_required_token(r, what, i1, i2)
    if (r%failed) return
    call parse_i8(r%line(i1:i2), value, ok)
    if (.not. ok) call reader_fail(r, 'expected '//what//' (an integer), found '''// &
        clip(r%line(i1:i2))//'''')
  end subroutine read_i8

  !> Next token as a default integer.
  subroutine read_int(r, what, value)
    type(reader_t), intent(inout) :: r
    character(len=*), intent(in) :: what
    integer, intent(out) :: value
    integer(i8) :: big
    value = 0
    call read_i8(r, what, big)
    if (r%failed) return
    if (abs(big) > int(huge(value), i8)) then
      call reader_fail(r, what//' '//i8toa(big)//' is too large')
      return
    end if
    value = int(big)
  end subroutine read_int

  !> A count: an integer >= 0.
  subroutine read_count(r, what, value)
    type(reader_t), intent(inout) :: r
    character(len=*), intent(in) :: what
    integer, intent(out) :: value
    call read_int(r, what, value)
    if (r%failed) return
    if (value < 0) call reader_fail(r, 'bad counts: '//what//' is negative ('//itoa(value)//')')
  end subroutine read_count

  !> Next token as a real number.
  subroutine read_real(r, what, value)
    type(reader_t), intent(inout) :: r
    character(len=*), intent(in) :: what
    real(rk), intent(out) :: value
    integer :: i1, i2, ios
    value = 0.0_rk
    call reader_required_token(r, what, i1, i2)
    if (r%failed) return
    ios = 1
    if (verify(r%line(i1:i2), '0123456789+-.eEdD') == 0) then
      read(r%line(i1:i2), *, iostat=ios) value
    end if
    if (ios /= 0) call reader_fail(r, 'expected '//what//' (a number), found '''// &
        clip(r%line(i1:i2))//'''')
  end subroutine read_real

  !> Decimal integer with an optional sign; ok false on anything else or overflow.
  pure subroutine parse_i8(text, value, ok)
    character(len=*), intent(in) :: text
    integer(i8), intent(out) :: value
    logical, intent(out) :: ok
    integer :: i, start, digit
    logical :: negative
    value = 0
    ok = .false.
    if (len(text) == 0) return
    negative = text(1:1) == '-'
    start = 1
    if (text(1:1) == '-' .or. text(1:1) == '+') start = 2
    if (start > len(text)) return
    do i = start, len(text)
      digit = iachar(text(i:i)) - iachar('0')
      if (digit < 0 .or. digit > 9) return
      if (value > (huge(value) - digit) / 10) return
      value = 10 * value + digit
    end do
    if (negative) value = -value
    ok = .true.
  end subroutine parse_i8

  !> Space or tab.
  pure logical function is_blank(c)
    character, intent(in) :: c
    is_blank = c == ' ' .or. c == achar(9)
  end function is_blank

  !> At most 40 characters of text, for messages.
  pure function clip(text) result(short)
    character(len=*), intent(in) :: text
    character(len=:), allocatable :: short
    if (len(text) > 40) then
      short = text(1:40)//'...'
    else
      short = text
    end if
  end function clip

  ! ---------------------------------------------------------------------------
  ! Read in chunks: rank 0 streams the file, every rank keeps its share
  ! ---------------------------------------------------------------------------

  !> The rank that keeps node tag (its block of the part's tag range; tags
  !> outside the range go to the first or last rank).
  integer function tag_owner(part, tag) result(r)
    type(gmsh_part_t), intent(in) :: part
    integer(i8), intent(in) :: tag
    r = par_block_owner(part%ntag, par_size(), min(max(tag - part%tag_lo + 1, 1_i8), &
        part%ntag))
  end function tag_owner

  !> Rank 0 tells the others what comes next (cmd and two numbers).
  subroutine send_command(cmd, a, b)
    integer, intent(in) :: cmd
    integer(i8), intent(in) :: a, b
    integer(i8) :: c(3)
    c = [int(cmd, i8), a, b]
    call par_bcast(c)
  end subroutine send_command

  !> The node tags' layout: tags lo .. lo + n - 1 in blocks over the ranks.
  subroutine stream_layout(data, lo, n)
    type(gmsh_data_t), intent(inout) :: data
    integer(i8), intent(in) :: lo, n
    data%part%tag_lo = lo
    data%part%ntag = max(n, 1_i8)
    call send_command(CMD_LAYOUT, data%part%tag_lo, data%part%ntag)
  end subroutine stream_layout

  !> One record of kind cmd for rank dest into rank 0's chunk (sent when full).
  subroutine emit(data, cmd, rec, dest)
    type(gmsh_data_t), intent(inout) :: data
    integer, intent(in) :: cmd
    integer(i8), intent(in) :: rec(:)
    integer, intent(in) :: dest
    if (data%buf_cmd /= cmd .and. data%nbuf > 0) call flush(data)
    if (data%nbuf == 0) then
      data%buf_cmd = cmd
      if (allocated(data%buf)) then
        if (size(data%buf, 1) /= WIDTH(cmd)) deallocate(data%buf)
      end if
      if (.not. allocated(data%buf)) allocate(data%buf(WIDTH(cmd), CHUNK_WORDS / WIDTH(cmd)))
      if (.not. allocated(data%buf_dest)) allocate(data%buf_dest(CHUNK_WORDS))
    end if
    data%nbuf = data%nbuf + 1
    data%buf(:, data%nbuf) = rec
    data%buf_dest(data%nbuf) = dest
    if (data%nbuf == size(data%buf, 2)) call flush(data)
  end subroutine emit

  !> Send rank 0's chunk (every rank takes part in deliver).
  subroutine flush(data)
    type(gmsh_data_t), intent(inout) :: data
    if (data%nbuf == 0) return
    call send_command(data%buf_cmd, int(data%nbuf, i8), 0_i8)
    call deliver(data%buf_cmd, data%part, data%range, data%buf, data%buf_dest(:data%nbuf))
    data%nbuf = 0
  end subroutine flush

  !> A chunk's records to their ranks, kept there (collective).
  subroutine deliver(cmd, part, range, send, dest)
    integer, intent(in) :: cmd
    type(gmsh_part_t), intent(inout) :: part
    type(mesh_range_t), intent(inout) :: range
    !> (width, >= size(dest)) the chunk (its first size(dest) records); freed
    integer(i8), allocatable, intent(inout) :: send(:, :)
    integer, intent(in) :: dest(:)
    integer(i8), allocatable :: recv(:, :), grown(:, :)
    integer :: i, m, p, local
    call par_route_free(send, dest, recv)
    m = size(recv, 2)
    select case (cmd)
    case (CMD_NODES)
      if (part%nstore + m > size(part%store, 2)) then
        allocate(grown(6, max(part%nstore + m, 2 * size(part%store, 2))))
        grown(:, :part%nstore) = part%store(:, :part%nstore)
        call move_alloc(grown, part%store)
      end if
      part%store(1:5, part%nstore + 1:part%nstore + m) = recv
      part%store(6, part%nstore + 1:part%nstore + m) = 0
      part%nstore = part%nstore + m
    case (CMD_USED)
      do i = 1, m
        p = find_store(part, recv(1, i))
        if (p > 0) part%store(6, p) = 1
      end do
    case (CMD_HEX)
      do i = 1, m
        local = int(recv(1, i) - range%first) + 1
        range%conn(:, local) = recv(4:11, i)
        range%zone_block(local) = int(recv(3, i), ik)
        part%hex_tag(local) = recv(2, i)
      end do
    case (CMD_QUAD)
      if (part%nq + m > size(part%quads, 2)) then
        allocate(grown(7, max(part%nq + m, 2 * size(part%quads, 2))))
        grown(:, :part%nq) = part%quads(:, :part%nq)
        call move_alloc(grown, part%quads)
      end if
      part%quads(:, part%nq + 1:part%nq + m) = recv
      part%nq = part%nq + m
    end select
  end subroutine deliver

  !> Column of the first stored node with tag (the store sorted), 0 if none.
  integer function find_store(part, tag) result(p)
    type(gmsh_part_t), intent(in) :: part
    integer(i8), intent(in) :: tag
    integer :: lo, hi, mid
    lo = 1
    hi = part%nstore + 1
    do while (lo < hi)
      mid = (lo + hi) / 2
      if (part%store(1, mid) < tag) then
        lo = mid + 1
      else
        hi = mid
      end if
    end do
    p = 0
    if (lo <= part%nstore) then
      if (part%store(1, lo) == tag) p = lo
    end if
  end function find_store

  !> This rank's nodes sorted by tag, then by place in $Nodes.
  subroutine sort_store(part)
    type(gmsh_part_t), intent(inout) :: part
    integer, allocatable :: order(:)
    call sort_order(part%store(1:2, :part%nstore), order)
    part%store = part%store(:, order)
    part%nstore = size(order)
  end subroutine sort_store

  !> The ranks other than 0 while rank 0 streams: take part in its chunks.
  subroutine stream_serve(part, range)
    type(gmsh_part_t), intent(inout) :: part
    type(mesh_range_t), intent(inout) :: range
    integer(i8) :: c(3)
    integer(i8), allocatable :: empty(:, :)
    integer :: none(0)
    do
      c = 0
      call par_bcast(c)
      select case (int(c(1)))
      case (CMD_END)
        exit
      case (CMD_LAYOUT)
        part%tag_lo = c(2)
        part%ntag = c(3)
      case (CMD_NODES_DONE)
        call sort_store(part)
      case default
        allocate(empty(WIDTH(int(c(1))), 0))
        call deliver(int(c(1)), part, range, empty, none)
      end select
    end do
  end subroutine stream_serve

  !> Rank 0: a node of $Nodes to the owner of its tag.
  subroutine stream_node(data, tag, xyz)
    type(gmsh_data_t), intent(inout) :: data
    integer(i8), intent(in) :: tag
    real(rk), intent(in) :: xyz(3)
    data%nstream_node = data%nstream_node + 1
    call emit(data, CMD_NODES, [tag, data%nstream_node, transfer(xyz(1), 1_i8), &
        transfer(xyz(2), 1_i8), transfer(xyz(3), 1_i8)], tag_owner(data%part, tag))
  end subroutine stream_node

  !> Rank 0: the end of $Nodes (every rank sorts its nodes).
  subroutine stream_nodes_done(data)
    type(gmsh_data_t), intent(inout) :: data
    call flush(data)
    call send_command(CMD_NODES_DONE, 0_i8, 0_i8)
    call sort_store(data%part)
  end subroutine stream_nodes_done

  !> Rank 0: a hexahedron. Scan: its group noted, its node tags marked used
  !> by their owners; zones: the whole record to the rank of its zone.
  subroutine stream_hex(data, tag, nodes, phys)
    type(gmsh_data_t), intent(inout) :: data
    integer(i8), intent(in) :: tag, nodes(8)
    integer, intent(in) :: phys
    integer(i8) :: g
    integer :: k
    data%nstream_hex = data%nstream_hex + 1
    if (data%mode == MODE_SCAN) then
      if (phys /= 0) then
        call add_distinct(data%hex_groups, phys)
      else
        data%nnogroup = data%nnogroup + 1
        if (data%nnogroup <= size(data%nogroup)) data%nogroup(data%nnogroup) = &
            data%prefix//'hexahedron '//i8toa(tag)//' is in no 3D physical group (every '// &
            'zone needs a block: define Physical Volumes)'
      end if
      do k = 1, 8
        call emit(data, CMD_USED, [nodes(k)], tag_owner(data%part, nodes(k)))
      end do
    else
      g = data%zone0 + data%nstream_hex
      call emit(data, CMD_HEX, [g, tag, int(phys, i8), nodes], &
          par_block_owner(data%range%nzone_global, par_size(), g))
    end if
  end subroutine stream_hex

  !> Rank 0: a quadrilateral of a 2D group (scan: its group noted; zones: to
  !> the rank of its block of the quadrilaterals).
  subroutine stream_quad(data, tag, nodes, phys)
    type(gmsh_data_t), intent(inout) :: data
    integer(i8), intent(in) :: tag, nodes(4)
    integer, intent(in) :: phys
    data%nstream_quad = data%nstream_quad + 1
    if (data%mode == MODE_SCAN) then
      call add_distinct(data%quad_groups, phys)
    else
      call emit(data, CMD_QUAD, [data%nstream_quad, tag, int(phys, i8), nodes], &
          par_block_owner(data%part%nquad, par_size(), data%nstream_quad))
    end if
  end subroutine stream_quad

  !> value into the list if not there yet.
  subroutine add_distinct(list, value)
    integer, allocatable, intent(inout) :: list(:)
    integer, intent(in) :: value
    if (.not. allocated(list)) allocate(list(0))
    if (any(list == value)) return
    list = [list, value]
  end subroutine add_distinct

  !> Rank 0 streams the file with data%mode set; the other ranks serve.
  !> Problems of the parse are added to status on rank 0 only.
  subroutine stream_file(path, prefix, data, part, range, status, opened)
    character(len=*), intent(in) :: path, prefix
    type(gmsh_data_t), intent(inout) :: data
    type(gmsh_part_t), intent(inout), target :: part
    type(mesh_range_t), intent(inout), target :: range
    type(status_t), intent(inout) :: status
    logical, intent(out) :: opened
    type(reader_t) :: r
    logical :: exists
    integer :: ios
    character(len=256) :: msg
    opened = .false.
    if (par_rank() /= 0) then
      call stream_serve(part, range)
      return
    end if
    data%part => part
    data%range => range
    data%prefix = prefix
    inquire(file=path, exist=exists)
    if (.not. exists) then
      call status%add(prefix//'no such file')
    else
      open(newunit=r%unit, file=path, status='old', action='read', form='unformatted', &
          access='stream', iostat=ios, iomsg=msg)
      if (ios /= 0) then
        call status%add(prefix//'cannot open it: '//trim(msg))
      else
        opened = .true.
        r%line = ''
        r%section = ''
        r%message = ''
        inquire(unit=r%unit, size=r%fsize)
        allocate(character(len=BLOCK_LEN) :: r%block)
        call parse_file(r, data, prefix, status)
        close(r%unit)
        if (r%failed) then
          call status%add(prefix//r%message)
        else
          call flush(data)
        end if
      end if
    end if
    data%nbuf = 0
    call send_command(CMD_END, 0_i8, 0_i8)
  end subroutine stream_file

  !> First pass of a read in chunks (collective): rank 0 streams the file,
  !> sending the nodes to the owners of their tags and the hexahedra's node
  !> tags to the same owners (which mark them used), and keeps only the
  !> groups seen and counts; then the blocks and sets are named, repeated
  !> node tags found and the used nodes numbered in tag order. Every rank
  !> ends with the same problems in status.
  subroutine gmsh_scan(path, part, status)
    character(len=*), intent(in) :: path
    type(gmsh_part_t), intent(inout), target :: part
    type(status_t), intent(inout) :: status
    type(gmsh_data_t) :: data
    type(mesh_range_t), target :: none
    character(len=:), allocatable :: prefix
    character(len=LINE_LEN), allocatable :: lines(:), all(:)
    integer(i8) :: sizes(4), nused, before
    integer :: count0, i, nbad
    logical :: opened

    prefix = "mesh file '"//trim(path)//"': "
    part%path = path
    count0 = status%count
    allocate(part%store(6, 1024), part%quads(7, 0), part%hex_tag(0))
    allocate(part%block_tags(0), part%set_tags(0), part%block_names(0), part%set_names(0))
    data%mode = MODE_SCAN
    call stream_file(path, prefix, data, part, none, status, opened)
    if (par_rank() == 0 .and. status%count == count0) call scan_groups(data, prefix, part, status)
    ! Rank 0's problems to every rank.
    allocate(lines(0))
    if (par_rank() == 0 .and. status%count > count0) then
      deallocate(lines)
      allocate(lines(max(0, min(status%count, size(status%messages)) - count0)))
      do i = 1, size(lines)
        lines(i) = status%messages(count0 + i)
      end do
    end if
    call par_allgather_text(lines, all)
    if (par_rank() /= 0) then
      do i = 1, size(all)
        call status%add(trim(all(i)))
      end do
    end if
    if (size(all) > 0) return
    ! Sizes and names to every rank.
    sizes = [data%nstream_hex, data%nstream_quad, int(size(part%block_tags), i8), &
        int(size(part%set_tags), i8)]
    call par_bcast(sizes)
    part%nhex = sizes(1)
    part%nquad = sizes(2)
    if (par_rank() /= 0) then
      deallocate(part%block_tags, part%set_tags, part%block_names, part%set_names)
      allocate(part%block_tags(sizes(3)), part%set_tags(sizes(4)), &
          part%block_names(sizes(3)), part%set_names(sizes(4)), part%block_used(sizes(3)))
    end if
    call par_bcast(part%block_used)
    call par_bcast(part%block_tags)
    call par_bcast(part%set_tags)
    call par_bcast(part%block_names)
    call par_bcast(part%set_names)
    ! Repeated tags (tag order is rank order), then the used nodes' ids.
    deallocate(lines)
    allocate(lines(10))
    nbad = 0
    do i = 2, part%nstore
      if (part%store(1, i) /= part%store(1, i - 1)) cycle
      nbad = nbad + 1
      if (nbad <= size(lines)) lines(nbad) = prefix//'node tag '//i8toa(part%store(1, i))// &
          ' appears more than once in $Nodes'
    end do
    call merge_capped(status, prefix, lines, nbad, 'repeated node tags')
    nused = count(part%store(6, :part%nstore) > 0)
    before = par_exscan_i8(nused)
    part%nnode = par_sum(nused)
    nused = 0
    do i = 1, part%nstore
      if (part%store(6, i) == 0) cycle
      nused = nused + 1
      part%store(6, i) = before + nused
    end do
  end subroutine gmsh_scan

  !> Rank 0 after the scan: the checks of build_mesh that need only the
  !> groups seen (no hexahedra; names of the groups; hexahedra in no group).
  subroutine scan_groups(data, prefix, part, status)
    type(gmsh_data_t), intent(inout) :: data
    character(len=*), intent(in) :: prefix
    type(gmsh_part_t), intent(inout) :: part
    type(status_t), intent(inout) :: status
    integer :: i
    if (.not. allocated(data%hex_groups)) allocate(data%hex_groups(0))
    if (.not. allocated(data%quad_groups)) allocate(data%quad_groups(0))
    if (data%nstream_hex == 0) then
      call status%add(prefix//'no 8-node hexahedra (Gmsh type 5) found; impact3d needs '// &
          'a hexahedral mesh (Recombine with Transfinite, or Extrude with Layers)')
      return
    end if
    call group_tags(data, 3, data%hex_groups, part%block_tags)
    call group_tags(data, 2, data%quad_groups, part%set_tags)
    if (data%version == VERSION_41 .and. .not. data%has_names .and. &
        size(part%block_tags) + size(part%set_tags) > 0) then
      call status%add(prefix//'physical groups are used but the file has no '// &
          '$PhysicalNames section: name every 2D and 3D physical group '// &
          '(e.g. Physical Volume("steel") = {...};)')
    end if
    call group_names(data, prefix, 3, part%block_tags, part%block_names, status)
    call group_names(data, prefix, 2, part%set_tags, part%set_names, status)
    part%block_used = [(any(data%hex_groups == part%block_tags(i)), i = 1, size(part%block_tags))]
    do i = 1, min(data%nnogroup, size(data%nogroup))
      call status%add(trim(data%nogroup(i)))
    end do
    call status%add_more(prefix, data%nnogroup, MAX_REPORT, 'hexahedra in no 3D physical group')
  end subroutine scan_groups

  !> Second pass (collective): rank 0 streams the file again, sending each
  !> hexahedron to the rank of its zone (global id zone0 + its place) and the
  !> quadrilaterals in blocks; the nodes' owners answer the ids and positions
  !> of the tags each rank's zones and quadrilaterals use; then the checks of
  !> build_mesh, the matching of quadrilaterals to hexahedron faces (by the
  !> owners of the faces' smallest node) and the face sets (sorted by zone
  !> and face, repeats dropped, as build_sets makes them), all distributed.
  !> part%set_count: the faces of each set (the range's set counts are the
  !> caller's). summary: mesh_import_summary's lines, bitwise on any rank
  !> count. lo..hi: the range positions filled.
  subroutine range_add_gmsh(range, part, zone0, node0, sets, ord0, lo, hi, title, summary, &
      status)
    type(mesh_range_t), intent(inout), target :: range
    type(gmsh_part_t), intent(inout), target :: part
    integer(i8), intent(in) :: zone0, node0
    integer, intent(in) :: sets(:, :) !< (2, nset of the part)
    integer(i8), intent(in) :: ord0(:, :) !< (2, nset of the part)
    integer, intent(out) :: lo, hi
    character(len=*), intent(in) :: title
    character(len=200), allocatable, intent(out) :: summary(:)
    type(status_t), intent(inout) :: status
    type(gmsh_data_t) :: data
    type(status_t) :: again
    type(keyed_report_t) :: keyed
    character(len=:), allocatable :: prefix
    character(len=LINE_LEN) :: lines(MAX_REPORT)
    character(len=24) :: text
    integer(i8), allocatable :: ids(:), send(:, :), recv(:, :), answer(:, :), key(:), ans(:, :)
    integer(i8), allocatable :: faces(:, :), entries(:, :), cnt(:), off(:), quads(:, :), &
        best2(:, :)
    integer, allocatable :: dest(:), source(:), order(:)
    real(rk), allocatable :: value(:, :), vol(:), volume(:)
    real(rk) :: total(4), p(3, 4), a
    integer(i8) :: zfirst, zlast, g, fk(2), kk(4)
    integer :: nz, i, j, k, c, f, n, nbad, s, m, pos, nset, cand, nid(4)
    logical :: opened, unknown

    prefix = "mesh file '"//trim(part%path)//"': "
    nset = size(part%set_tags)
    zfirst = max(zone0 + 1, range%first)
    zlast = min(zone0 + part%nhex, range%first + range%nzone - 1)
    lo = int(zfirst - range%first) + 1
    hi = int(zlast - range%first) + 1
    nz = max(0, hi - lo + 1)
    allocate(summary(0), part%set_count(nset))
    part%set_count = 0
    deallocate(part%hex_tag)
    allocate(part%hex_tag(range%nzone))
    data%mode = MODE_ZONES
    data%zone0 = zone0
    call stream_file(part%path, prefix, data, part, range, again, opened)
    if (par_max(again%count) > 0) then
      call status%add(prefix//'the file changed while it was read')
      return
    end if

    ! Ids and positions of the node tags used here, from the tags' owners:
    ! [tag, found, id, x, y, z, index in $Nodes].
    ids = [reshape(range%conn(:, lo:lo + nz - 1), [8 * nz]), &
        reshape(part%quads(4:7, :part%nq), [4 * part%nq])]
    call sort_unique(ids)
    allocate(send(1, size(ids)), dest(size(ids)))
    send(1, :) = ids
    do i = 1, size(ids)
      dest(i) = tag_owner(part, ids(i))
    end do
    call par_route_free(send, dest, recv, source)
    deallocate(dest)
    allocate(answer(7, size(recv, 2)))
    do i = 1, size(recv, 2)
      k = find_store(part, recv(1, i))
      if (k == 0) then
        answer(:, i) = [recv(1, i), 0_i8, 0_i8, 0_i8, 0_i8, 0_i8, 0_i8]
      else
        answer(:, i) = [recv(1, i), 1_i8, part%store(6, k), part%store(3:5, k), part%store(2, k)]
      end if
    end do
    deallocate(recv)
    call par_route_free(answer, source, ans)
    deallocate(source)
    if (any(ans(1, :) /= ids)) error stop 'range_add_gmsh: answers out of order'

    ! Hexahedra: every node tag in $Nodes (zone order is rank order).
    nbad = 0
    do i = 1, nz
      do c = 1, 8
        k = sorted_find(ids, range%conn(c, lo + i - 1))
        if (ans(2, k) /= 0) cycle
        nbad = nbad + 1
        if (nbad <= MAX_REPORT) lines(nbad) = prefix//'hexahedron '//i8toa(part%hex_tag(lo + &
            i - 1))//' refers to node '//i8toa(ans(1, k))//', which is not in $Nodes'
      end do
    end do
    call merge_capped(status, prefix, lines, nbad, 'unknown node tags in hexahedra')
    if (par_max(nbad) > 0) return
    ! Used nodes with finite coordinates (in the order of $Nodes).
    do i = 1, part%nstore
      if (part%store(6, i) == 0) cycle
      if (all(ieee_is_finite([(transfer(part%store(2 + j, i), 1.0_rk), j = 1, 3)]))) cycle
      call keyed%add(part%store(2, i), prefix//'node '//i8toa(part%store(1, i))// &
          ' has a coordinate that is not a finite number')
    end do
    call keyed%merge(status, prefix, 'nodes with non-finite coordinates')
    if (par_max(keyed%n) > 0) return
    do i = 1, nz
      do c = 1, 8
        k = sorted_find(ids, range%conn(c, lo + i - 1))
        range%conn(c, lo + i - 1) = node0 + ans(3, k)
        do j = 1, 3
          range%corner_x(j, c, lo + i - 1) = transfer(ans(3 + j, k), 1.0_rk)
        end do
      end do
      range%zone_block(lo + i - 1) = int(find_sorted(part%block_tags, &
          int(range%zone_block(lo + i - 1))), ik)
    end do

    ! The same hexahedron twice: [sorted node key (4), zone, tag] to the owner
    ! of the smallest node's block of ids (key order is rank order).
    allocate(send(6, nz), dest(nz))
    do i = 1, nz
      send(1:4, i) = sorted_key(int(range%conn(:, lo + i - 1) - node0))
      send(5:6, i) = [zfirst + i - 1, part%hex_tag(lo + i - 1)]
      dest(i) = par_block_owner(part%nnode, par_size(), send(1, i) / SHIFT)
    end do
    call par_route_free(send, dest, recv)
    deallocate(dest)
    call sort_order(recv(1:5, :), order)
    nbad = 0
    do i = 2, size(order)
      if (any(recv(1:4, order(i)) /= recv(1:4, order(i - 1)))) cycle
      nbad = nbad + 1
      if (nbad <= MAX_REPORT) lines(nbad) = prefix//'hexahedra '//i8toa(recv(6, order(i - 1)))// &
          ' and '//i8toa(recv(6, order(i)))//' have the same nodes (is a volume in '// &
          'several 3D physical groups?)'
    end do
    deallocate(recv, order)
    call merge_capped(status, prefix, lines, nbad, 'repeated hexahedra')

    ! Orientation: Gmsh and impact3d share the node order.
    allocate(vol(nz))
    nbad = 0
    do i = 1, nz
      vol(i) = hex_volume(range%corner_x(:, :, lo + i - 1))
      if (vol(i) <= 0.0_rk) then
        write(text, '(es12.4)') vol(i)
        nbad = nbad + 1
        if (nbad <= MAX_REPORT) lines(nbad) = prefix//'hexahedron '//i8toa(part%hex_tag(lo + &
            i - 1))//' has volume '//trim(adjustl(text))//' <= 0: its nodes are inverted or '// &
            'degenerate (impact3d does not reorder them)'
      end if
    end do
    call merge_capped(status, prefix, lines, nbad, 'hexahedra with volume <= 0')

    ! Quadrilaterals: node tags in $Nodes (quadrilateral order is rank
    ! order), then [key (2), index, set and tag, ids packed (2)] to the owner
    ! of their smallest node's block of ids.
    nbad = 0
    keyed = keyed_report_t()
    allocate(send(6, part%nq), dest(part%nq))
    m = 0
    do i = 1, part%nq
      unknown = .false.
      do c = 1, 4
        k = sorted_find(ids, part%quads(3 + c, i))
        nid(c) = int(ans(3, k))
        if (ans(2, k) == 0) then
          unknown = .true.
          nbad = nbad + 1
          if (nbad <= MAX_REPORT) lines(nbad) = prefix//'quadrilateral '// &
              i8toa(part%quads(2, i))//' refers to node '//i8toa(part%quads(3 + c, i))// &
              ', which is not in $Nodes'
        end if
      end do
      if (unknown) cycle
      if (any(nid == 0)) then
        call keyed%add(part%quads(1, i), prefix//'quadrilateral '//i8toa(part%quads(2, i))// &
            ' of face set '''//trim(part%set_names(find_sorted(part%set_tags, &
            int(part%quads(3, i)))))//''' matches no hexahedron face')
        cycle
      end if
      m = m + 1
      send(1:2, m) = sorted_key(nid)
      send(3:6, m) = [part%quads(1, i), int(find_sorted(part%set_tags, int(part%quads(3, i))), &
          i8) * SHIFT + part%quads(2, i), int(nid(1), i8) * SHIFT + nid(2), &
          int(nid(3), i8) * SHIFT + nid(4)]
      dest(m) = par_block_owner(part%nnode, par_size(), send(1, m) / SHIFT)
    end do
    call merge_capped(status, prefix, lines, nbad, 'unknown node tags in quadrilaterals')
    send = send(:, :m)
    call par_route_free(send, dest(:m), quads)
    deallocate(dest, ids, ans)
    ! Each quadrilateral's face: the first (smallest 6 (zone - 1) + face)
    ! with its nodes, or the first of those whose orientation agrees, as
    ! build_sets takes it. The hexahedra's faces [key (2), 6 (zone - 1) +
    ! face, ids packed (2)] go to the same owners one face direction at a
    ! time (six rounds of nz records), each quadrilateral keeping its best
    ! so far: best2(1) the first face, best2(2) the first that agrees.
    allocate(best2(2, size(quads, 2)))
    best2 = huge(1_i8)
    do f = 1, 6
      allocate(faces(5, nz), dest(nz))
      do i = 1, nz
        nid = int(range%conn(HEX_FACE_NODES(:, f), lo + i - 1) - node0)
        faces(1:2, i) = sorted_key(nid)
        faces(3:5, i) = [6 * (zfirst - zone0 + i - 2) + f, int(nid(1), i8) * SHIFT + nid(2), &
            int(nid(3), i8) * SHIFT + nid(4)]
        dest(i) = par_block_owner(part%nnode, par_size(), faces(1, i) / SHIFT)
      end do
      call par_route_free(faces, dest, recv)
      deallocate(dest)
      call sort_order(recv(1:3, :), order)
      do i = 1, size(quads, 2)
        fk = quads(1:2, i)
        kk = [quads(5, i) / SHIFT, modulo(quads(5, i), SHIFT), quads(6, i) / SHIFT, &
            modulo(quads(6, i), SHIFT)]
        j = face_lower_bound(recv, order, fk)
        do while (j <= size(order))
          cand = order(j)
          if (any(recv(1:2, cand) /= fk)) exit
          best2(1, i) = min(best2(1, i), recv(3, cand))
          if (same_cycle([int(recv(4, cand) / SHIFT), int(modulo(recv(4, cand), SHIFT)), &
              int(recv(5, cand) / SHIFT), int(modulo(recv(5, cand), SHIFT))], int(kk))) then
            best2(2, i) = min(best2(2, i), recv(3, cand))
            exit
          end if
          j = j + 1
        end do
      end do
      deallocate(recv, order)
    end do
    ! [global zone, 6 (zone - 1) + face, set] to the zone's rank.
    allocate(send(3, size(quads, 2)), dest(size(quads, 2)))
    m = 0
    do i = 1, size(quads, 2)
      if (best2(1, i) == huge(1_i8)) then
        s = int(quads(4, i) / SHIFT)
        call keyed%add(quads(3, i), prefix//'quadrilateral '//i8toa(modulo(quads(4, i), SHIFT))// &
            ' of face set '''//trim(part%set_names(s))//''' matches no hexahedron face')
        cycle
      end if
      m = m + 1
      if (best2(2, i) < huge(1_i8)) best2(1, i) = best2(2, i)
      g = zone0 + (best2(1, i) - 1) / 6 + 1
      send(:, m) = [g, best2(1, i), quads(4, i) / SHIFT]
      dest(m) = par_block_owner(range%nzone_global, par_size(), g)
    end do
    deallocate(quads, best2)
    call keyed%merge(status, prefix, 'quadrilaterals matching no hexahedron face')
    send = send(:, :m)
    call par_route_free(send, dest(:m), entries)
    deallocate(dest)

    ! Face sets: sorted by (set, zone and face), repeats dropped; each set's
    ! places follow the ranks.
    call sort_order(entries([3, 2], :), order)
    entries = entries(:, order)
    deallocate(order)
    allocate(cnt(nset), off(nset))
    cnt = 0
    n = 0
    do i = 1, size(entries, 2)
      if (i > 1) then
        if (all(entries(2:3, i) == entries(2:3, i - 1))) cycle
      end if
      n = n + 1
      entries(:, n) = entries(:, i)
      cnt(entries(3, n)) = cnt(entries(3, n)) + 1
    end do
    do s = 1, nset
      off(s) = par_exscan_i8(cnt(s))
      part%set_count(s) = par_sum(cnt(s))
    end do
    call range_grow_faces(range, 2 * n)
    pos = range%nface
    allocate(key(n), value(4, n))
    cnt = 0
    do i = 1, n
      s = int(entries(3, i))
      cnt(s) = cnt(s) + 1
      k = int(entries(1, i) - range%first) + 1
      f = int(entries(2, i) - 6 * ((entries(2, i) - 1) / 6))
      do c = 1, 2
        if (sets(c, s) == 0) cycle
        pos = pos + 1
        range%face_set(pos) = sets(c, s)
        range%face_zone(pos) = k
        range%face_face(pos) = f
        range%face_ord(pos) = ord0(c, s) + off(s) + cnt(s)
      end do
      do j = 1, 4
        p(:, j) = range%corner_x(:, HEX_FACE_NODES(j, f), k)
      end do
      a = norm2(quad_vector_area(p))
      key(i) = off(s) + cnt(s)
      value(:, i) = [a, a * 0.25_rk * sum(p, dim=2)]
    end do
    range%nface = pos

    ! The summary, its sums in a single reader's order.
    allocate(volume(size(part%block_tags)))
    do c = 1, size(part%block_tags)
      call par_ordered_sum(pack([(zfirst - zone0 + i - 1, i = 1, nz)], &
          range%zone_block(lo:lo + nz - 1) == c), reshape(pack(vol, &
          range%zone_block(lo:lo + nz - 1) == c), [1, count(range%zone_block(lo:lo + nz - 1) &
          == c)]), total(1:1))
      volume(c) = total(1)
    end do
    deallocate(summary)
    allocate(summary(2 + size(part%block_tags) + nset))
    summary(1) = title
    write(summary(2), '(a,i0,a,i0,a,es24.16)') '  ', part%nnode, ' nodes, ', part%nhex, &
        ' zones, volume ', sum(volume)
    n = 2
    do c = 1, size(part%block_tags)
      n = n + 1
      write(summary(n), '(3a,i0,a,es24.16)') '  block ''', trim(part%block_names(c)), &
          ''': ', par_sum(int(count(range%zone_block(lo:lo + nz - 1) == c), i8)), &
          ' zones, volume ', volume(c)
    end do
    do s = 1, nset
      call par_ordered_sum(pack(key, entries(3, :size(key)) == s), reshape(pack(value, &
          spread(entries(3, :size(key)) == s, 1, 4)), [4, count(entries(3, :size(key)) == s)]), &
          total)
      if (total(1) > 0.0_rk) total(2:4) = total(2:4) / total(1)
      n = n + 1
      write(summary(n), '(3a,i0,a,es24.16,a,3es24.16)') '  face set ''', &
          trim(part%set_names(s)), ''': ', part%set_count(s), ' faces, area ', total(1), &
          ', centre', total(2:4)
    end do
    deallocate(part%hex_tag, part%quads, part%store)
  end subroutine range_add_gmsh

  !> First position in order of the faces (sorted by order) whose key is >= fk.
  pure integer function face_lower_bound(faces, order, fk) result(lo)
    integer(i8), intent(in) :: faces(:, :), fk(2)
    integer, intent(in) :: order(:)
    integer :: hi, mid
    lo = 1
    hi = size(order) + 1
    do while (lo < hi)
      mid = (lo + hi) / 2
      if (faces(1, order(mid)) < fk(1) .or. (faces(1, order(mid)) == fk(1) .and. &
          faces(2, order(mid)) < fk(2))) then
        lo = mid + 1
      else
        hi = mid
      end if
    end do
  end function face_lower_bound

end module mesh_gmsh
