!> Parser of Gmsh ASCII meshes, format 2.2 and 4.1, shared by the two
!> readers: the whole-file one (mesh_gmsh, kept for tests that compare with
!> the whole mesh) and the streamed one of the runs (mesh_gmsh_stream, rank
!> 0 streaming the file to the ranks in chunks).
!>
!> The parser checks the syntax and the counts and keeps the file's header
!> data (format version, physical names, entities: gmsh_header_t); each
!> node, hexahedron and quadrilateral in a physical group goes to a sink
!> (an extension of gmsh_sink_t, whose deferred procedures the readers
!> implement): the whole-file reader keeps them, the streamed reader sends
!> them on. The group naming and the checks on the groups that both
!> readers make are here too.
module mesh_gmsh_parse
  use core_kinds, only: rk, i8
  use core_status, only: status_t
  use core_sort, only: sort_order, sort_values
  use core_text, only: itoa => to_text, i8toa => to_text
  use mesh_global, only: NAME_LEN
  implicit none
  private
  public :: gmsh_parse, gmsh_groups, group_tags, sorted_key, same_cycle, lower_bound, &
      find_sorted

  integer, parameter, public :: TYPE_QUAD = 3 !< Gmsh 4-node quadrilateral
  integer, parameter, public :: TYPE_HEX = 5 !< Gmsh 8-node hexahedron
  integer, parameter, public :: VERSION_22 = 22, VERSION_41 = 41
  !> Per-element problems of one kind reported one by one before a summary line.
  integer, parameter, public :: MAX_REPORT = 10
  !> Packs two non-negative 32-bit integers into one 64-bit sort key.
  integer(i8), parameter, public :: SHIFT = 4294967296_i8
  !> Bytes of the file read at a time.
  integer, parameter :: BLOCK_LEN = 65536

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

  !> What the parser keeps of the file itself (the elements go to the sink).
  type, public :: gmsh_header_t
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
    logical :: has_elements = .false.
    integer :: nbad = 0 !< other elements in 2D or 3D physical groups
  end type gmsh_header_t

  !> Where the parser puts the nodes and elements, in the order of the file.
  type, abstract, public :: gmsh_sink_t
    logical :: skip_nodes = .false. !< $Nodes is skipped (a second pass)
    logical :: nodes_first = .false. !< $Elements must come after $Nodes
  contains
    !> $Nodes starts: n nodes, tags from lo (4.1: the header's smallest tag; 2.2: 1).
    procedure(sink_nodes_begin), deferred :: nodes_begin
    !> One node of $Nodes.
    procedure(sink_node), deferred :: node
    !> The end of $Nodes.
    procedure(sink_nodes_done), deferred :: nodes_done
    !> One hexahedron (phys: its 3D physical tag, 0 if none).
    procedure(sink_hex), deferred :: hex
    !> One quadrilateral of the 2D physical group phys (one call per group).
    procedure(sink_quad), deferred :: quad
    !> Room for more elements (a hint: an entity block's count, 4.1).
    procedure :: reserve => sink_reserve
  end type gmsh_sink_t

  abstract interface
    subroutine sink_nodes_begin(data, lo, n, ok)
      import :: gmsh_sink_t, i8
      class(gmsh_sink_t), intent(inout) :: data
      integer(i8), intent(in) :: lo
      integer, intent(in) :: n
      logical, intent(out) :: ok !< false: no room for n nodes
    end subroutine sink_nodes_begin
    subroutine sink_node(data, tag, xyz)
      import :: gmsh_sink_t, i8, rk
      class(gmsh_sink_t), intent(inout) :: data
      integer(i8), intent(in) :: tag
      real(rk), intent(in) :: xyz(3)
    end subroutine sink_node
    subroutine sink_nodes_done(data)
      import :: gmsh_sink_t
      class(gmsh_sink_t), intent(inout) :: data
    end subroutine sink_nodes_done
    subroutine sink_hex(data, tag, nodes, phys)
      import :: gmsh_sink_t, i8
      class(gmsh_sink_t), intent(inout) :: data
      integer(i8), intent(in) :: tag, nodes(8)
      integer, intent(in) :: phys
    end subroutine sink_hex
    subroutine sink_quad(data, tag, nodes, phys)
      import :: gmsh_sink_t, i8
      class(gmsh_sink_t), intent(inout) :: data
      integer(i8), intent(in) :: tag, nodes(4)
      integer, intent(in) :: phys
    end subroutine sink_quad
  end interface

contains

  !> Parse the file at path: its header into data, its nodes and elements
  !> into sink. Problems go to status with prefix ("mesh file '<path>': ");
  !> parsed: the file was opened and read to its end without a fatal
  !> problem of syntax or counts.
  subroutine gmsh_parse(path, prefix, data, sink, status, parsed)
    character(len=*), intent(in) :: path, prefix
    type(gmsh_header_t), intent(inout) :: data
    class(gmsh_sink_t), intent(inout) :: sink
    type(status_t), intent(inout) :: status
    logical, intent(out) :: parsed
    type(reader_t) :: r
    character(len=256) :: msg
    logical :: exists
    integer :: ios

    parsed = .false.
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
    call parse_file(r, data, sink, prefix, status)
    close(r%unit)
    if (r%failed) then
      call status%add(prefix//r%message)
    else
      parsed = .true.
    end if
  end subroutine gmsh_parse

  !> The blocks and face sets, as both readers make them: the sorted
  !> distinct tags of the 3D and 2D physical groups (named ones and those
  !> used: hex_groups and quad_groups, 0 = none), their names, and the
  !> checks on them; nhex = 0 is an error (a hexahedral mesh is needed).
  subroutine gmsh_groups(data, prefix, nhex, hex_groups, quad_groups, block_tags, set_tags, &
      block_names, set_names, status)
    type(gmsh_header_t), intent(in) :: data
    character(len=*), intent(in) :: prefix
    integer(i8), intent(in) :: nhex
    integer, intent(in) :: hex_groups(:), quad_groups(:)
    integer, allocatable, intent(out) :: block_tags(:), set_tags(:)
    character(len=NAME_LEN), allocatable, intent(inout) :: block_names(:), set_names(:)
    type(status_t), intent(inout) :: status

    if (nhex == 0) then
      call status%add(prefix//'no 8-node hexahedra (Gmsh type 5) found; impact3d needs '// &
          'a hexahedral mesh (Recombine with Transfinite, or Extrude with Layers)')
      allocate(block_tags(0), set_tags(0))
      return
    end if
    call group_tags(data, 3, hex_groups, block_tags)
    call group_tags(data, 2, quad_groups, set_tags)
    if (data%version == VERSION_41 .and. .not. data%has_names .and. &
        size(block_tags) + size(set_tags) > 0) then
      call status%add(prefix//'physical groups are used but the file has no '// &
          '$PhysicalNames section: name every 2D and 3D physical group '// &
          '(e.g. Physical Volume("steel") = {...};)')
    end if
    call group_names(data, prefix, 3, block_tags, block_names, status)
    call group_names(data, prefix, 2, set_tags, set_names, status)
  end subroutine gmsh_groups

  !> The default reserve: no room to make.
  subroutine sink_reserve(data, nhex, nquad)
    class(gmsh_sink_t), intent(inout) :: data
    integer, intent(in) :: nhex, nquad !< more hexahedra and quadrilaterals to come
  end subroutine sink_reserve

  ! Parsing
  ! ---------------------------------------------------------------------------

  !> Read the sections of the file into data and sink; unknown sections are skipped.
  subroutine parse_file(r, data, sink, prefix, status)
    type(reader_t), intent(inout) :: r
    type(gmsh_header_t), intent(inout) :: data
    class(gmsh_sink_t), intent(inout) :: sink
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
        else if (sink%skip_nodes) then
          call reader_skip_section(r, 'Nodes')
          data%has_nodes = .true.
        else if (data%version == VERSION_22) then
          call parse_nodes_22(r, data, sink)
        else
          call parse_nodes_41(r, data, sink)
        end if
      case ('$Elements')
        if (data%has_elements) then
          call reader_fail(r, 'a second $Elements section')
        else if (sink%nodes_first .and. .not. data%has_nodes) then
          call reader_fail(r, 'the $Elements section comes before $Nodes (a file read in '// &
              'chunks needs the nodes first, as Gmsh writes them)')
        else if (data%version == VERSION_22) then
          call parse_elements_22(r, data, sink, prefix, status)
        else
          call parse_elements_41(r, data, sink, prefix, status)
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
    type(gmsh_header_t), intent(inout) :: data
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
    type(gmsh_header_t), intent(inout) :: data
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
    type(gmsh_header_t), intent(inout) :: data
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
  subroutine parse_nodes_22(r, data, sink)
    type(reader_t), intent(inout) :: r
    type(gmsh_header_t), intent(inout) :: data
    class(gmsh_sink_t), intent(inout) :: sink
    integer :: n, i, k
    integer(i8) :: tag
    real(rk) :: xyz(3)
    logical :: ok

    call read_count(r, 'the number of nodes', n)
    if (r%failed) return
    call reader_end_line(r)
    call sink%nodes_begin(1_i8, n, ok)
    if (.not. ok) then
      call reader_fail(r, 'bad counts: cannot allocate '//itoa(n)//' nodes')
      return
    end if
    do i = 1, n
      call read_i8(r, 'a node tag', tag)
      do k = 1, 3
        call read_real(r, 'a node coordinate', xyz(k))
      end do
      if (r%failed) return
      call sink%node(tag, xyz)
      call reader_end_line(r)
    end do
    call sink%nodes_done()
    data%has_nodes = .true.
    call reader_expect(r, '$EndNodes')
  end subroutine parse_nodes_22

  !> $Nodes in format 4.1: entity blocks of tags followed by coordinates.
  !> The tags of a block are kept until its coordinates are read (8 bytes a
  !> node of the largest block), each node then given to the sink.
  subroutine parse_nodes_41(r, data, sink)
    type(reader_t), intent(inout) :: r
    type(gmsh_header_t), intent(inout) :: data
    class(gmsh_sink_t), intent(inout) :: sink
    integer :: nblock, n, b, i, k, dim, tag, parametric, count, first
    integer(i8) :: min_tag, max_tag
    integer(i8), allocatable :: tags(:)
    real(rk) :: xyz(3)
    logical :: ok

    call read_count(r, 'the number of node blocks', nblock)
    call read_count(r, 'the number of nodes', n)
    call read_i8(r, 'the smallest node tag', min_tag)
    call read_i8(r, 'the largest node tag', max_tag)
    if (r%failed) return
    call reader_end_line(r)
    call sink%nodes_begin(min_tag, n, ok)
    if (.not. ok) then
      call reader_fail(r, 'bad counts: cannot allocate '//itoa(n)//' nodes')
      return
    end if
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
        ! Parametric coordinates, if any, follow on the same line.
        call reader_end_line(r)
        if (r%failed) return
        call sink%node(tags(i), xyz)
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
    call sink%nodes_done()
    call reader_expect(r, '$EndNodes')
  end subroutine parse_nodes_41

  !> $Elements in format 2.2: "tag type ntags tags... nodes..." lines.
  subroutine parse_elements_22(r, data, sink, prefix, status)
    type(reader_t), intent(inout) :: r
    type(gmsh_header_t), intent(inout) :: data
    class(gmsh_sink_t), intent(inout) :: sink
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
        call sink%hex(tag, nodes, phys)
      case (TYPE_QUAD)
        do k = 1, 4
          call read_i8(r, 'a node tag', nodes(k))
        end do
        if (r%failed) return
        if (phys /= 0) call sink%quad(tag, nodes(1:4), phys)
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
  subroutine parse_elements_41(r, data, sink, prefix, status)
    type(reader_t), intent(inout) :: r
    type(gmsh_header_t), intent(inout) :: data
    class(gmsh_sink_t), intent(inout) :: sink
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
      if (element_type == TYPE_HEX) call sink%reserve(count, 0)
      if (element_type == TYPE_QUAD) call sink%reserve(0, count * (last_phys - first_phys + 1))
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
          call sink%hex(tag, nodes, phys)
        else if (element_type == TYPE_QUAD) then
          do k = 1, 4
            call read_i8(r, 'a node tag', nodes(k))
          end do
          if (r%failed) return
          do p = first_phys, last_phys
            call sink%quad(tag, nodes(1:4), data%entity_phys(p))
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
    type(gmsh_header_t), intent(in) :: data
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
    type(gmsh_header_t), intent(inout) :: data
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
    type(gmsh_header_t), intent(in) :: data
    character(len=*), intent(in) :: prefix
    type(status_t), intent(inout) :: status
    if (data%nbad > MAX_REPORT) then
      call status%add(prefix//itoa(data%nbad - MAX_REPORT)//' more elements of the wrong'// &
          ' type in 2D or 3D physical groups')
    end if
  end subroutine report_bad_summary

  !> 'name' (tag N) of a physical group if it is named, else "tag N".
  function group_label(data, dim, tag) result(label)
    type(gmsh_header_t), intent(in) :: data
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

  !> Sorted distinct physical tags of dimension dim: named ones and those used.
  subroutine group_tags(data, dim, used, tags)
    type(gmsh_header_t), intent(in) :: data
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
    type(gmsh_header_t), intent(in) :: data
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

end module mesh_gmsh_parse
